#include "state/packed_point_grid.h"

#include <algorithm>
#include <cmath>

#include "state/point_grid.h"

namespace corsa::engine::detail {
namespace {

// Cells at most eight per point (and at least this many): building the grid costs in proportion
// to the points, and sparse points get larger cells (800 vehicles on Town04 get 16 m cells, 100
// get 32-64 m ones, depending on how far they spread).
constexpr size_t kMinCellBudget = 256;
constexpr size_t kCellsPerPoint = 8;

}  // namespace

PackedPointGrid::PackedPointGrid(double cell) : cell_(cell > 0.0 ? cell : 1.0), size_(cell_) {}

void PackedPointGrid::clear() {
  staged_.clear();
  points_.clear();
  overflow_.clear();
  starts_.assign(1, 0);
  nx_ = ny_ = 0;
}

[[gnu::hot]] void PackedPointGrid::add(double x, double y, uint32_t id) {
  if (!(std::abs(x / cell_) < kMaxGridCell) || !(std::abs(y / cell_) < kMaxGridCell)) {
    overflow_.push_back(id);
    return;
  }
  staged_.push_back({x, y, id});
}

[[gnu::hot]] int64_t PackedPointGrid::cell_of(double v, double origin, int64_t count) const {
  // v >= origin: truncation is floor (the same as span_of takes).
  const double f = (v - origin) / size_;
  return f < static_cast<double>(count - 1) ? static_cast<int64_t>(f) : count - 1;
}

[[gnu::hot]] void PackedPointGrid::finish() {
  points_.clear();
  nx_ = ny_ = 0;
  starts_.assign(1, 0);
  if (staged_.empty()) {
    return;
  }
  double x1 = staged_[0].x, y1 = staged_[0].y;
  x0_ = x1, y0_ = y1;
  for (const Point& p : staged_) {
    x0_ = std::min(x0_, p.x), x1 = std::max(x1, p.x);
    y0_ = std::min(y0_, p.y), y1 = std::max(y1, p.y);
  }
  const double budget =
      static_cast<double>(std::max(kMinCellBudget, kCellsPerPoint * staged_.size()));
  size_ = cell_;
  while ((std::floor((x1 - x0_) / size_) + 1.0) * (std::floor((y1 - y0_) / size_) + 1.0) > budget) {
    size_ *= 2.0;
  }
  nx_ = static_cast<int64_t>(std::floor((x1 - x0_) / size_)) + 1;
  ny_ = static_cast<int64_t>(std::floor((y1 - y0_) / size_)) + 1;
  // Counting sort by cell; points of one cell keep the order they were added in.
  cells_.resize(staged_.size());
  starts_.assign(static_cast<size_t>(nx_ * ny_) + 1, 0);
  for (size_t k = 0; k < staged_.size(); ++k) {
    const int64_t cell = cell_of(staged_[k].x, x0_, nx_) * ny_ + cell_of(staged_[k].y, y0_, ny_);
    cells_[k] = static_cast<uint32_t>(cell);
    ++starts_[cells_[k]];
  }
  for (size_t c = 1; c + 1 < starts_.size(); ++c) starts_[c] += starts_[c - 1];  // cell ends
  points_.resize(staged_.size());
  // Each point goes before its cell's end, counted down (the last point first, so that a cell
  // keeps the order of adding): each cell's end becomes its start.
  for (size_t k = staged_.size(); k-- > 0;) points_[--starts_[cells_[k]]] = staged_[k];
  starts_.back() = static_cast<uint32_t>(points_.size());
}

void PackedPointGrid::query_box(double x_min, double y_min, double x_max, double y_max,
                                std::vector<uint32_t>& out) const {
  out.insert(out.end(), overflow_.begin(), overflow_.end());
  visit_box(x_min, y_min, x_max, y_max, [&](const Point* first, const Point* last) {
    for (const Point* p = first; p != last; ++p) out.push_back(p->id);
  });
}

[[gnu::hot]] void PackedPointGrid::query_band(double x_min, double y_min, double x_max,
                                              double y_max, double x, double y, double c, double s,
                                              double along_min, double along_max, double half,
                                              std::vector<uint32_t>& out) const {
  visit_band(
      x_min, y_min, x_max, y_max, x, y, c, s, along_min, along_max, half,
      [&out](const uint32_t* ids, size_t count) { out.insert(out.end(), ids, ids + count); });
}

}  // namespace corsa::engine::detail
