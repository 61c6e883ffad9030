#include "state/point_grid.h"

#include <cmath>

namespace corsa::engine::detail {
namespace {

// Cell coordinates beyond this (|x| / cell) go to the overflow list: keys stay exact 32-bit
// integers, and a query never loops over absurd ranges.
constexpr double kMaxCell = 1e9;

uint64_t key(int64_t i, int64_t j) {
  return (static_cast<uint64_t>(static_cast<uint32_t>(i)) << 32) |
         static_cast<uint64_t>(static_cast<uint32_t>(j));
}

}  // namespace

PointGrid::PointGrid(double cell) : cell_(cell > 0.0 ? cell : 1.0) {}

void PointGrid::clear() {
  cells_.clear();
  overflow_.clear();
}

void PointGrid::add(double x, double y, uint32_t id) {
  const double i = std::floor(x / cell_);
  const double j = std::floor(y / cell_);
  if (!(std::abs(i) < kMaxCell) || !(std::abs(j) < kMaxCell)) {
    overflow_.push_back(id);
    return;
  }
  cells_[key(static_cast<int64_t>(i), static_cast<int64_t>(j))].push_back(id);
}

void PointGrid::query(double x, double y, double radius, std::vector<uint32_t>& out) const {
  query_box(x - radius, y - radius, x + radius, y + radius, out);
}

void PointGrid::query_box(double x_min, double y_min, double x_max, double y_max,
                          std::vector<uint32_t>& out) const {
  out.insert(out.end(), overflow_.begin(), overflow_.end());
  if (cells_.empty()) {
    return;
  }
  const double i0 = std::floor(x_min / cell_), i1 = std::floor(x_max / cell_);
  const double j0 = std::floor(y_min / cell_), j1 = std::floor(y_max / cell_);
  if (!(i1 - i0 < 64.0 && j1 - j0 < 64.0 && std::abs(i0) < kMaxCell && std::abs(i1) < kMaxCell &&
        std::abs(j0) < kMaxCell && std::abs(j1) < kMaxCell)) {
    // A huge or far-off region (or NaN): every point.
    for (const auto& [cell, ids] : cells_) {
      out.insert(out.end(), ids.begin(), ids.end());
    }
    return;
  }
  for (auto i = static_cast<int64_t>(i0); i <= static_cast<int64_t>(i1); ++i) {
    for (auto j = static_cast<int64_t>(j0); j <= static_cast<int64_t>(j1); ++j) {
      const auto it = cells_.find(key(i, j));
      if (it != cells_.end()) {
        out.insert(out.end(), it->second.begin(), it->second.end());
      }
    }
  }
}

}  // namespace corsa::engine::detail
