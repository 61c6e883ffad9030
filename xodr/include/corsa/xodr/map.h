#pragma once

// A loaded OpenDRIVE map: read-only after Map::build, safe to share between threads. Holds the
// MapData plus what queries need: road lookup by id, the lane graph and a spatial index for
// world -> lane queries. All s are road s (metres from the road start), t is lateral (metres, to
// the left of the reference line), headings counter-clockwise from +x (OpenDRIVE 1.8 §2.3).
//
// Road arguments are indices into data().roads (find_road() maps an id to one). s outside
// [0, length] is clamped to the road.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/xodr/geometry.h"
#include "corsa/xodr/lane_graph.h"
#include "corsa/xodr/lane_ref.h"
#include "corsa/xodr/model.h"

namespace corsa::xodr {

namespace detail {
struct MapAccess;  // corsa_xodr's own fast paths (spatial index, lane graph)
}  // namespace detail

/// Position and orientation in map coordinates: metres; heading, pitch, roll in radians.
/// Pitch follows ISO 8855 / OpenSCENARIO: positive is nose down, so an uphill road has negative
/// pitch. Roll is the superelevation: positive lowers the right side (-t).
struct WorldPose {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
  double h = 0.0;
  double p = 0.0;
  double r = 0.0;
};

/// Lateral extent of one lane at some s: t of its inner border (the side of the centre lane) and
/// of its outer border, in metres from the reference line (laneOffset included).
struct LaneSpan {
  int id = 0;
  double t_inner = 0.0;
  double t_outer = 0.0;

  double width() const { return t_outer > t_inner ? t_outer - t_inner : t_inner - t_outer; }
  double t_center() const { return 0.5 * (t_inner + t_outer); }
  double t_min() const { return t_inner < t_outer ? t_inner : t_outer; }
  double t_max() const { return t_inner < t_outer ? t_outer : t_inner; }
};

/// Where a world point is on the map (the answer of Map::locate).
struct LanePosition {
  uint32_t road = 0;
  uint32_t section = 0;
  int lane = 0;  ///< the lane containing the point, or the nearest one (then `distance` > 0)
  double s = 0.0;
  double t = 0.0;
  /// Horizontal distance (m) from the point to the nearest lane: 0 when it lies on one.
  double distance = 0.0;
  double heading = 0.0;  ///< reference-line heading at s (rad)

  LaneRef lane_ref() const { return LaneRef{road, section, lane}; }
};

struct LocateOptions {
  /// Points farther than this (m) from every lane give no answer.
  double max_distance = 5.0;
  /// Only lanes vehicles drive on (driving, entry/exit, ramps, bidirectional, ...).
  bool drivable_only = false;
  /// The point's height (m), when known: where roads are stacked (an underpass below a bridge),
  /// of the lanes at (x, y) the one whose surface is nearest this height wins (heights closer
  /// than 1 m count as the same level, so overlapping junction lanes rank as without z).
  std::optional<double> z;
};

struct BuildOptions {
  /// Largest gap (m) / heading jump (rad) between consecutive planView records tolerated
  /// silently; larger ones are warned about (once per road).
  double max_joint_gap = 0.01;
  double max_joint_heading = 0.01;
};

class Map {
 public:
  /// Checks and indexes `data`: sorts nothing, but verifies that records are in s order, that
  /// every road/junction reference exists, that geometry lengths add up (warning otherwise) and
  /// that consecutive planView records join (gap/heading warnings); builds the lane graph. The
  /// spatial index is built by the first locate (thread-safe), so maps that are never queried by
  /// world point do not pay for it. Throws corsa::InputError (located at the offending element)
  /// on bad data.
  static Map build(MapData data, corsa::Diagnostics& diagnostics, const BuildOptions& options = {});
  /// parse_xodr + build.
  static Map load(const std::filesystem::path& path, corsa::Diagnostics& diagnostics,
                  const BuildOptions& options = {});

  Map(Map&&) noexcept;
  Map& operator=(Map&&) noexcept;
  ~Map();

  const MapData& data() const;
  size_t road_count() const;
  const Road& road(size_t road) const;
  std::optional<size_t> find_road(std::string_view id) const;
  size_t junction_count() const;
  const Junction& junction(size_t junction) const;
  std::optional<size_t> find_junction(std::string_view id) const;

