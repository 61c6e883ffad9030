#include "corsa/suite/golden.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "corsa/core/atomic_file.h"
#include "corsa/core/diagnostic.h"
#include "corsa/core/strings.h"
#include "corsa/sweep/csv.h"

namespace corsa::suite {
namespace {

// Trajectory columns: time,entity,x,y,z,h,p,r,speed,road,lane,s,t.
constexpr size_t kTime = 0, kEntity = 1, kRoad = 9, kLane = 10, kWidth = 13;
constexpr std::array<size_t, kGoldenColumns.size()> kColumnIndex = {2, 3, 4, 5, 6, 7, 8, 11, 12};

using Rows = std::vector<std::vector<std::string>>;

std::optional<Rows> parse(std::string_view text, const char* what,
                          std::vector<std::string>& failures) {
  Rows rows;
  if (!sweep::parse_csv(text, rows) || rows.empty() || rows.front().size() != kWidth ||
      rows.front()[0] != "time") {
    failures.push_back(std::string("the ") + what + " is not a trajectory CSV");
    return std::nullopt;
  }
  rows.erase(rows.begin());
  for (size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].size() != kWidth || !parse_double(rows[i][kTime])) {
      failures.push_back(std::string("the ") + what + " has a malformed row " +
                         std::to_string(i + 2));
      return std::nullopt;
    }
  }
  return rows;
}

// |a - b|, for angles the shortest way round; an empty field (off the road) equals only another.
std::optional<double> difference(const std::string& a, const std::string& b, bool angle) {
  if (a.empty() || b.empty()) {
    return a.empty() && b.empty() ? std::optional<double>(0.0) : std::nullopt;
  }
  const auto x = parse_double(a);
  const auto y = parse_double(b);
  if (!x || !y) return std::nullopt;
  double d = std::fabs(*x - *y);
  if (angle) {
    d = std::fmod(d, 2.0 * std::numbers::pi);
    d = std::min(d, 2.0 * std::numbers::pi - d);
  }
  return d;
}

std::string where(const std::vector<std::string>& row) {
  return "at t=" + row[kTime] + " s (" + row[kEntity] + ")";
}

constexpr std::array<std::string_view, kWidth> kHeader = {
    "time", "entity", "x", "y", "z", "h", "p", "r", "speed", "road", "lane", "s", "t"};

/// The problem with one golden row (fields of line `line`), or "" when it is fine.
std::string golden_row_problem(const std::vector<std::string>& fields) {
  if (fields.size() != kWidth) {
    return std::to_string(fields.size()) + " fields where a trajectory row has " +
           std::to_string(kWidth);
  }
  for (size_t c = 0; c < kWidth; ++c) {
    const std::string& field = fields[c];
    const bool may_be_empty = c == kRoad || c == kLane || c == 11 || c == 12;
    if (c == kEntity) {
      if (field.empty()) return "no entity name";
      continue;
    }
    if (field.empty()) {
      if (may_be_empty) continue;
      return "column '" + std::string(kHeader[c]) + "' is empty";
    }
    if (c == kRoad || c == kLane) continue;  // road ids are text
    if (!parse_double(field)) {
      return "column '" + std::string(kHeader[c]) + "' is not a finite number: '" + clip(field) +
             "'";
    }
  }
  return {};
}

}  // namespace

