#include "state/point_grid.h"

#include <cmath>

namespace corsa::engine::detail {
namespace {

uint64_t key(int64_t i, int64_t j) {
  return (static_cast<uint64_t>(static_cast<uint32_t>(i)) << 32) |
         static_cast<uint64_t>(static_cast<uint32_t>(j));
}

}  // namespace

PointGrid::PointGrid(double cell) : cell_(cell > 0.0 ? cell : 1.0) {}

void PointGrid::clear() {
  // Cells emptied in place keep their memory for the next points; a grid that has gathered
  // many more cells than points (points that wandered far) starts afresh.
  if (cells_.size() > 4 * points_ + 1024) {
    cells_.clear();
  } else {
    for (auto& [cell, points] : cells_) points.clear();
  }
  points_ = 0;
  overflow_.clear();
}

void PointGrid::add(double x, double y, uint32_t id) {
  const double i = std::floor(x / cell_);
  const double j = std::floor(y / cell_);
  if (!(std::abs(i) < kMaxGridCell) || !(std::abs(j) < kMaxGridCell)) {
    overflow_.push_back(id);
    return;
  }
  cells_[key(static_cast<int64_t>(i), static_cast<int64_t>(j))].push_back({x, y, id});
  ++points_;
}

void PointGrid::query(double x, double y, double radius, std::vector<uint32_t>& out) const {
  query_box(x - radius, y - radius, x + radius, y + radius, out);
}

template <typename Visit>
void PointGrid::visit_cells(double x_min, double y_min, double x_max, double y_max,
                            Visit visit) const {
  if (points_ == 0) {
    return;
  }
  const double i0 = std::floor(x_min / cell_), i1 = std::floor(x_max / cell_);
  const double j0 = std::floor(y_min / cell_), j1 = std::floor(y_max / cell_);
  if (!(i1 - i0 < 64.0 && j1 - j0 < 64.0 && std::abs(i0) < kMaxGridCell &&
        std::abs(i1) < kMaxGridCell && std::abs(j0) < kMaxGridCell &&
        std::abs(j1) < kMaxGridCell)) {
    // A huge or far-off region (or NaN): every point.
    for (const auto& [cell, points] : cells_) {
      visit(points);
    }
    return;
  }
  for (auto i = static_cast<int64_t>(i0); i <= static_cast<int64_t>(i1); ++i) {
    for (auto j = static_cast<int64_t>(j0); j <= static_cast<int64_t>(j1); ++j) {
      const auto it = cells_.find(key(i, j));
      if (it != cells_.end()) {
        visit(it->second);
      }
    }
  }
}

void PointGrid::query_box(double x_min, double y_min, double x_max, double y_max,
                          std::vector<uint32_t>& out) const {
  out.insert(out.end(), overflow_.begin(), overflow_.end());
  visit_cells(x_min, y_min, x_max, y_max, [&](const std::vector<Point>& points) {
    for (const Point& p : points) out.push_back(p.id);
  });
}

void PointGrid::query_band(double x_min, double y_min, double x_max, double y_max, double x,
                           double y, double c, double s, double along_min, double along_max,
                           double half, std::vector<uint32_t>& out) const {
  out.insert(out.end(), overflow_.begin(), overflow_.end());
  visit_cells(x_min, y_min, x_max, y_max, [&](const std::vector<Point>& points) {
    for (const Point& p : points) {
      const double dx = p.x - x, dy = p.y - y;
      const double along = dx * c + dy * s;
      const double across = -dx * s + dy * c;
      if (along >= along_min && along <= along_max && std::abs(across) <= half) {
        out.push_back(p.id);
      }
    }
  });
}

}  // namespace corsa::engine::detail
