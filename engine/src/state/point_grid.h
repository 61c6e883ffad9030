#pragma once

// Points (entity reference points) in a uniform grid of square cells, hashed by cell: "who is
// near (x, y)" in time proportional to the points nearby instead of all of them. Used where
// traffic is placed (spawn points at least a clearance from every entity) and where generated
// traffic looks around itself (controllers/npc_caution.h).

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace corsa::engine::detail {

/// Cell coordinates (|x| / cell) at or beyond this go to a grid's overflow list: cell keys stay
/// exact 32-bit integers, a query never loops over absurd ranges, and the bounds stay sane.
inline constexpr double kMaxGridCell = 1e9;

class PointGrid {
 public:
  /// `cell`: side of a cell (m, > 0); queries reaching a few cells are the cheapest.
  explicit PointGrid(double cell);

  void clear();
  /// Adds point `id` at (x, y) (m). Non-finite coordinates go to one overflow list that every
  /// query returns.
  void add(double x, double y, uint32_t id);
  /// Appends to `out` the ids of every point within `radius` (m) of (x, y) in both axes, and
  /// possibly some beyond (callers test the exact distance); in no particular order.
  void query(double x, double y, double radius, std::vector<uint32_t>& out) const;
  /// Appends to `out` the ids of every point in [x_min, x_max] x [y_min, y_max] (m), and
  /// possibly some beyond; in no particular order.
  void query_box(double x_min, double y_min, double x_max, double y_max,
                 std::vector<uint32_t>& out) const;
  /// A rectangle in a frame at (x, y) whose x axis has cosine `c` and sine `s` (finite): appends
  /// to `out` the ids of the points of the cells covering [x_min, x_max] x [y_min, y_max] (m, the
  /// rectangle's bounding box) whose frame coordinates, (px - x) * c + (py - y) * s along and
  /// -(px - x) * s + (py - y) * c across, lie in [along_min, along_max] x [-half, half], and
  /// the points with non-finite coordinates. The points are tested where the grid keeps them,
  /// one after the other, instead of by the caller at each entity's own place in memory.
  void query_band(double x_min, double y_min, double x_max, double y_max, double x, double y,
                  double c, double s, double along_min, double along_max, double half,
                  std::vector<uint32_t>& out) const;

 private:
  struct Point {
    double x = 0.0, y = 0.0;
    uint32_t id = 0;
  };
  /// Visits the cells covering the box (every cell for a huge or non-finite box).
  template <typename Visit>
  void visit_cells(double x_min, double y_min, double x_max, double y_max, Visit visit) const;

  double cell_;
  /// Cells are kept when emptied (clear), so that a step's points refill the same vectors.
  std::unordered_map<uint64_t, std::vector<Point>> cells_;
  size_t points_ = 0;
  std::vector<uint32_t> overflow_;
};

}  // namespace corsa::engine::detail
