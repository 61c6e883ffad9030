#pragma once

// Golden trajectories: a run's trajectory CSV (engine format, DESIGN.md "File formats") compared
// row by row with a stored one, numbers within per-column tolerances.

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace corsa::suite {

/// The numeric columns compared with a tolerance, in trajectory order.
inline constexpr std::array<std::string_view, 9> kGoldenColumns = {"x", "y",     "z", "h", "p",
                                                                   "r", "speed", "s", "t"};

/// Tolerance per numeric column: metres for x, y, z, s, t; radians for h, p, r (compared modulo
/// 2 pi); m/s for speed.
struct Tolerances {
  std::array<double, kGoldenColumns.size()> value = {0.01,  0.01, 0.01, 0.001, 0.001,
                                                     0.001, 0.01, 0.01, 0.01};
  /// The slot of a column name; nothing for a name that is not in kGoldenColumns.
  static std::optional<size_t> column(std::string_view name);
};

/// The worst difference found in one column, and where.
struct Deviation {
  std::string column;
  double worst = 0.0;
  double time = 0.0;  ///< s
  std::string entity;
  double tolerance = 0.0;
  bool exceeded() const { return worst > tolerance; }
};

struct GoldenComparison {
  /// Problems, one sentence each: a column beyond its tolerance (with its worst deviation and
  /// where), a row whose time, entity, road or lane differ, rows missing on either side.
  std::vector<std::string> failures;
  /// The worst deviation of every numeric column (also when within tolerance).
  std::vector<Deviation> deviations;
  bool ok() const { return failures.empty(); }
};

/// Compares trajectory CSV texts. Rows are matched in order; the comparison stops at the first
/// row whose time or entity differ (the rows after it would not be comparable). s and t are not
/// compared on rows where the road differs.
GoldenComparison compare_trajectories(std::string_view golden, std::string_view actual,
                                      const Tolerances& tolerances);

/// Checks a stored golden trajectory before any test runs, so that a golden that cannot be read
/// is bad input of the suite (exit 2) rather than a failing test: the header must be the
/// trajectory header, every row must have its 13 fields, time and x..speed must be finite
/// numbers, s and t numbers or empty (off the road). Throws InputError at `file:line`.
void check_golden_file(const std::filesystem::path& file);

}  // namespace corsa::suite
