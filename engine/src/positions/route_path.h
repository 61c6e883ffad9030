#pragma once

// A Route (OpenSCENARIO 1.3 §6.6) laid onto the map: consecutive waypoints joined by the
// shortest lane route (xodr::find_route), giving a path along which RoutePosition's pathS is
// measured. AssignRouteAction drives along the same path (motion/route_chooser.h).

#include <cstdint>
#include <optional>
#include <vector>

#include "corsa/xodr/route.h"
#include "corsa/xosc/trajectories.h"
#include "positions/position_resolver.h"

namespace corsa::engine::detail {

struct SimState;

struct RoutePath {
  std::vector<xodr::RouteStep> steps;
  /// Per waypoint after the first: index of the step that ends at it.
  std::vector<size_t> waypoint_steps;
  double length = 0.0;  ///< m, sum of the steps' |s_to - s_from|
};

/// Options of xodr::find_route for a routeStrategy (§6.6): shortest by lane length; fastest by
/// time at the speed limits (lane speed records, else the road type's, else 50 km/h);
/// leastIntersections with a penalty on entering a junction; random with lane weights drawn
/// from `seed`.
xodr::RouteOptions route_options(const xodr::Map& map, xosc::RouteStrategy strategy, uint64_t seed);

/// Lays `route` onto the map, each leg by its destination waypoint's routeStrategy. Throws
/// InputError (located at the route) when a waypoint is not on a lane or two waypoints are not
/// connected.
RoutePath build_route_path(const xosc::Route& route, const SimState& state,
                           std::optional<uint32_t> self);

/// Where pathS lies on the path: road, s and the lane of the step.
struct RouteLocation {
  xodr::LaneRef lane;
  double s = 0.0;
  int dir = 1;  ///< +1 when the path runs toward +s there
};
RouteLocation locate_on_route(const RoutePath& path, double path_s);

ResolvedPosition resolve_route_position(const xosc::RoutePosition& position, const SimState& state,
                                        std::optional<uint32_t> self);

}  // namespace corsa::engine::detail
