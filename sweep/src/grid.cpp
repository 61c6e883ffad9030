#include "corsa/sweep/grid.h"

#include <algorithm>
#include <cmath>

#include "corsa/core/diagnostic.h"
#include "corsa/core/strings.h"

namespace corsa::sweep {
namespace {

// Same cap as the loader's DistributionRange: a typo in a step must not allocate gigabytes.
constexpr size_t kMaxValues = 10'000'000;

std::string too_many(size_t max_values) {
  return max_values >= kMaxValues ? "the range has more than 10 million values"
                                  : "the grid's axes hold more than 10 million values in all (" +
                                        std::to_string(max_values) + " are left for this one)";
}

[[noreturn]] void fail(std::string_view text, const std::string& message) {
  throw InputError(make_error("--param " + std::string(text), 0, message));
}

// LOW:HIGH:STEP when the spec has exactly three numeric parts; false otherwise.
bool parse_range(std::string_view text, std::string_view spec, std::vector<std::string>& values,
                 size_t max_values) {
  const auto parts = split(spec, ':');
  if (parts.size() != 3) {
    return false;
  }
  const auto low = parse_double(parts[0]);
  const auto high = parse_double(parts[1]);
  const auto step = parse_double(parts[2]);
  if (!low || !high || !step) {
    return false;
  }
  if (!(*step > 0.0)) {
    fail(text, "the step of a range LOW:HIGH:STEP must be positive");
  }
  if (*high < *low) {
    fail(text, "empty range: HIGH (" + std::string(trim(parts[1])) + ") is below LOW (" +
                   std::string(trim(parts[0])) + ")");
  }
  const double steps = std::floor((*high - *low) / *step + 1e-9);
  if (steps + 1.0 > static_cast<double>(std::min(max_values, kMaxValues))) {
    fail(text, too_many(max_values));
  }
  const auto count = static_cast<size_t>(steps) + 1;
  values.reserve(count);
  for (size_t k = 0; k < count; ++k) {
    // low + k * step, not a running sum, so that rounding does not accumulate (as xosc does).
    values.push_back(format_double(*low + static_cast<double>(k) * *step + 0.0));
  }
  return true;
}

}  // namespace

GridAxis parse_grid_axis(std::string_view text, size_t max_values) {
  const size_t eq = text.find('=');
  if (eq == std::string_view::npos) {
    fail(text, "expected NAME=VALUES (VALUES: LOW:HIGH:STEP, a list A,B,C or one value)");
  }
  GridAxis axis;
  axis.spec = std::string(text);
  axis.name = std::string(trim(text.substr(0, eq)));
  if (!axis.name.empty() && axis.name.front() == '$') {
    axis.name.erase(0, 1);  // `$speed` names the parameter `speed`, as in parameterRef
  }
  if (axis.name.empty()) {
    fail(text, "the parameter name is empty");
  }
  const std::string_view spec = text.substr(eq + 1);
  if (trim(spec).empty()) {
    fail(text, "no value given for parameter '" + axis.name + "'");
  }
  if (parse_range(text, spec, axis.values, max_values)) {
    return axis;
  }
  for (const std::string_view value : split(spec, ',')) {
    if (trim(value).empty()) {
      fail(text, "empty value in the list for parameter '" + axis.name + "'");
    }
    axis.values.emplace_back(trim(value));
  }
  if (axis.values.size() > max_values) {
    fail(text, too_many(max_values));
  }
  return axis;
}

}  // namespace corsa::sweep
