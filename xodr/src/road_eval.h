#pragma once

// Record lookups and lane-border arithmetic shared by Map, the spatial index and the lane graph.
// Private to corsa_xodr. Records are in s order (Map::build checks it), so every lookup is a
// binary search.

#include <algorithm>
#include <cstddef>
#include <vector>

#include "corsa/xodr/map.h"
#include "corsa/xodr/model.h"

namespace corsa::xodr::detail {

/// The most lanes one section may have (Map::build rejects more), so spans fit on the stack.
inline constexpr size_t kMaxLanesPerSection = 128;

/// Index of the last record whose start (given by `start_of`) is <= s; 0 when s precedes all.
template <typename T, typename StartOf>
size_t record_index(const std::vector<T>& records, double s, StartOf start_of) {
  const auto it = std::upper_bound(records.begin(), records.end(), s,
                                   [&](double value, const T& r) { return value < start_of(r); });
  return it == records.begin() ? 0 : static_cast<size_t>(it - records.begin()) - 1;
}

/// Value of a piecewise cubic with absolute (road) s starts (elevation, superelevation,
/// laneOffset); 0 without records and before the first one, the standard's default.
inline double poly_value(const std::vector<Poly3>& records, double s) {
  if (records.empty() || s < records.front().s) {
    return 0.0;
  }
  return records[record_index(records, s, [](const Poly3& p) { return p.s; })].value(s);
}
inline double poly_slope(const std::vector<Poly3>& records, double s) {
  if (records.empty() || s < records.front().s) {
    return 0.0;
  }
  return records[record_index(records, s, [](const Poly3& p) { return p.s; })].slope(s);
}

/// Reference line point with its unit tangent (tx, ty), from the cached record headings.
struct RefFrame {
  RefPoint point;
  double tx = 1.0;
  double ty = 0.0;
};

class PoseTable;

/// Map internals for corsa_xodr's hot paths.
struct MapAccess {
  static RefFrame reference_frame(const Map& map, size_t road, double s);
  /// The map's packed road records (pose_table.h).
  static const PoseTable& poses(const Map& map);
  /// section_lane_offset, read from the map's packed tables (pose_table.h, span_table.h).
  static double section_lane_offset(const Map& map, size_t road, size_t section, double s);
};

/// laneOffset for the lanes of section `section` at s. Inside the section this is laneOffset(s);
/// at the section's end it is the limit from the left: files (CARLA) often start a new laneOffset
/// record exactly where the next section starts, and that record belongs to the next section's
/// lanes.
double section_lane_offset(const Map& map, size_t road, size_t section, double s);

/// Width or border polynomial at ds from the section start (records hold sOffset in `s`).
inline double offset_poly_value(const std::vector<Poly3>& records, double ds) {
  if (records.empty()) {
    return 0.0;
  }
  return records[record_index(records, ds, [](const Poly3& p) { return p.s; })].value(ds);
}

/// Spans of every non-centre lane of `section` at road s (left to right), given the laneOffset
/// there. OpenDRIVE 1.8 §9.5: a lane's inner border is the outer border of its inner neighbour;
/// the outer border is inner + width (left) or inner - width (right), or the <border> cubic
/// when the lane has no <width> (widths win when both are present, §9.5.2). A negative width
/// (rounding at a lane's start or end) counts as 0. Returns the number of spans written.
size_t compute_spans(const LaneSection& section, double s, double offset, LaneSpan* out);

/// The span of lane `lane_id` of `section` at s, as compute_spans makes it (the same arithmetic
/// in the same order), evaluating only the lanes from the centre out to it. False when the
/// section has no such lane.
bool compute_span(const LaneSection& section, double s, double offset, int lane_id, LaneSpan& out);

/// The lane of `section` containing t at s (walking outward from the centre lane on t's side,
/// so only the lanes up to it are evaluated; a shared border belongs to the inner lane). False
/// when t is outside every lane of that side.
bool find_lane_at(const LaneSection& section, double s, double offset, double t, LaneSpan& out);

/// The lane of `section` nearest to lateral position t at s (gap 0 when t is inside it), among
/// lanes of positive width (and drivable ones only, if asked). False when there is none.
struct NearestLane {
  int lane = 0;
  double gap = 0.0;            ///< lateral distance from t to the lane (m), 0 inside
  double center_offset = 0.0;  ///< |t - lane centre| (m)
};
bool nearest_lane(const LaneSection& section, double s, double offset, double t, bool drivable_only,
                  NearestLane& out);

/// Index of the centre lane in section.lanes (lanes are sorted by descending id).
size_t center_index(const LaneSection& section);

}  // namespace corsa::xodr::detail
