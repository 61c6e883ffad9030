// Broken OpenSCENARIO scenarios through `corsa validate` and `corsa run`: exit 0 or 1 (the
// scenario still runs), or exit 2 with a located error and no trajectory or summary file left
// behind; never a crash, an internal error or a hang.

#include <string>
#include <vector>

#include "bounded_run.h"
#include "mutations.h"

namespace corsa::test {
namespace {

/// `text` with the first occurrence of `from` replaced by `to` (which must exist).
std::string edited(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

/// What a broken scenario is allowed to do.
enum class Expect {
  kMayRun,         ///< still a valid scenario, or rejected: either is fine
  kRejected,       ///< validate and run both reject it
  kRejectedByRun,  ///< validate (which places no entity) may pass it; run rejects it
};

struct Outcome {
  BoundedResult validate;
  BoundedResult run;
};

/// Runs `corsa validate` and `corsa run` (3 s simulated, trajectories and summary into the
/// folder) on `text` as scenario.xosc. When `run` rejects it, only scenario.xosc may remain.
Outcome check_scenario(const std::string& name, const std::string& text, Expect expect) {
  TempDir dir;
  const auto scenario = dir.path() / "scenario.xosc";
  std::ofstream(scenario, std::ios::binary) << text;
  Outcome outcome;
  outcome.validate = run_bounded({"validate", scenario.string()});
  check_rejected_or_ok(name + " (validate)", outcome.validate, expect != Expect::kRejected);
  outcome.run = run_bounded({"run", scenario.string(), "--quiet", "--duration", "3", "--record",
                             (dir.path() / "out.csv").string(), "--summary",
                             (dir.path() / "summary.json").string()});
  INFO(describe(name + " (run)", outcome.run));
  CHECK_FALSE(outcome.run.timed_out);
  if (outcome.run.exit_code == 2) {
    CHECK(has_located_error(outcome.run.err));
    CHECK(entry_names(dir.path()) == std::set<std::string>{"scenario.xosc"});
  } else {
    // 0: ran to its end; 1: ran and failed. Either way it produced both outputs.
    CHECK(expect == Expect::kMayRun);
    CHECK((outcome.run.exit_code == 0 || outcome.run.exit_code == 1));
    CHECK(entry_names(dir.path()) ==
          std::set<std::string>{"scenario.xosc", "out.csv", "summary.json"});
  }
  return outcome;
}

TEST_CASE("Truncated scenarios are rejected with a located error and no outputs",
          "[robustness][xosc]") {
  for (const Mutant& mutant :
       truncations(cut_in_text(), {0.0, 0.001, 0.05, 0.2, 0.45, 0.7, 0.9, 0.995})) {
    check_scenario("cut_in.xosc " + mutant.name, mutant.text, Expect::kRejected);
  }
}

TEST_CASE("Scenarios with random bytes overwritten never crash, hang or half-write",
          "[robustness][xosc]") {
  for (const Mutant& mutant : byte_flips(cut_in_text(), 7, 16)) {
    check_scenario("cut_in.xosc " + mutant.name, mutant.text, Expect::kMayRun);
  }
}

TEST_CASE("NaN, infinite, text and huge numbers in scenario attributes are handled",
          "[robustness][xosc]") {
  struct Target {
    const char* element;
    const char* attribute;
  };
  const Target targets[] = {{"ParameterDeclaration", "value"},
                            {"LanePosition", "s"},
                            {"RelativeLanePosition", "ds"},
                            {"SpeedActionDynamics", "value"},
                            {"RelativeDistanceCondition", "value"}};
  const std::string original = cut_in_text();
  for (const Target& target : targets) {
    for (const std::string& value : bad_numbers()) {
      const std::string text = with_attribute(original, target.element, target.attribute, value);
      REQUIRE_FALSE(text.empty());
      check_scenario(
          std::string("<") + target.element + " " + target.attribute + "=\"" + value + "\">", text,
          Expect::kMayRun);
    }
  }
}

TEST_CASE("Scenario elements without a required attribute are rejected at their line",
          "[robustness][xosc]") {
  struct Target {
    const char* element;
    const char* attribute;
  };
  const Target targets[] = {{"ParameterDeclaration", "name"},  {"ScenarioObject", "name"},
                            {"CatalogReference", "entryName"}, {"LanePosition", "roadId"},
                            {"AbsoluteTargetSpeed", "value"},  {"Event", "priority"},
                            {"LogicFile", "filepath"}};
  const std::string original = cut_in_text();
  for (const Target& target : targets) {
    const std::string text = without_attribute(original, target.element, target.attribute);
    REQUIRE_FALSE(text.empty());
    check_scenario(std::string("<") + target.element + "> without " + target.attribute, text,
                   Expect::kRejected);
  }
}

TEST_CASE("Unknown references, cyclic parameters and wrong types are rejected at their line",
          "[robustness][xosc]") {
  struct Case {
    const char* name;
    const char* from;
    const char* to;
    int line;  ///< where the error must point
    Expect expect = Expect::kRejected;
  };
  const Case cases[] = {
      {"self-referencing parameter", "value=\"27.78\"", "value=\"$EgoSpeed\"", 9},
      {"division by zero", "value=\"27.78\"", "value=\"${$CutInGap / 0}\"", 9},
      {"int parameter given text", "parameterType=\"double\" value=\"10\"",
       "parameterType=\"int\" value=\"ten\"", 11},
      {"NaN parameter", "value=\"27.78\"", "value=\"nan\"", 9},
      // tinyxml2 reads no DTD and kept "&x;" as the value.
      {"undeclared entity", "value=\"27.78\"", "value=\"&x;\"", 9},
      // tinyxml2 kept a signed reference as its text, wrote a surrogate as bytes no UTF-8 reader
      // accepts and ended a value at a NUL reference.
      {"signed character reference", "author=\"Corsa\"", "author=\"&#-18446744073709551615;\"", 7},
      {"surrogate character reference", "author=\"Corsa\"", "author=\"&#xD800;\"", 7},
      {"NUL character reference", "author=\"Corsa\"", "author=\"Co&#0;rsa\"", 7},
      // Internal entities with plain values are expanded; a parameter entity is not read (errors
      // at the declaration's line).
      {"DOCTYPE declaring a parameter entity", "<OpenSCENARIO>",
       "<!DOCTYPE OpenSCENARIO [\n<!ENTITY % x \"27.78\">\n]>\n<OpenSCENARIO>", 7},
      {"DOCTYPE entity holding a reference", "<OpenSCENARIO>",
       "<!DOCTYPE OpenSCENARIO [\n<!ENTITY x \"&#38;\">\n]>\n<OpenSCENARIO>", 7},
      {"unknown entity", "<EntityRef entityRef=\"Cutter\"/>", "<EntityRef entityRef=\"Nobody\"/>",
       76},
      {"unknown catalog entry", "entryName=\"sedan\"", "entryName=\"no_such_car\"", 23},
      {"missing map", "motorway_2km.xodr", "no_such_map.xodr", 19},
      {"unknown storyboard element", "storyboardElementRef=\"CutInAction\"",
       "storyboardElementRef=\"NoSuchAction\"", 126},
      // validate checks the roads and lanes positions name against the map.
      {"unknown road", "roadId=\"1\"", "roadId=\"99\"", 36},
      {"unknown lane", "laneId=\"-2\"", "laneId=\"-9\"", 36},
      {"lane id not an integer", "laneId=\"-2\"", "laneId=\"-2.5\"", 36},
      {"position beyond the road network", "ds=\"-40\"", "ds=\"-2e7\"", 55, Expect::kRejectedByRun},
      // Magnitudes beyond physical sense (docs/engine.md): at the element that uses the value.
      {"speed of 1e308 m/s", "value=\"27.78\"", "value=\"1e308\"", 45},
      {"speed of -1e5 m/s", "value=\"27.78\"", "value=\"-1e5\"", 45},
      {"s of 1e20 m", "s=\"100\"", "s=\"1e20\"", 36},
      {"ds of 1e300 m", "ds=\"-40\"", "ds=\"1e300\"", 55},
      {"simulation time of 1e300 s", "<SimulationTimeCondition value=\"60\"",
       "<SimulationTimeCondition value=\"1e300\"", 188},
  };
  const std::string original = cut_in_text();
  for (const Case& c : cases) {
    const Outcome outcome = check_scenario(c.name, edited(original, c.from, c.to), c.expect);
    INFO(c.name << ": " << outcome.run.err);
    CHECK(outcome.run.err.find("scenario.xosc:" + std::to_string(c.line) + ": error: ") !=
          std::string::npos);
    if (c.expect == Expect::kRejected) {
      INFO("validate: " << outcome.validate.err);
      CHECK(outcome.validate.err.find("scenario.xosc:" + std::to_string(c.line) + ": error: ") !=
            std::string::npos);
    }
  }
}

TEST_CASE(
    "Defects whose meaning is clear run with a warning at their line, and --strict refuses them",
    "[robustness][xosc]") {
  struct Case {
    const char* name;
    const char* from;
    const char* to;
    int line;                      ///< where the warning (and under --strict the error) must point
    bool runs_to_end = true;       ///< false: a later element fails because of the reading
    bool seen_by_validate = true;  ///< false: found only when the map is loaded (run)
  };
  const Case cases[] = {
      // The Vehicle catalog directory has one catalog holding the entry asked for.
      {"unknown catalog", "catalogName=\"VehicleCatalog\"", "catalogName=\"NoSuchCatalog\"", 23},
      // A rate's sign is the direction of the change, which the target already gives.
      {"negative transition rate", "value=\"2\" dynamicsDimension=\"rate\"",
       "value=\"-2\" dynamicsDimension=\"rate\"", 114},
      // Read as the road's start; the cut-in's relative position then lies before it.
      {"negative s", "s=\"100\"", "s=\"-5\"", 36, false, false},
  };
  const std::string original = cut_in_text();
  for (const Case& c : cases) {
    const Outcome outcome = check_scenario(c.name, edited(original, c.from, c.to), Expect::kMayRun);
    const std::string at = "scenario.xosc:" + std::to_string(c.line) + ": ";
    INFO(c.name << ": " << outcome.run.err);
    CHECK((outcome.run.exit_code == 0) == c.runs_to_end);
    CHECK(outcome.run.err.find(at + "warning: ") != std::string::npos);

    TempDir dir;
    const auto scenario = dir.path() / "scenario.xosc";
    std::ofstream(scenario, std::ios::binary) << edited(original, c.from, c.to);
    for (const std::string command : {"validate", "run"}) {
      if (command == "validate" && !c.seen_by_validate) continue;
      const BoundedResult strict = run_bounded({command, scenario.string(), "--strict"});
      INFO(describe(c.name + std::string(" (") + command + " --strict)", strict));
      CHECK(strict.exit_code == 2);
      CHECK(strict.err.find(at + "error: ") != std::string::npos);
    }
  }
}

TEST_CASE("Messages quote at most 200 bytes of a value from the file", "[robustness][xosc]") {
  // A 1 MB parameter value was printed whole.
  const std::string value = std::string(1 << 20, '7') + "x";
  const Outcome outcome = check_scenario(
      "1 MB parameter value", edited(cut_in_text(), "value=\"27.78\"", "value=\"" + value + "\""),
      Expect::kRejected);
  CHECK(outcome.run.err.find("scenario.xosc:9: error: parameter 'EgoSpeed': '" +
                             std::string(200, '7') + "...' is not a valid double") !=
        std::string::npos);
  CHECK(outcome.run.err.size() < 1000);
  CHECK(outcome.validate.err.size() < 1000);
}

TEST_CASE("A step too small for a run ever to end is refused", "[robustness][xosc]") {
  TempDir dir;
  for (const char* dt : {"1e-300", "1e-5", "0"}) {
    for (const char* command : {"run", "sweep"}) {
      std::vector<std::string> args = {command, "scenarios/cut_in.xosc", "--quiet", "--dt", dt};
      if (std::string(command) == "sweep") {
        args.insert(args.end(), {"--param", "EgoSpeed=20,30", "-o", (dir.path() / "out").string()});
      } else {
        args.insert(args.end(), {"--record", (dir.path() / "out.csv").string()});
      }
      const BoundedResult result = run_bounded(args);
      INFO(describe(std::string(command) + " --dt " + dt, result));
      CHECK_FALSE(result.timed_out);
      CHECK(result.exit_code == 2);
      CHECK(result.err.find("--dt expects a step in seconds, 0.0001 <= dt <= 10") !=
            std::string::npos);
      CHECK(dir.entries() == 0);
    }
  }
}

}  // namespace
}  // namespace corsa::test

namespace corsa::test {
namespace {

TEST_CASE("A broken file in a catalog folder is a warning unless an entry it may hold is needed",
          "[robustness][xosc]") {
  TempDir dir;
  const auto catalogs = dir.path() / "catalogs";
  std::filesystem::create_directory(catalogs);
  std::filesystem::copy_file(
      std::filesystem::path(CORSA_SOURCE_DIR) / "scenarios/catalogs/vehicles.xosc",
      catalogs / "vehicles.xosc");
  std::ofstream(catalogs / "broken.xosc") << "<OpenSCENARIO>\n<Catalog name=\"X\">\n";
  const std::string scenario =
      edited(cut_in_text(), "path=\"" + std::string(CORSA_SOURCE_DIR) + "/scenarios/catalogs\"",
             "path=\"" + catalogs.string() + "\"");
  const auto broken = (catalogs / "broken.xosc").string();
  // The entries needed are in vehicles.xosc: the scenario runs, with a warning at the broken file.
  std::ofstream(dir.path() / "ok.xosc") << scenario;
  const BoundedResult runs =
      run_bounded({"run", (dir.path() / "ok.xosc").string(), "--quiet", "--duration", "1"});
  INFO(describe("run with a broken catalog file beside the one needed", runs));
  CHECK(runs.exit_code == 0);
  CHECK(runs.err.find(broken + ":2: warning: catalog file skipped: malformed XML") !=
        std::string::npos);
  // An entry found nowhere may be in the broken file: its error, saying what needed it.
  std::ofstream(dir.path() / "missing.xosc")
      << edited(scenario, "entryName=\"sedan\"", "entryName=\"no_such_car\"");
  const BoundedResult missing =
      run_bounded({"run", (dir.path() / "missing.xosc").string(), "--quiet", "--duration", "1"});
  INFO(describe("run needing an entry found nowhere", missing));
  CHECK(missing.exit_code == 2);
  CHECK(missing.err.find(broken + ":2: error: malformed XML") != std::string::npos);
  CHECK(missing.err.find("(this catalog file may hold entry 'no_such_car' of catalog "
                         "'VehicleCatalog', needed at " +
                         (dir.path() / "missing.xosc").string() + ":23)") != std::string::npos);
}

}  // namespace
}  // namespace corsa::test
