#pragma once

// Shortest route between two lane positions over the lane graph (lane centre lengths), driving
// each lane only in its travel direction, with optional changes between adjacent drivable lanes
// of the same section and direction.

#include <optional>
#include <vector>

#include "corsa/xodr/lane_graph.h"
#include "corsa/xodr/map.h"

namespace corsa::xodr {

struct RouteOptions {
  /// Extra cost (m) of one lane change, so that of two equally long routes the one with fewer
  /// changes wins.
  double lane_change_cost = 5.0;
  bool allow_lane_changes = true;
  /// Per lane node (LaneGraph index): factor on the metres driven on that lane (empty: 1), e.g.
  /// 1 / speed limit for the fastest route. Factors must be positive.
  std::vector<double> lane_cost_scale;
  /// Per lane node: extra cost (>= 0) of entering that lane over a lane end (empty: none), e.g.
  /// a penalty on junction lanes for the route through the fewest intersections.
  std::vector<double> lane_entry_cost;
  /// Drivable lanes may be driven either way, against their direction of travel too (wrong-way
  /// driving; OpenSCENARIO's routes do not forbid it), for a route that has no other way.
  bool against_traffic = false;
};

/// A place on a lane: road index, lane id, road s.
struct LanePoint {
  uint32_t road = 0;
  int lane = 0;
  double s = 0.0;
};

/// One piece of a route: drive along `lane` from road s `s_from` to `s_to` (s_to < s_from when
/// the lane runs in -s). A lane change happens between two consecutive steps whose lanes are
/// neighbours (`lane_change` set on the second).
struct RouteStep {
  LaneRef lane;
  double s_from = 0.0;
  double s_to = 0.0;
  bool lane_change = false;
};

struct Route {
  std::vector<RouteStep> steps;
  double length = 0.0;  ///< metres driven along lane centres (lane change costs excluded)
  int lane_changes = 0;
};

/// The shortest route from `from` to `to`, or nothing when `to` cannot be reached (or either
/// point is not on a drivable lane). Throws nothing on unreachable targets.
std::optional<Route> find_route(const Map& map, const LanePoint& from, const LanePoint& to,
                                const RouteOptions& options = {});

}  // namespace corsa::xodr
