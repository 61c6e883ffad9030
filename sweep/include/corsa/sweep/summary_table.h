#pragma once

// summary.csv of a sweep: one row per variant, sorted by index. Columns:
//   index, one column per parameter (in the plan's order), status, exit_status, end_reason,
//   sim_time, steps, collisions, min_ttc, min_distance, max_deceleration, error, wall_time
// Numbers are in the shortest text that reads back exactly; a metric never measured is empty.
// wall_time (seconds) is last and is the only column that differs between two runs of the same
// sweep, so that everything before it compares byte for byte.

#include <cstddef>
#include <string>
#include <vector>

#include "corsa/sweep/csv.h"
#include "corsa/sweep/variant_plan.h"
#include "corsa/sweep/variant_run.h"

namespace corsa::sweep {

/// The header fields for these parameter columns. A parameter whose name is also a fixed column
/// (e.g. "index") gets the column "$index".
std::vector<std::string> summary_header(const std::vector<std::string>& parameter_names);

/// The row of variant `index` (fields in header order).
std::vector<std::string> summary_row(size_t index, const std::vector<std::string>& parameter_names,
                                     const ParameterValues& values, const VariantResult& result);

/// A row's text without its last field (wall_time): what must be identical between runs.
inline std::string without_wall_time(const std::vector<std::string>& row) {
  return csv_line(std::vector<std::string>(row.begin(), row.end() - (row.empty() ? 0 : 1)));
}

/// Number of columns that are not parameters (index, status, ..., wall_time).
inline constexpr size_t kFixedColumnCount = 12;

/// Position of the status column in a row with `parameters` parameter columns.
inline size_t status_column(size_t parameters) { return 1 + parameters; }

}  // namespace corsa::sweep
