#pragma once

// A regression suite: tests, each one scenario run with optional parameter values and checked
// against expectations (how it ended, collisions, metric bounds, a golden trajectory).
//
// A suite is a manifest file (schemas/suite.xsd, validated with located errors), or a folder:
// the folder's suite.xml when it has one, else every scenario *.xosc directly in the folder
// (catalogs and parameter distributions skipped), by file name, each compared with
// goldens/<stem>.csv when that file exists.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "corsa/engine/simulation.h"
#include "corsa/suite/golden.h"
#include "corsa/sweep/variant_plan.h"

namespace corsa::suite {

/// The metrics a bound can name (schemas/suite.xsd, MetricName).
enum class Metric : uint8_t {
  kMinTtc,
  kMinDistance,
  kMaxDeceleration,
  kMaxAcceleration,
  kMaxSpeed,
  kSimTime,
  kCollisions,
};
std::string_view to_string(Metric metric);  ///< "min_ttc", ...
std::optional<Metric> metric_from_string(std::string_view name);
/// The unit a metric is printed with: "s", "m", "m/s^2", "m/s" or "".
std::string_view unit(Metric metric);

/// min <= value <= max; at least one of them is given.
struct MetricBound {
  Metric metric = Metric::kMinTtc;
  std::optional<double> min;
  std::optional<double> max;
};

struct Expectations {
  std::optional<engine::EndReason> end_reason;
  /// true: at least one contact between two entities is required; false: none is allowed.
  std::optional<bool> collision;
  std::vector<MetricBound> metrics;
  /// Monitors (the scenario's MonitorDeclarations) expected to end with a given value; every
  /// other monitor must end true, the scenario's own "passed".
  std::vector<std::pair<std::string, bool>> monitors;
};

struct GoldenSpec {
  std::filesystem::path file;  ///< resolved against the suite folder
  int64_t every = 10;          ///< steps between rows
  Tolerances tolerances;
  int line = 0;  ///< of the <Golden> element in the manifest, 0 in folder mode
};

struct TestCase {
  std::string name;
  std::filesystem::path scenario;  ///< resolved against the suite folder
  sweep::ParameterValues parameters;
  engine::SimulationOptions simulation;
  std::string ego;  ///< "" chooses (sweep::choose_ego)
  Expectations expect;
  std::optional<GoldenSpec> golden;
  int line = 0;  ///< of the <Test> element in the manifest, 0 in folder mode
};

struct Suite {
  std::string name;
  std::filesystem::path folder;    ///< paths in the suite are relative to it
  std::filesystem::path manifest;  ///< empty for a folder without suite.xml
  std::vector<TestCase> tests;
};

/// Loads a suite from a manifest file or a folder (see above). Throws InputError located in the
/// manifest (file:line) for anything malformed: schema violations, duplicate test names, a
/// metric bound without min and max or with min > max, a tolerance given twice, a scenario file
/// that does not exist; and for a folder without any scenario.
Suite load_suite(const std::filesystem::path& path);

/// Same, from manifest text; `file` names it in messages and gives the folder.
Suite parse_suite_manifest(std::string_view xml, const std::filesystem::path& file);

}  // namespace corsa::suite
