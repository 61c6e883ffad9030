#pragma once

// Points (entity reference points) of one step in a uniform grid of square cells, laid out as
// one array sorted by cell (column after column) with each cell's start: "who is near (x, y)"
// for a picture that is built once and then only read (controllers/follow_view.h). Against the
// hashed grid of state/point_grid.h, which takes points between queries, a query finds a cell
// by arithmetic instead of a hash look-up and reads a column's cells as one run of memory:
// small cells then cost little, and a query looks at few points besides the ones it returns.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace corsa::engine::detail {

class PackedPointGrid {
 public:
  /// `cell`: side of a cell (m, > 0). When the points spread so wide that this would make many
  /// more cells than points, the cells are made larger (queries stay exact, only slower).
  explicit PackedPointGrid(double cell);

  /// Empties the grid (keeping its memory); add() the points, then finish() before a query.
  void clear();
  /// Adds point `id` at (x, y) (m). Non-finite or absurdly far coordinates go to one overflow
  /// list that every query returns.
  void add(double x, double y, uint32_t id);
  /// Sorts the points added since clear() into their cells.
  void finish();

  /// Appends to `out` the ids of every point in [x_min, x_max] x [y_min, y_max] (m), and
  /// possibly some beyond; in no particular order.
  void query_box(double x_min, double y_min, double x_max, double y_max,
                 std::vector<uint32_t>& out) const;
  /// A rectangle in a frame at (x, y) whose x axis has cosine `c` and sine `s`: appends to `out`
  /// the ids of the points of the cells covering [x_min, x_max] x [y_min, y_max] (m, the
  /// rectangle's bounding box) whose frame coordinates,
  /// (px - x) * c + (py - y) * s along and -(px - x) * s + (py - y) * c across, lie in
  /// [along_min, along_max] x [-half, half], and the points of the overflow list. The same
  /// contract as PointGrid::query_band.
  void query_band(double x_min, double y_min, double x_max, double y_max, double x, double y,
                  double c, double s, double along_min, double along_max, double half,
                  std::vector<uint32_t>& out) const;
  /// The ids query_band appends, in the same order, handed to `visit(ids, count)` in runs
  /// instead (a caller that tests each of them at once needs no list of them: the corridor
  /// queries of generated traffic, one per vehicle and step).
  template <typename Visit>
  void visit_band(double x_min, double y_min, double x_max, double y_max, double x, double y,
                  double c, double s, double along_min, double along_max, double half,
                  Visit visit) const;

  /// Points in the cells (the overflow list apart).
  size_t size() const { return points_.size(); }

 private:
  struct Point {
    double x = 0.0, y = 0.0;
    uint32_t id = 0;
  };
  /// Column (x) or row (y) of coordinate `v` (>= `origin`), at most count - 1.
  int64_t cell_of(double v, double origin, int64_t count) const;
  /// The columns (or rows) [first, last] that [low, high] covers; false when none.
  bool span_of(double low, double high, double origin, int64_t count, int64_t& first,
               int64_t& last) const;
  /// Calls visit(first, last) with runs of the points of the cells covering the box (every
  /// point for a NaN bound).
  template <typename Visit>
  void visit_box(double x_min, double y_min, double x_max, double y_max, Visit visit) const;

  double cell_;  ///< m, asked for
  double size_;  ///< m, the side used since the last finish()
  double x0_ = 0.0, y0_ = 0.0;
  int64_t nx_ = 0, ny_ = 0;
  std::vector<Point> staged_;
  std::vector<Point> points_;     ///< by cell: column i, row j at cell i * ny_ + j
  std::vector<uint32_t> starts_;  ///< nx_ * ny_ + 1 offsets into points_
  std::vector<uint32_t> overflow_;
  std::vector<uint32_t> cells_;  ///< scratch of finish(): each staged point's cell
};

[[gnu::always_inline]] inline bool PackedPointGrid::span_of(double low, double high, double origin,
                                                            int64_t count, int64_t& first,
                                                            int64_t& last) const {
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
[[gnu::always_inline]] inline void PackedPointGrid::visit_box(double x_min, double y_min,
                                                              double x_max, double y_max,
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
  const Point* const points = points_.data();
  const uint32_t* const starts = starts_.data();
  for (int64_t i = i0; i <= i1; ++i) {
    visit(points + starts[i * ny_ + j0], points + starts[i * ny_ + j1 + 1]);
  }
}

template <typename Visit>
[[gnu::always_inline]] inline void PackedPointGrid::visit_band(double x_min, double y_min,
                                                               double x_max, double y_max, double x,
                                                               double y, double c, double s,
                                                               double along_min, double along_max,
                                                               double half, Visit visit) const {
  if (!overflow_.empty()) {
    visit(overflow_.data(), overflow_.size());
  }
  // Whether a point is in the band follows no pattern a branch predictor learns (800 vehicles
  // on Town04: a corridor's query looks at 5.8 points and keeps 2.5), so every point's id is
  // written to a buffer on the stack and the buffer's end moved by the test; the buffer goes to
  // `visit` when full and at the end. The same ids in the same order as a test per point, at
  // more instructions (the three comparisons of every point) and fewer mispredicted branches.
  constexpr size_t kBuffer = 128;
  uint32_t kept[kBuffer];
  size_t count = 0;
  visit_box(x_min, y_min, x_max, y_max, [&](const Point* first, const Point* last) {
    while (first != last) {
      if (count == kBuffer) {
        visit(static_cast<const uint32_t*>(kept), count);
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
  if (count != 0) {
    visit(static_cast<const uint32_t*>(kept), count);
  }
}

}  // namespace corsa::engine::detail
