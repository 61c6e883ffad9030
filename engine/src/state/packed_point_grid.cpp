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

[[gnu::hot]] bool PackedPointGrid::span_of(double low, double high, double origin, int64_t count,
                                           int64_t& first, int64_t& last) const {
  // Truncation is floor for the non-negative values it is applied to, and cheaper.
  const double a = (low - origin) / size_, b = (high - origin) / size_;
  if (!(a <= b) || b < 0.0 || a >= static_cast<double>(count)) {
    return false;
  }
  first = a > 0.0 ? static_cast<int64_t>(a) : 0;
  last = b < static_cast<double>(count - 1) ? static_cast<int64_t>(b) : count - 1;
  return true;
}

template <typename Visit>
void PackedPointGrid::visit_box(double x_min, double y_min, double x_max, double y_max,
                                Visit visit) const {
  if (points_.empty()) {
    return;
  }
  if (std::isnan(x_min) || std::isnan(y_min) || std::isnan(x_max) || std::isnan(y_max)) {
    visit(points_.data(), points_.data() + points_.size());  // no region: every point
    return;
  }
  int64_t i0 = 0, i1 = 0, j0 = 0, j1 = 0;
  if (!span_of(x_min, x_max, x0_, nx_, i0, i1) || !span_of(y_min, y_max, y0_, ny_, j0, j1)) {
    return;
  }
  // A column's rows j0..j1 are one run of memory.
  for (int64_t i = i0; i <= i1; ++i) {
    visit(points_.data() + starts_[i * ny_ + j0], points_.data() + starts_[i * ny_ + j1 + 1]);
  }
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
  out.insert(out.end(), overflow_.begin(), overflow_.end());
  // Whether a point is in the band follows no pattern a branch predictor learns (800 vehicles
  // on Town04: a corridor's query looks at 5.8 points and keeps 2.5), so every point's id is
  // written to a buffer on the stack and the buffer's end moved by the test; the buffer goes to
  // `out` when full and at the end. The same ids in the same order as a test and push_back per
  // point, at more instructions (the three comparisons of every point) and fewer mispredicted
  // branches.
  constexpr size_t kBuffer = 128;
  uint32_t kept[kBuffer];
  size_t count = 0;
  visit_box(x_min, y_min, x_max, y_max, [&](const Point* first, const Point* last) {
    while (first != last) {
      if (count == kBuffer) {
        out.insert(out.end(), kept, kept + count);
        count = 0;
      }
      // At most as many points as the buffer has room for, so that every write fits.
      const Point* const end =
          first + std::min<size_t>(kBuffer - count, static_cast<size_t>(last - first));
      for (const Point* p = first; p != end; ++p) {
        const double dx = p->x - x, dy = p->y - y;
        const double along = dx * c + dy * s;
        const double across = -dx * s + dy * c;
        kept[count] = p->id;
        count += static_cast<size_t>((along >= along_min) & (along <= along_max) &
                                     (std::abs(across) <= half));
      }
      first = end;
    }
  });
  out.insert(out.end(), kept, kept + count);
}

}  // namespace corsa::engine::detail
