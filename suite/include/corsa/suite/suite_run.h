#pragma once

// Running a suite: every test on a few threads (the map and catalogs of a scenario shared between
// its tests), each checked against its expectations and golden trajectory.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/suite/golden.h"
#include "corsa/suite/suite.h"
#include "corsa/sweep/variant_run.h"

namespace corsa::suite {

struct SuiteOptions {
  size_t jobs = 0;  ///< threads; 0: every core
  /// Write every test's golden file from this run (tests with a <Golden>, or in folder mode every
  /// scenario) instead of comparing; the other expectations are still checked.
  bool update_goldens = false;
  /// Let update_goldens write golden files outside the suite folder (a manifest's `file="../x"`
  /// or an absolute path). Without it such a golden is refused before any test runs, as is a
  /// symbolic link on the way to a golden inside the folder: updating never writes elsewhere.
  bool goldens_outside = false;
  /// When set, each test writes <output>/<test>/trajectory.csv and summary.json there.
  std::optional<std::filesystem::path> output;
  /// The map-to-Earth transform for GeoPositions, given to every test's run
  /// (engine::SimulationOptions::geo_projection).
  engine::GeoProjectionFactory geo_projection;
  /// Every test refuses lenient readings (engine::SimulationOptions::strict, `--strict`).
  bool strict = false;
  /// Every test reads what the standard leaves open this way (engine::SimulationOptions::
  /// semantics, `--semantics`); unset: each test's own.
  std::optional<engine::Semantics> semantics;
};

enum class Verdict : uint8_t { kPassed, kFailed, kError };
std::string_view to_string(Verdict verdict);  ///< "PASS", "FAIL", "ERROR"

struct TestOutcome {
  std::string name;
  Verdict verdict = Verdict::kPassed;
  std::vector<std::string> failures;  ///< expectations missed (kFailed)
  std::string error;                  ///< why the scenario could not run (kError)
  std::optional<GoldenComparison> golden;
  bool golden_written = false;
  sweep::VariantResult run;
};

struct SuiteReport {
  std::vector<TestOutcome> outcomes;  ///< in the suite's order
  size_t passed = 0;
  size_t failed = 0;
  size_t errors = 0;
  double wall_seconds = 0.0;
  bool ok() const { return failed == 0 && errors == 0; }
};

/// Called as each test finishes (from worker threads, one at a time).
using TestFinished = std::function<void(const TestOutcome& outcome)>;

/// Runs the suite. A test whose scenario cannot run is an error of that test, never of the
/// suite; writing a golden file or an output that fails throws. With update_goldens and without
/// goldens_outside, every golden outside the suite folder is reported (all but the last through
/// `diagnostics`, the last thrown as InputError, at their manifest lines) before any test runs.
SuiteReport run_suite(const Suite& suite, const SuiteOptions& options, Diagnostics& diagnostics,
                      const TestFinished& finished = {});

}  // namespace corsa::suite
