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
  /// Where anything along s may change non-smoothly: s0, s1 and the geometry, profile, width
  /// and height record starts between them, sorted, without exact duplicates.
  std::vector<double> record_starts() const;

 private:
  const Map& map_;
  const Road& road_;
  const LaneSection& section_;
  uint32_t road_index_ = 0;
  uint32_t section_index_ = 0;
  double s0_ = 0.0;
  double s1_ = 0.0;
  size_t lane_count_ = 0;
  const Lane* span_lanes_[kMaxLanesPerSection] = {};
};

/// How far (m) before a record start its left limit is evaluated.
inline constexpr double kJumpEpsilon = 1e-7;

/// Samples of one section: s values and, per sample, the frame and the border ts (flattened,
/// `borders` per row). Where the cross-section jumps at a record start (a kink between planView
/// records, as in polyline maps, or a laneOffset, width or elevation record that does not
/// continue the previous one) there are two rows kJumpEpsilon apart: the left limit and the
/// right limit. Between them a kink leaves a wedge that closes the outer side of the turn; a
/// sideways jump leaves only slivers, which the mesh drops (the file has a gap there).
struct SectionSamples {
  size_t borders = 0;
  std::vector<double> s;
  std::vector<RoadFrame> frames;
  std::vector<double> t;  ///< row r, border j at t[r * borders + j]

  size_t rows() const { return s.size(); }
  /// Whether rows r and r + 1 are the two limits of a jump.
  bool is_jump(size_t r) const { return s[r + 1] - s[r] < 2.0 * kJumpEpsilon; }
  const double* row_t(size_t r) const { return t.data() + r * borders; }
};

/// Chooses the s samples of a section so that, between consecutive samples, every lane border
/// (and, on roads with a lateral shape, the surface between borders) stays within `tolerance`
/// of the straight segment joining its two samples. Always includes s0, s1 and the breakpoints;
/// `max_segment` > 0 caps the spacing.
SectionSamples sample_section(const SectionView& view, double tolerance, double max_segment);

}  // namespace corsa::xodr::detail
