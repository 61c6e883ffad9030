// Broken OpenDRIVE maps through `corsa validate`, `corsa map info` and `corsa map mesh`: every
// case ends with exit 0 (still valid) or exit 2 and a located error, within the time limit, and a
// rejected mesh leaves no file behind.

#include <string>
#include <vector>

#include "bounded_run.h"
#include "mutations.h"

namespace corsa::test {
namespace {

std::string shared_map(const std::string& name) {
  return slurp(std::filesystem::path(CORSA_SHARED_DIR) / "data" / "xodr" / name);
}

/// Writes `text` as map.xodr in `dir`, runs `corsa map mesh` on it into dir/out.obj and checks
/// the outcome; a rejected map must leave only map.xodr in the folder.
void check_mesh_case(const std::string& name, const std::string& text) {
  TempDir dir;
  const auto map = dir.path() / "map.xodr";
  std::ofstream(map, std::ios::binary) << text;
  const BoundedResult result =
      run_bounded({"map", "mesh", map.string(), "-o", (dir.path() / "out.obj").string()});
  check_rejected_or_ok(name, result, true);
  if (result.exit_code != 0) {
    INFO(describe(name, result));
    CHECK(entry_names(dir.path()) == std::set<std::string>{"map.xodr"});
  }
}

void check_info_case(const std::string& name, const std::string& text, bool may_succeed) {
  TempDir dir;
  const auto map = dir.path() / "map.xodr";
  std::ofstream(map, std::ios::binary) << text;
  check_rejected_or_ok(name, run_bounded({"map", "info", map.string()}), may_succeed);
}

TEST_CASE("Truncated OpenDRIVE maps are rejected with a located error and no mesh file",
          "[robustness][xodr]") {
  for (const char* file : {"straight_500m.xodr", "Ex_Line-Spiral-Arc.xodr", "fabriksgatan.xodr"}) {
    for (const Mutant& mutant :
         truncations(shared_map(file), {0.0, 0.002, 0.05, 0.31, 0.5, 0.77, 0.995})) {
      check_mesh_case(std::string(file) + " " + mutant.name, mutant.text);
    }
  }
}

TEST_CASE("OpenDRIVE maps with random bytes overwritten never crash, hang or half-write",
          "[robustness][xodr]") {
  uint32_t seed = 1;
  for (const char* file : {"straight_500m.xodr", "Ex_Line-Spiral-Arc.xodr", "fabriksgatan.xodr"}) {
    for (const Mutant& mutant : byte_flips(shared_map(file), seed++, 12)) {
      check_mesh_case(std::string(file) + " " + mutant.name, mutant.text);
    }
  }
}

TEST_CASE("NaN, infinite, text, negative and huge numbers in OpenDRIVE attributes are handled",
          "[robustness][xodr]") {
  struct Target {
    const char* file;
    const char* element;
    const char* attribute;
  };
  const Target targets[] = {
      {"straight_500m.xodr", "road", "length"},
      {"straight_500m.xodr", "geometry", "length"},
      {"straight_500m.xodr", "geometry", "x"},
      {"straight_500m.xodr", "geometry", "hdg"},
      {"straight_500m.xodr", "width", "a"},
      {"straight_500m.xodr", "width", "d"},
      {"straight_500m.xodr", "laneSection", "s"},
      {"straight_500m.xodr", "lane", "id"},
      {"straight_500m.xodr", "elevation", "b"},
      {"Ex_Line-Spiral-Arc.xodr", "spiral", "curvStart"},
      {"Ex_Line-Spiral-Arc.xodr", "arc", "curvature"},
  };
  for (const Target& target : targets) {
    const std::string original = shared_map(target.file);
    for (const std::string& value : bad_numbers()) {
      const std::string text = with_attribute(original, target.element, target.attribute, value);
      REQUIRE_FALSE(text.empty());
      check_info_case(std::string(target.file) + " <" + target.element + " " + target.attribute +
                          "=\"" + value + "\">",
                      text, true);
    }
  }
}

TEST_CASE("OpenDRIVE elements without a required attribute are rejected at their line",
          "[robustness][xodr]") {
  struct Target {
    const char* element;
    const char* attribute;
  };
  const Target targets[] = {{"road", "id"},       {"road", "length"},  {"geometry", "s"},
                            {"geometry", "x"},    {"geometry", "hdg"}, {"geometry", "length"},
                            {"laneSection", "s"}, {"lane", "id"},      {"width", "a"},
                            {"width", "sOffset"}};
  const std::string original = shared_map("straight_500m.xodr");
  for (const Target& target : targets) {
    const std::string text = without_attribute(original, target.element, target.attribute);
    REQUIRE_FALSE(text.empty());
    check_info_case(std::string("<") + target.element + "> without " + target.attribute, text,
                    false);
  }
}

TEST_CASE("Hand-made OpenDRIVE files of the corpus load, or are rejected at their line",
          "[robustness][xodr]") {
  // corpus/bad_*.xodr must be rejected (exit 2, located in that file); corpus/ok_*.xodr are valid
  // maps that once crashed or hung Corsa and must now load (exit 0) in time. Each file's comment
  // says what it checks.
  const auto corpus = std::filesystem::path(CORSA_SOURCE_DIR) / "tests/robustness/corpus";
  size_t bad = 0;
  size_t ok = 0;
  for (const auto& entry : std::filesystem::directory_iterator(corpus)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".xodr") {
      continue;
    }
    const bool must_fail = name.starts_with("bad_");
    REQUIRE((must_fail || name.starts_with("ok_")));
    ++(must_fail ? bad : ok);
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"validate", entry.path().string()},
          std::vector<std::string>{"map", "info", entry.path().string()}}) {
      const BoundedResult result = run_bounded(args);
      INFO(describe(args[0] + " " + name, result));
      CHECK_FALSE(result.timed_out);
      if (must_fail) {
        CHECK(result.exit_code == 2);
        CHECK(has_located_error(result.err));
        CHECK(result.err.find(name + ":") != std::string::npos);
      } else {
        CHECK(result.exit_code == 0);
      }
    }
  }
  CHECK(bad >= 10);
  CHECK(ok >= 2);
}

}  // namespace
}  // namespace corsa::test
