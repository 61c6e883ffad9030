#pragma once

// Points (entity reference points) of one step in a uniform grid of square cells, laid out as
// one array sorted by cell (column after column) with each cell's start: "who is near (x, y)"
// for a picture that is built once and then only read (controllers/follow_view.h). Against the
// hashed grid of state/point_grid.h, which takes points between queries, a query finds a cell
// by arithmetic instead of a hash look-up and reads a column's cells as one run of memory:
// small cells then cost little, and a query looks at few points besides the ones it returns.

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

}  // namespace corsa::engine::detail
