#pragma once

// Cross-sections of one lane section for the road mesh and the road marks: the reference frame
// and the lane borders at a given s, and the adaptive choice of the s samples. Private to
// corsa_xodr.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "corsa/xodr/map.h"
#include "corsa/xodr/road_mesh.h"
#include "road_eval.h"

namespace corsa::xodr::detail {

/// The road frame at one s: reference point, elevation, superelevation roll.
struct RoadFrame {
  double s = 0.0;
  double x = 0.0;
  double y = 0.0;
  double cos_h = 1.0;  ///< of the reference heading
  double sin_h = 0.0;
  double z = 0.0;      ///< elevation (m)
  double cos_r = 1.0;  ///< of the superelevation roll
  double sin_r = 0.0;
};

/// A place along s where the samples must have a row. At a kink (a planView record whose start
/// does not continue the previous record's end in position or heading, as in polyline maps) the
/// surface has two edges at the same s: the previous record's end and this record's start.
struct Knot {
  double s = 0.0;
  int kink_geometry = -1;  ///< index of the planView record starting here with a kink, or -1
};

/// One lane section of one road, ready to be evaluated at any s in [s0, s1].
class SectionView {
 public:
  SectionView(const Map& map, uint32_t road, uint32_t section);

  const Map& map() const { return map_; }
  const Road& road() const { return road_; }
  const LaneSection& section() const { return section_; }
  uint32_t road_index() const { return road_index_; }
  double s0() const { return s0_; }
  double s1() const { return s1_; }
  /// Lanes with a span (the centre lane left out), left to right; borders() = lanes() + 1.
  size_t lanes() const { return lane_count_; }
  size_t borders() const { return lane_count_ + 1; }
  /// The Lane record of span `i` (left to right).
  const Lane& lane(size_t i) const { return *span_lanes_[i]; }
  bool has_shape() const { return !road_.shapes.empty(); }

  RoadFrame frame(double s) const;
  /// Lane borders at s, left to right (`borders()` values, t in m). Border i is the left border
  /// of lane i and border i + 1 its right border.
  void border_ts(double s, double* out) const;
  /// The road surface at lateral position t (no lane height): OpenDRIVE 1.8 §2.3 / §8.4, the
  /// same formula as Map::world_pose with h = 0.
  Vec3 surface(const RoadFrame& frame, double t) const;
  /// Height (m) of lane `i` at s on its left (`left` true) or right border (lane height records,
  /// linear between records along s, held after the last; 0 without records).
  double lane_height(size_t i, double s, bool left) const;
  /// Where anything along s may change non-smoothly, s0 and s1 included, sorted, without
  /// near-duplicates: geometry, profile, width and height record starts.
  std::vector<Knot> knots() const;
  /// The frame at s as the planView record *before* `knot.geometry` gives it (its end, the left
  /// limit at a kink).
  RoadFrame frame_before(const Knot& knot) const;

 private:
  const Map& map_;
  const Road& road_;
  const LaneSection& section_;
  uint32_t road_index_ = 0;
  double s0_ = 0.0;
  double s1_ = 0.0;
  size_t lane_count_ = 0;
  const Lane* span_lanes_[kMaxLanesPerSection] = {};
};

/// Samples of one section: s values and, per sample, the frame and the border ts (flattened,
/// `borders` per row). At a kink two consecutive rows have the same s (the left and the right
/// limit); the lanes between them form a wedge that closes the gap on the outer side of the
/// turn, and its inner side (which would overlap) is left out.
struct SectionSamples {
  size_t borders = 0;
  std::vector<double> s;
  std::vector<RoadFrame> frames;
  std::vector<double> t;  ///< row r, border j at t[r * borders + j]

  size_t rows() const { return s.size(); }
  const double* row_t(size_t r) const { return t.data() + r * borders; }
};

/// Chooses the s samples of a section so that, between consecutive samples, every lane border
/// (and, on roads with a lateral shape, the surface between borders) stays within `tolerance`
/// of the straight segment joining its two samples. Always includes s0, s1 and the breakpoints;
/// `max_segment` > 0 caps the spacing.
SectionSamples sample_section(const SectionView& view, double tolerance, double max_segment);

}  // namespace corsa::xodr::detail
