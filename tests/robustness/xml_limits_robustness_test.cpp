// XML that is well-formed-looking but absurd in size: elements nested millions deep and names or
// values megabytes long. Both XML readers (Corsa's own for OpenDRIVE, tinyxml2 for OpenSCENARIO,
// suites and rigs) must stop at a nesting limit with a located error that says so, quickly and
// without hundreds of megabytes, and a message must quote at most a clipped piece of a name.

#include <string>
#include <vector>

#include "bounded_run.h"
#include "corsa/core/strings.h"

namespace corsa::test {
namespace {

/// `depth` nested <e> elements inside `root`, properly closed.
std::string nested(const std::string& root, size_t depth) {
  std::string text = "<?xml version=\"1.0\"?>\n<" + root + ">\n";
  text.reserve(depth * 7 + 64);
  for (size_t i = 0; i < depth; ++i) text += "<e>";
  for (size_t i = 0; i < depth; ++i) text += "</e>";
  return text + "\n</" + root + ">\n";
}

BoundedResult run_on(const TempDir& dir, const std::string& name, const std::string& text,
                     std::vector<std::string> args) {
  const auto file = dir.path() / name;
  std::ofstream(file, std::ios::binary) << text;
  for (auto& arg : args) {
    if (arg == "@") arg = file.string();
  }
  return run_bounded(args, 15);
}

TEST_CASE("OpenDRIVE nested 2 million deep stops at the depth limit, at its line",
          "[robustness][xodr][xml]") {
  for (const size_t depth : {300UL, 2000000UL}) {
    TempDir dir;
    const BoundedResult result =
        run_on(dir, "deep.xodr", nested("OpenDRIVE", depth), {"map", "info", "@"});
    INFO(describe("depth " + std::to_string(depth), result));
    CHECK_FALSE(result.timed_out);
    CHECK(result.cpu_seconds < 5.0);  // CPU time: wall time depends on the load
    CHECK(result.exit_code == 2);
    // <OpenDRIVE> on line 2 and all the <e> on line 3.
    CHECK(result.err.find("deep.xodr:3: error: malformed XML: <e> is nested deeper than 256 "
                          "levels") != std::string::npos);
  }
  // 255 levels of unknown elements inside the root are still read (and then found not a map).
  TempDir dir;
  const BoundedResult shallow =
      run_on(dir, "ok.xodr", nested("OpenDRIVE", 255), {"map", "info", "@"});
  CHECK(shallow.err.find("nested deeper") == std::string::npos);
}

TEST_CASE("Megabyte names and values in OpenDRIVE are quoted clipped in messages",
          "[robustness][xodr][xml]") {
  const std::string huge(5000000, 'n');
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"element name", "<OpenDRIVE><" + huge + " a=\"1\" a=\"2\"/></OpenDRIVE>"},
      {"end tag", "<OpenDRIVE><road></" + huge + "></OpenDRIVE>"},
      {"attribute name", "<OpenDRIVE><header " + huge + "/></OpenDRIVE>"},
      {"integer", "<OpenDRIVE><header revMajor=\"" + huge + "\" revMinor=\"8\"/></OpenDRIVE>"},
      {"unknown entity", "<OpenDRIVE a=\"&" + huge + ";\"/>"},
  };
  for (const auto& [what, text] : cases) {
    TempDir dir;
    const BoundedResult result = run_on(dir, "big.xodr", text, {"map", "info", "@"});
    INFO(describe(what, result));
    CHECK(result.exit_code == 2);
    CHECK(has_located_error(result.err));
    CHECK(result.err.size() < 2000);
    CHECK(result.err.find(std::string(corsa::kClipBytes, 'n') + "...") != std::string::npos);
  }
}

TEST_CASE("OpenSCENARIO, suites and rigs nested too deeply are located errors that say so",
          "[robustness][xml]") {
  const std::string suite_dir = std::string(CORSA_SOURCE_DIR) + "/scenarios";
  struct Case {
    const char* what;
    const char* file;
    const char* root;
    std::vector<std::string> args;
  };
  const std::vector<Case> cases = {
      {"scenario", "deep.xosc", "OpenSCENARIO", {"validate", "@"}},
      {"scenario run", "deep.xosc", "OpenSCENARIO", {"run", "@", "--quiet"}},
      {"suite", "suite.xml", "Suite", {"test", "@", "--quiet"}},
      {"rig",
       "rig.xml",
       "SensorRig",
       {"run", suite_dir + "/cut_in.xosc", "--rig", "@", "-o", "", "--quiet"}},
  };
  for (const Case& c : cases) {
    for (const size_t depth : {1000UL, 2000000UL}) {
      TempDir dir;
      std::vector<std::string> args = c.args;
      for (auto& arg : args) {
        if (arg.empty()) arg = (dir.path() / "dataset").string();
      }
      const BoundedResult result = run_on(dir, c.file, nested(c.root, depth), args);
      INFO(describe(std::string(c.what) + " depth " + std::to_string(depth), result));
      CHECK_FALSE(result.timed_out);
      CHECK(result.cpu_seconds < 5.0);  // CPU time: wall time depends on the load
      CHECK(result.exit_code == 2);
      CHECK(has_located_error(result.err));
      CHECK(result.err.find(c.file) != std::string::npos);
      CHECK(result.err.find("nested too deeply") != std::string::npos);
      CHECK(entry_names(dir.path()) == std::set<std::string>{c.file});
    }
  }
}

}  // namespace
}  // namespace corsa::test