  // --- reference line and road profile --------------------------------------------------------

  /// Reference line point at s (planView, §7).
  RefPoint reference(size_t road, double s) const;
  /// The last planView record of `road` starting at or before s (s not clamped to the road),
  /// nullptr when s precedes them all; read from the map's packed copy of the records.
  const Geometry* plan_record_at(size_t road, double s) const;
  /// Elevation z(s) (m) and its slope dz/ds (§8.4.1).
  double elevation(size_t road, double s) const;
  double elevation_slope(size_t road, double s) const;
  /// Superelevation roll (rad) at s (§8.4.2).
  double superelevation(size_t road, double s) const;
  /// laneOffset (m): t of the centre lane at s (§9.3).
  double lane_offset(size_t road, double s) const;
  /// Height (m) of the lateralProfile shape at (s, t), 0 without <shape> records (§8.4.3).
  double shape_height(size_t road, double s, double t) const;
  /// (road, s, t, h) -> world pose: t along the reference line's normal, tilted by the
  /// superelevation roll, and h along the road surface normal; z includes elevation, the roll
  /// term and lateral shape. Heading is the reference line's, pitch from the elevation slope.
  WorldPose world_pose(size_t road, double s, double t, double h = 0.0) const;

  // --- lanes ----------------------------------------------------------------------------------

  /// Index of the lane section containing s (the last one starting at or before s).
  size_t section_index(size_t road, double s) const;
  /// Road s where section `section` ends (the next section's s, or the road length).
  double section_end(size_t road, size_t section) const;
  /// Spans of every lane of the section at s, ordered left to right (ids descending; the centre
  /// lane is left out). `out` is cleared first; reuse it to avoid allocations.
  void lane_spans(size_t road, double s, std::vector<LaneSpan>& out) const;
  /// Span of one lane at s, or nothing when the section at s has no such lane.
  std::optional<LaneSpan> lane_span(size_t road, double s, int lane_id) const;
  /// The same, evaluated in a given lane section (s may be its end, where section_index would
  /// already return the next section): what a lane's own end looks like.
  void lane_spans_in_section(size_t road, size_t section, double s,
                             std::vector<LaneSpan>& out) const;
  std::optional<LaneSpan> lane_span_in_section(size_t road, size_t section, double s,
                                               int lane_id) const;
  /// Whether every lane of the section has its outer border from width records (none from
  /// <border> records alone, §9.5.2): then the lanes of each side follow one another outward
  /// without overlapping. Kept per section at build, so that asking reads no Lane record.
  bool section_widths_only(size_t road, size_t section) const;
  /// The lane containing lateral position t at s (borders belong to the inner lane), or nothing
  /// when t is outside every lane.
  std::optional<int> lane_at(size_t road, double s, double t) const;
  /// The Lane record of a lane reference, or nullptr if it does not exist.
  const Lane* lane(const LaneRef& ref) const;

  // --- world -> lane --------------------------------------------------------------------------

  /// Nearest lane to world point (x, y), ignoring z: s from the projection onto the reference
  /// line, t the lateral offset (divided by cos(superelevation), so that world_pose(road, s, t)
  /// returns to the point). A point inside several lanes (overlapping junction roads) gets the
  /// one whose centre is nearest; ties go to the lower road index. Nothing when no lane is within
  /// options.max_distance.
  std::optional<LanePosition> locate(double x, double y, const LocateOptions& options = {}) const;

  /// A distance d (m, 0 <= d <= reach) such that locate has no answer at any point (x', y')
  /// with |x' - x| <= d and |y' - y| <= d, for any options whose max_distance is at most
  /// `max_distance`: no part of the index that such a query examines comes that near. 0 when
  /// the point is that near a lane (or is not finite). What a query examines bounds the answer:
  /// an off-road point that moves by less than d needs no search.
  double clear_of_lanes(double x, double y, double max_distance, double reach) const;

  /// Lane connectivity (successors, predecessors, neighbours) across sections, roads, junctions.
  const LaneGraph& lane_graph() const;

 private:
  friend struct detail::MapAccess;
  struct Impl;
  explicit Map(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace corsa::xodr
