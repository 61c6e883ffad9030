#pragma once

// What a road pose reads (Map::world_pose, Map::reference, the lane offset of a lane span),
// packed for the whole map at build: per road a small header, the road's planView records each
// with its heading's cosine and sine, and its laneOffset, elevation and superelevation records
// one after the other. Read from the Road records, a pose touched the Road (its length and the
// vectors' headers), then each of those vectors' heap blocks and the cached trigonometry apart:
// with hundreds of vehicles at as many places of a large map those were cache misses on every
// move. The records are copies, evaluated by the same functions, so every result is the same to
// the bit.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "corsa/xodr/model.h"
#include "geometry_local.h"

namespace corsa::xodr::detail {

/// A planView record with its heading's cosine and sine (std::cos / std::sin of hdg).
struct PoseGeometry {
  Geometry geometry;
  double cos_h = 1.0;
  double sin_h = 0.0;
};

/// One road: its length and where its records are in PoseTable's arrays. The records' starts
/// are also kept apart, one road's one after the other (planView, laneOffset, elevation,
/// superelevation) from `key_first`, so that the binary searches read a line or two of them and
/// then one record, not a line of every record they probe.
struct PoseRoad {
  double length = 0.0;
  uint32_t key_first = 0;       ///< in PoseTable::keys
  uint32_t geometry_first = 0;  ///< in PoseTable::geometries
  uint32_t geometry_count = 0;
  uint32_t offset_first = 0;  ///< laneOffset records, in PoseTable::polys
  uint32_t offset_count = 0;
  uint32_t elevation_first = 0;  ///< then the elevation records
  uint32_t elevation_count = 0;
  uint32_t roll_first = 0;  ///< then the superelevation records
  uint32_t roll_count = 0;
  bool has_shapes = false;  ///< lateralProfile shapes (read from the Road record)
  /// Every laneOffset record (or none) a = b = c = d = +0 with |s| <= PoseTable::kZeroBound: the
  /// offset is +0 at every s with |s| <= kZeroBound (no search, no record read).
  bool zero_offsets = false;
  /// The same for the superelevation records: the roll is +0 there.
  bool level = false;
};

/// A run of Poly3 records in road-s order (absolute s starts), with their starts apart.
struct PolyRun {
  const Poly3* first = nullptr;
  const double* starts = nullptr;  ///< first[i].s
  size_t count = 0;

  /// poly_value (road_eval.h) on the same records: 0 without records and before the first.
  double value(double s) const {
    if (count == 0 || s < starts[0]) {
      return 0.0;
    }
    return first[index(s)].value(s);
  }
  /// Index of the last record starting at or before s (0 when s precedes all), as record_index.
  size_t index(double s) const;
};

class PoseTable {
 public:
  /// Below this |s| and |record s|, s - record s is finite, and a record of four +0 coefficients
  /// evaluates to +0 (a + x (b + x (c + x d)) with every product +-0 and every sum +0).
  static constexpr double kZeroBound = 1e300;

  /// Packs `roads` with the cosines and sines of their planView headings.
  void build(const std::vector<Road>& roads);

  const PoseRoad& road(size_t road) const { return roads_[road]; }
  double clamp_s(const PoseRoad& road, double s) const {
    return s < 0.0 ? 0.0 : s > road.length ? road.length : s;
  }
  /// The last planView record starting at or before s, nullptr when s precedes them all.
  const PoseGeometry* geometry_before(const PoseRoad& road, double s) const;
  /// The planView record holding s (already clamped to the road), as Map::reference picks it.
  const PoseGeometry& geometry_at(const PoseRoad& road, double s) const;
  PolyRun lane_offsets(const PoseRoad& road) const {
    return {polys_.data() + road.offset_first, keys_.data() + road.key_first + road.geometry_count,
            road.offset_count};
  }
  PolyRun elevation(const PoseRoad& road) const {
    return {polys_.data() + road.elevation_first,
            keys_.data() + road.key_first + road.geometry_count + road.offset_count,
            road.elevation_count};
  }
  PolyRun superelevation(const PoseRoad& road) const {
    return {polys_.data() + road.roll_first,
            keys_.data() + road.key_first + road.geometry_count + road.offset_count +
                road.elevation_count,
            road.roll_count};
  }

 private:
  std::vector<PoseRoad> roads_;
  std::vector<PoseGeometry> geometries_;
  std::vector<Poly3> polys_;
  std::vector<double> keys_;  ///< the records' starts, by road (PoseRoad::key_first)
};

}  // namespace corsa::xodr::detail
