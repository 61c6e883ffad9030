#pragma once

// World -> lane lookup structure: every lane section is cut into chunks short enough to be
// nearly straight (<= 5 m, <= 0.1 rad of heading); each chunk gets an oriented rectangle around
// its chord covering all its lanes, and a uniform grid lists the chunks whose rectangle touches
// each cell. A query tests the rectangles of its cell, then projects onto the reference line of
// the few chunks that contain the point (Newton on s). Private to corsa_xodr.

#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "corsa/xodr/map.h"

namespace corsa::xodr::detail {

struct Chunk {
  uint32_t road = 0;
  uint32_t section = 0;
  double s0 = 0.0;
  double s1 = 0.0;
  // Oriented rectangle: origin, unit direction (ux, uy) along the chord, normal (-uy, ux);
  // along-range [a0, a1] and lateral range [b0, b1] in that frame, margins included.
  double ox = 0.0, oy = 0.0, ux = 1.0, uy = 0.0;
  double a0 = 0.0, a1 = 0.0, b0 = 0.0, b1 = 0.0;

  // Reference line at both ends: position, unit tangent; curvature at s0. The normals at the
  // two ends bound the points whose foot point lies in [s0, s1].
  double x0 = 0.0, y0 = 0.0, tx0 = 1.0, ty0 = 0.0, k0 = 0.0, hdg0 = 0.0;
  /// The reference line over the chunk, when it lies within one planView record whose shape
  /// allows a closed-form foot point: a line or an arc.
  enum class Shape : uint8_t { kGeneral, kLine, kArc } shape = Shape::kGeneral;
  double x1 = 0.0, y1 = 0.0, tx1 = 1.0, ty1 = 0.0;

  /// Whether (x, y) lies between the normals at s0 and s1 (with a hair of tolerance), i.e. its
  /// foot point on the reference line is in this chunk.
  bool spans(double x, double y) const {
    constexpr double kTolerance = 1e-9;
    return (x - x0) * tx0 + (y - y0) * ty0 >= -kTolerance &&
           (x - x1) * tx1 + (y - y1) * ty1 <= kTolerance;
  }

  /// Distance (m) from (x, y) to the rectangle, 0 inside.
  double distance_to(double x, double y) const {
    const double dx = x - ox;
    const double dy = y - oy;
    const double a = dx * ux + dy * uy;
    const double b = dy * ux - dx * uy;
    const double da = a < a0 ? a0 - a : a > a1 ? a - a1 : 0.0;
    const double db = b < b0 ? b0 - b : b > b1 ? b - b1 : 0.0;
    return std::sqrt(da * da + db * db);
  }

  /// Whether (x, y) is within `r` metres of the rectangle (a square-ish test, enough to prune).
  bool near(double x, double y, double r) const {
    const double dx = x - ox;
    const double dy = y - oy;
    const double a = dx * ux + dy * uy;
    const double b = dy * ux - dx * uy;
    return a >= a0 - r && a <= a1 + r && b >= b0 - r && b <= b1 + r;
  }
};

class SpatialIndex {
 public:
  void build(const Map& map);
  std::optional<LanePosition> locate(const Map& map, double x, double y,
                                     const LocateOptions& options) const;
  size_t chunk_count() const { return chunks_.size(); }

 private:
  void add_section_chunks(const Map& map, uint32_t road, uint32_t section);
  void build_grid();
  /// (chunk, cell) pairs the grid would hold with the current cell size and origin.
  double grid_entries() const;
  /// Cells overlapped by [x0, x1] x [y0, y1], clamped to the grid.
  void cell_range(double x0, double y0, double x1, double y1, int& i0, int& j0, int& i1,
                  int& j1) const;

  std::vector<Chunk> chunks_;
  double min_x_ = 0.0, min_y_ = 0.0, cell_ = 8.0;
  int nx_ = 0, ny_ = 0;
  std::vector<uint32_t> cell_start_;  ///< CSR: nx*ny + 1 offsets into cell_items_
  std::vector<uint32_t> cell_items_;
};

}  // namespace corsa::xodr::detail
