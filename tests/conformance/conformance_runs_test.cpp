// Every published scenario of ../shared/conformance runs to its stop trigger: ASAM's 15 ALKS
// scenarios (OpenSCENARIO 1.1, with the rule breaks Corsa reads leniently) and the 14 scenarios
// of the ASAM OpenSCENARIO 1.3 examples.

#include <catch2/catch.hpp>
#include <string>

#include "conformance_files.h"
#include "corsa/engine/run.h"
#include "corsa/engine/simulation.h"
#include "corsa/xosc/scenario.h"

namespace fs = std::filesystem;
using corsa::test::kConformanceDir;
using corsa::test::xosc_files;

namespace {

struct Outcome {
  corsa::engine::RunReport report;
  std::vector<corsa::Diagnostic> warnings;
  std::string error;
};

Outcome run(const fs::path& scenario, bool strict = false) {
  Outcome outcome;
  corsa::Diagnostics diagnostics;
  corsa::engine::RunOptions options;
  options.scenario = scenario;
  options.simulation.strict = strict;
  try {
    outcome.report = corsa::engine::run_scenario(options, diagnostics);
  } catch (const corsa::InputError& error) {
    outcome.error = error.what();
  }
  for (const auto& diagnostic : diagnostics.all()) {
    if (diagnostic.severity == corsa::Severity::kWarning) outcome.warnings.push_back(diagnostic);
  }
  return outcome;
}

bool lenient_warning(const corsa::Diagnostic& warning) {
  return warning.message.find("(read as ") != std::string::npos;
}

}  // namespace

TEST_CASE("every ASAM ALKS scenario runs to its stop trigger", "[conformance][alks]") {
  const auto scenarios = xosc_files(kConformanceDir / "alks" / "Scenarios", "<Storyboard");
  REQUIRE(scenarios.size() == 15);
  size_t lenient = 0;
  for (const auto& scenario : scenarios) {
    INFO(scenario.filename().string());
    const Outcome outcome = run(scenario);
    REQUIRE(outcome.error.empty());
    CHECK(outcome.report.end_reason == corsa::engine::EndReason::kStopTrigger);
    CHECK(outcome.report.sim_time > 0.0);
    lenient += std::count_if(outcome.warnings.begin(), outcome.warnings.end(), lenient_warning);
  }
  // ASAM's own files break rules of the standard (lane ids declared as strings and compared or
  // computed as numbers): read as meant, each with a warning.
  CHECK(lenient > 0);
}

TEST_CASE("ALKS scenarios that break a rule of the standard are refused under --strict",
          "[conformance][alks]") {
  const fs::path scenario = kConformanceDir / "alks" / "Scenarios" /
                            "ALKS_Scenario_4.2_1_FullyBlockingTarget_TEMPLATE.xosc";
  const Outcome outcome = run(scenario, true);
  CHECK_THAT(outcome.error, Catch::Contains("rule lessOrEqual on string parameter "
                                            "'Ego_InitPosition_LaneId'") &&
                                Catch::Contains("--strict"));
}

TEST_CASE("every ASAM OpenSCENARIO 1.3 example scenario runs to its stop trigger",
          "[conformance][asam]") {
  const auto scenarios = xosc_files(kConformanceDir / "asam-osc-1.3", "<Storyboard");
  REQUIRE(scenarios.size() == 14);
  for (const auto& scenario : scenarios) {
    INFO(scenario.filename().string());
    const Outcome outcome = run(scenario);
    REQUIRE(outcome.error.empty());
    CHECK(outcome.report.end_reason == corsa::engine::EndReason::kStopTrigger);
    // The ASAM examples follow the standard: nothing is read leniently.
    CHECK(std::none_of(outcome.warnings.begin(), outcome.warnings.end(), lenient_warning));
  }
}
