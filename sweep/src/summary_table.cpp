#include "corsa/sweep/summary_table.h"

#include <algorithm>
#include <array>
#include <string_view>

#include "corsa/core/strings.h"
#include "corsa/sweep/csv.h"

namespace corsa::sweep {
namespace {

constexpr std::array<std::string_view, kFixedColumnCount> kFixedColumns = {
    "index",      "status",  "exit_status",  "end_reason",       "sim_time", "steps",
    "collisions", "min_ttc", "min_distance", "max_deceleration", "error",    "wall_time"};

std::string optional_number(const std::optional<double>& value) {
  return value ? format_double(*value + 0.0) : std::string();
}

}  // namespace

std::vector<std::string> summary_header(const std::vector<std::string>& parameter_names) {
  std::vector<std::string> header{"index"};
  for (const auto& name : parameter_names) {
    const bool clash =
        std::find(kFixedColumns.begin(), kFixedColumns.end(), name) != kFixedColumns.end();
    header.push_back(clash ? "$" + name : name);
  }
  for (size_t i = 1; i < kFixedColumns.size(); ++i) header.emplace_back(kFixedColumns[i]);
  return header;
}

std::vector<std::string> summary_row(size_t index, const std::vector<std::string>& parameter_names,
                                     const ParameterValues& values, const VariantResult& result) {
  std::vector<std::string> row{std::to_string(index)};
  for (const auto& name : parameter_names) {
    const auto found = std::find_if(values.begin(), values.end(),
                                    [&](const auto& value) { return value.first == name; });
    row.push_back(found == values.end() ? std::string() : found->second);
  }
  row.emplace_back(to_string(result.status));
  row.push_back(std::to_string(exit_status(result.status)));
  if (result.ok()) {
    row.emplace_back(engine::to_string(result.end_reason));
    row.push_back(format_double(result.sim_time + 0.0));
    row.push_back(std::to_string(result.steps));
    row.push_back(std::to_string(result.collisions));
    row.push_back(optional_number(result.metrics.min_ttc.value));
    row.push_back(optional_number(result.metrics.min_distance.value));
    row.push_back(optional_number(result.metrics.max_deceleration.value));
  } else {
    row.insert(row.end(), 7, std::string());
  }
  row.push_back(result.error);
  row.push_back(format_fixed(result.wall_seconds, 6));
  return row;
}

}  // namespace corsa::sweep
