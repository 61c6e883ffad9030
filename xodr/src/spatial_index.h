#pragma once

// World -> lane lookup structure: every lane section is cut into chunks short enough to be
// nearly straight (<= 5 m, <= 0.1 rad of heading); each chunk gets an oriented rectangle around
// its chord covering all its lanes. A query tests the rectangles near the point, then projects
// onto the reference line of the few chunks that contain it (Newton on s). Private to
// corsa_xodr.

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "corsa/xodr/map.h"
#include "region_bounds.h"

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

  /// The least r for which near(x, y, r) holds (up to rounding): how far, along the
  /// rectangle's own axes, (x, y) lies outside it (negative inside). It changes by no more than
  /// the point moves.
  double excess(double x, double y) const {
    const double dx = x - ox;
    const double dy = y - oy;
    const double a = dx * ux + dy * uy;
    const double b = dy * ux - dx * uy;
    return std::max(std::max(a0 - a, a - a1), std::max(b0 - b, b - b1));
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

/// The index, built region by region: Map's first query prepares a cheap bound per lane section
/// (region_bounds.h) and a coarse grid of those bounds; a section's chunks (and the boxes of
/// their runs of eight) are built the first time a query can reach the section, so that a run
/// that locates a few points pays for the roads around them, not for the whole map. Answers are
/// those of an index built all at once: the same chunks, evaluated in the same order (road,
/// section, s). Queries may come from several threads (a sweep shares the map).
class SpatialIndex {
 public:
  SpatialIndex();
  ~SpatialIndex();
  SpatialIndex(const SpatialIndex&) = delete;
  SpatialIndex& operator=(const SpatialIndex&) = delete;

  /// The coarse level: every section's bound and the grid over them (no chunks yet).
  void prepare(const Map& map);
  std::optional<LanePosition> locate(const Map& map, double x, double y,
                                     const LocateOptions& options) const;
  /// Map::clear_of_lanes: how far (x, y) can move with every locate query of at most
  /// `max_distance` still finding no chunk to examine.
  double clear_of_lanes(const Map& map, double x, double y, double max_distance,
                        double reach) const;
  /// Builds the chunks of every section now (what a query that reached all would do).
  void build_all(const Map& map) const;
  size_t section_count() const;
  /// Sections whose chunks have been built so far.
  size_t built_sections() const;
  /// Built chunks whose rectangle's box is not inside their section's bound (a check for the
  /// tests: must be 0, or a query could miss a section it needs).
  size_t chunks_outside_bounds() const;

 private:
  struct Block {
    uint32_t first = 0, end = 0;                    ///< chunks [first, end) of the section
    double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;  ///< box of their rectangles
  };
  struct Section {
    uint32_t road = 0;
    uint32_t section = 0;
    bool bounded = false;
    Bounds bounds;  ///< where its chunks can be (region_bounds.h)
    std::once_flag once;
    std::vector<Chunk> chunks;  ///< in s order, built on first need
    std::vector<Bounds> boxes;  ///< each chunk's rectangle's box
    std::vector<Block> blocks;  ///< runs of eight chunks
  };
  Section& built(const Map& map, uint32_t index) const;
  /// Sections the coarse grid lists near [x - r, x + r] x [y - r, y + r], ascending, with the
  /// sections without a bound.
  void sections_near(double x, double y, double r, std::vector<uint32_t>& out) const;

  std::vector<std::unique_ptr<Section>> sections_;
  std::vector<uint32_t> everywhere_;  ///< sections without a bound (or a huge one)
  double min_x_ = 0.0, min_y_ = 0.0, cell_ = 64.0;
  int nx_ = 0, ny_ = 0;
  std::vector<uint32_t> cell_start_;  ///< CSR: nx*ny + 1 offsets into cell_items_
  std::vector<uint32_t> cell_items_;
  mutable std::atomic<size_t> built_count_{0};
};

}  // namespace corsa::xodr::detail
