// Broken sweep distributions (`corsa sweep`) and suite manifests (`corsa test`): exit 2 with a
// located error before any output folder or report is made; never a crash, "out of memory" or a
// half-written sweep folder.

#include <string>
#include <vector>

#include "bounded_run.h"
#include "mutations.h"

namespace corsa::test {
namespace {

/// The 1,000-variant cut-in grid with its scenario named by absolute path.
std::string grid_text() {
  const std::string suites = std::string(CORSA_SOURCE_DIR) + "/scenarios/suites/";
  std::string text = slurp(suites + "sweeps/cut_in_grid.xosc");
  const std::string relative = "../regression/cut_in.xosc";
  const size_t at = text.find(relative);
  REQUIRE(at != std::string::npos);
  return text.replace(at, relative.size(), suites + "regression/cut_in.xosc");
}

/// `text` with every occurrence of `from` replaced by `to` (at least one must exist).
std::string replaced_all(std::string text, const std::string& from, const std::string& to) {
  size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  for (; at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

/// Runs `corsa sweep` on `text` and checks that it was rejected with no output folder made.
void check_sweep_rejected(const std::string& name, const std::string& text) {
  TempDir dir;
  const auto distribution = dir.path() / "grid.xosc";
  std::ofstream(distribution, std::ios::binary) << text;
  const BoundedResult result =
      run_bounded({"sweep", distribution.string(), "-o", (dir.path() / "out").string(), "--quiet",
                   "--duration", "0.1", "--no-trajectories"});
  INFO(describe(name, result));
  CHECK_FALSE(result.timed_out);
  CHECK(result.exit_code == 2);
  CHECK(has_located_error(result.err));
  CHECK(entry_names(dir.path()) == std::set<std::string>{"grid.xosc"});
}

TEST_CASE("Truncated sweep distributions are rejected before an output folder is made",
          "[robustness][sweep]") {
  for (const Mutant& mutant : truncations(grid_text(), {0.0, 0.1, 0.4, 0.7, 0.95, 0.995})) {
    check_sweep_rejected("cut_in_grid.xosc " + mutant.name, mutant.text);
  }
}

TEST_CASE("Bad ranges, missing scenarios and absurd variant counts are rejected at their line",
          "[robustness][sweep]") {
  const std::string grid = grid_text();
  for (const char* step : {"0", "-1", "nan", "1e-300", "abc"}) {
    check_sweep_rejected(
        std::string("stepWidth ") + step,
        replaced_all(grid, "stepWidth=\"2\"", std::string("stepWidth=\"") + step + "\""));
  }
  check_sweep_rejected("range over all doubles",
                       replaced_all(grid, "lowerLimit=\"20\" upperLimit=\"38\"",
                                    "lowerLimit=\"-1e308\" upperLimit=\"1e308\""));
  check_sweep_rejected("missing scenario", replaced_all(grid, "regression/cut_in.xosc",
                                                        "regression/no_such_scenario.xosc"));
  check_sweep_rejected("scenario is a folder",
                       replaced_all(grid, "regression/cut_in.xosc", "regression"));
  // Two ranges of 9 million values and a set of 10: 8.1e14 variants. Each range alone is
  // allowed; their product used to end in "out of memory" after sweep.json was written.
  check_sweep_rejected("8.1e14 variants",
                       replaced_all(grid, "stepWidth=\"2\"", "stepWidth=\"0.000002\""));
}

TEST_CASE("Broken suite manifests are rejected with a located error and no JUnit report",
          "[robustness][suite]") {
  const std::string manifest =
      slurp(std::string(CORSA_SOURCE_DIR) + "/scenarios/suites/regression/suite.xml");
  std::vector<Mutant> mutants = truncations(manifest, {0.0, 0.05, 0.3, 0.6, 0.9, 0.995});
  mutants.push_back({"NUL bytes", std::string(32, '\0')});
  mutants.push_back({"version text", replaced_all(manifest, "version=\"1\"", "version=\"one\"")});
  mutants.push_back({"dt NaN", replaced_all(manifest, "dt=\"0.01\"", "dt=\"nan\"")});
  for (const Mutant& mutant : mutants) {
    TempDir dir;
    std::ofstream(dir.path() / "suite.xml", std::ios::binary) << mutant.text;
    const BoundedResult result = run_bounded(
        {"test", dir.path().string(), "--quiet", "--junit", (dir.path() / "junit.xml").string()});
    INFO(describe("suite.xml " + mutant.name, result));
    CHECK_FALSE(result.timed_out);
    CHECK(result.exit_code == 2);
    CHECK(has_located_error(result.err));
    CHECK(result.err.find("suite.xml:") != std::string::npos);
    CHECK(entry_names(dir.path()) == std::set<std::string>{"suite.xml"});
  }
}

}  // namespace
}  // namespace corsa::test