void check_golden_file(const std::filesystem::path& file) {
  const std::string text = read_file(file);
  const auto fail = [&](int line, const std::string& message) {
    throw InputError(make_error(file.string(), line, "golden trajectory: " + message));
  };
  int line = 0;
  bool header_seen = false;
  size_t begin = 0;
  while (begin < text.size()) {
    size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    std::string_view content(text.data() + begin, end - begin);
    begin = end + 1;
    ++line;
    if (!content.empty() && content.back() == '\r') content.remove_suffix(1);
    if (content.empty()) continue;
    Rows rows;
    if (!sweep::parse_csv(content, rows) || rows.size() != 1) {
      fail(line, "a quoted field is not closed");
    }
    if (!header_seen) {
      if (rows[0].size() != kWidth ||
          !std::equal(kHeader.begin(), kHeader.end(), rows[0].begin())) {
        fail(line, "the first line is not the trajectory header (time,entity,x,...,s,t)");
      }
      header_seen = true;
      continue;
    }
    if (const std::string problem = golden_row_problem(rows[0]); !problem.empty()) {
      fail(line, problem);
    }
  }
  if (!header_seen) {
    fail(1, "empty file (write it with --update-goldens)");
  }
}

std::optional<size_t> Tolerances::column(std::string_view name) {
  for (size_t i = 0; i < kGoldenColumns.size(); ++i) {
    if (kGoldenColumns[i] == name) return i;
  }
  return std::nullopt;
}

GoldenComparison compare_trajectories(std::string_view golden, std::string_view actual,
                                      const Tolerances& tolerances) {
  GoldenComparison result;
  const auto expected = parse(golden, "golden file", result.failures);
  const auto got = parse(actual, "run's trajectory", result.failures);
  if (!expected || !got) return result;
  for (size_t c = 0; c < kGoldenColumns.size(); ++c) {
    result.deviations.push_back(
        {std::string(kGoldenColumns[c]), 0.0, 0.0, {}, tolerances.value[c]});
  }
  bool road_reported = false;
  const size_t common = std::min(expected->size(), got->size());
  for (size_t i = 0; i < common; ++i) {
    const auto& e = (*expected)[i];
    const auto& g = (*got)[i];
    if (std::fabs(*parse_double(e[kTime]) - *parse_double(g[kTime])) > 1e-9 ||
        e[kEntity] != g[kEntity]) {
      result.failures.push_back("row " + std::to_string(i + 2) + " is " + e[kEntity] +
                                " at t=" + e[kTime] + " s in the golden file but " + g[kEntity] +
                                " at t=" + g[kTime] + " s in the run");
      break;
    }
    const bool same_road = e[kRoad] == g[kRoad];
    if ((!same_road || e[kLane] != g[kLane]) && !road_reported) {
      road_reported = true;  // one report: later rows usually follow from the first
      result.failures.push_back("road/lane " + g[kRoad] + "/" + g[kLane] + " " + where(g) +
                                " differs from the golden " + e[kRoad] + "/" + e[kLane]);
    }
    for (size_t c = 0; c < kGoldenColumns.size(); ++c) {
      const size_t column = kColumnIndex[c];
      if (!same_road && (column == 11 || column == 12)) continue;  // s, t of different roads
      const auto d = difference(e[column], g[column], column >= 5 && column <= 7);
      Deviation& worst = result.deviations[c];
      const double value = d.value_or(std::numeric_limits<double>::infinity());
      if (value > worst.worst) {
        worst.worst = value;
        worst.time = *parse_double(g[kTime]);
        worst.entity = g[kEntity];
      }
    }
  }
  for (const Deviation& d : result.deviations) {
    if (d.exceeded()) {
      result.failures.push_back(
          d.column + " deviates by " +
          (std::isfinite(d.worst) ? format_double(d.worst) : std::string("a missing value")) +
          " at t=" + format_double(d.time) + " s (" + d.entity + "), tolerance " +
          format_double(d.tolerance));
    }
  }
  if (expected->size() != got->size()) {
    const auto& e_last = expected->empty() ? std::string("-") : expected->back()[kTime];
    const auto& g_last = got->empty() ? std::string("-") : got->back()[kTime];
    result.failures.push_back("the run has " + std::to_string(got->size()) +
                              " rows up to t=" + g_last + " s, the golden file " +
                              std::to_string(expected->size()) + " rows up to t=" + e_last + " s");
  }
  return result;
}

}  // namespace corsa::suite
