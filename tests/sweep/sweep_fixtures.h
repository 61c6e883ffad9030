#pragma once

// Shared helpers of the sweep tests: fixture paths, plans, and reading sweep outputs.

#include <filesystem>
#include <string>
#include <vector>

#include "corsa/core/atomic_file.h"
#include "corsa/core/diagnostic.h"
#include "corsa/sweep/csv.h"
#include "corsa/sweep/variant_plan.h"
#include "corsa/xosc/scenario.h"

namespace corsa::sweep::test {

inline std::filesystem::path fixture(const std::string& name) {
  return std::filesystem::path(CORSA_SOURCE_DIR) / "tests" / "sweep" / "fixtures" / name;
}

inline VariantPlan distribution_plan(const std::string& name, std::vector<GridAxis> grid = {},
                                     uint64_t seed = 0) {
  Diagnostics diagnostics;
  return VariantPlan::from_distribution(
      fixture(name), xosc::load_distribution(fixture(name), diagnostics), std::move(grid), seed);
}

inline xosc::Scenario follow_scenario() {
  Diagnostics diagnostics;
  return xosc::load_scenario(fixture("follow.xosc"), {}, diagnostics);
}

/// The rows of a CSV file, header first.
inline std::vector<std::vector<std::string>> csv_rows(const std::filesystem::path& file) {
  std::vector<std::vector<std::string>> rows;
  parse_csv(read_file(file), rows);
  return rows;
}

/// A sweep's summary.csv without its last column (wall_time, the one that differs between runs).
inline std::string summary_without_wall_time(const std::filesystem::path& folder) {
  std::string out;
  for (auto row : csv_rows(folder / "summary.csv")) {
    row.pop_back();
    out += csv_line(row);
  }
  return out;
}

/// A run summary JSON without the lines that differ between runs (wall time, real-time factor).
inline std::string without_timing(const std::string& json) {
  std::string out;
  size_t start = 0;
  while (start < json.size()) {
    size_t end = json.find('\n', start);
    end = end == std::string::npos ? json.size() : end + 1;
    const std::string line = json.substr(start, end - start);
    if (line.find("\"wall_time\"") == std::string::npos &&
        line.find("\"real_time_factor\"") == std::string::npos) {
      out += line;
    }
    start = end;
  }
  return out;
}

}  // namespace corsa::sweep::test
