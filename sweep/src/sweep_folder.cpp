#include "sweep_folder.h"

#include "corsa/core/input_file.h"
#include "corsa/core/strings.h"
#include "corsa/sweep/csv.h"

namespace corsa::sweep::detail {

std::string plan_of(const Json& description) {
  const auto plan = description.find("plan");
  return plan != description.end() && plan->is_string() ? plan->get<std::string>() : "";
}

std::optional<size_t> variant_count_of(const Json& description) {
  const auto count = description.find("variants");
  if (count == description.end() || !count->is_number_unsigned()) return std::nullopt;
  return count->get<size_t>();
}

std::optional<Table> read_table(const std::filesystem::path& file) {
  std::error_code error;
  if (!std::filesystem::exists(file, error)) return std::nullopt;
  // Anything but a regular file of bounded size is an error (a FIFO would block).
  const std::string text = read_file(file);
  std::vector<std::vector<std::string>> rows;
  if (!parse_csv(text, rows) || rows.empty()) return std::nullopt;
  Table table;
  table.header = std::move(rows.front());
  rows.erase(rows.begin());
  for (const auto& row : rows) {
    if (row.size() != table.header.size()) return std::nullopt;
  }
  table.rows = std::move(rows);
  return table;
}

std::optional<size_t> row_index(const std::vector<std::string>& row) {
  if (row.empty()) return std::nullopt;
  const auto value = parse_int(row.front());
  if (!value || *value < 0) return std::nullopt;
  return static_cast<size_t>(*value);
}

}  // namespace corsa::sweep::detail
