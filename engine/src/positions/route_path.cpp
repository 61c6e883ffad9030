#include "positions/route_path.h"

#include <cmath>
#include <numbers>
#include <type_traits>

#include "core/sim_state.h"
#include "corsa/core/strings.h"
#include "motion/lane_follow.h"
#include "positions/position_common.h"

namespace corsa::engine::detail {

RoutePath build_route_path(const xosc::Route& route, const SimState& state,
                           std::optional<uint32_t> self) {
  const xodr::Map& map = need_map(state, route.source, "Route");
  std::vector<xodr::LanePoint> points;
  for (const xosc::Waypoint& waypoint : route.waypoints) {
    const ResolvedPosition at = resolve_position(waypoint.position, state, self);
    if (!at.road || !at.road->lane) {
      fail(waypoint.source, "route waypoint is not on a lane of the road network");
    }
    points.push_back(xodr::LanePoint{at.road->road, *at.road->lane, at.road->s});
  }
  RoutePath path;
  for (size_t i = 1; i < points.size(); ++i) {
    const auto leg = xodr::find_route(map, points[i - 1], points[i]);
    if (!leg) {
      fail(route.waypoints[i].source, "route '" + route.name + "': waypoint " +
                                          std::to_string(i + 1) + " cannot be reached from " +
                                          "waypoint " + std::to_string(i));
    }
    for (const xodr::RouteStep& step : leg->steps) {
      path.steps.push_back(step);
      path.length += std::abs(step.s_to - step.s_from);
    }
  }
  return path;
}

RouteLocation locate_on_route(const RoutePath& path, double path_s) {
  RouteLocation out;
  double remaining = std::max(0.0, path_s);
  for (size_t i = 0; i < path.steps.size(); ++i) {
    const xodr::RouteStep& step = path.steps[i];
    const double length = std::abs(step.s_to - step.s_from);
    out.lane = step.lane;
    out.dir = step.s_to >= step.s_from ? 1 : -1;
    if (remaining <= length || i + 1 == path.steps.size()) {
      out.s = step.s_from + out.dir * std::min(remaining, length);
      return out;
    }
    remaining -= length;
  }
  return out;
}

ResolvedPosition resolve_route_position(const xosc::RoutePosition& position, const SimState& state,
                                        std::optional<uint32_t> self) {
  const xodr::Map& map = need_map(state, position.source, "RoutePosition");
  if (!position.route) {
    fail(position.source, "RoutePosition without a route");
  }
  return std::visit(
      [&](const auto& in_route) -> ResolvedPosition {
        using T = std::decay_t<decltype(in_route)>;
        if constexpr (std::is_same_v<T, xosc::PositionOfCurrentEntity>) {
          const Entity& entity = need_entity(state, in_route.entity_ref, in_route.source);
          ResolvedPosition out;
          const Pose& p = entity.state.pose;
          out.pose = {p.x, p.y, p.z, p.h, p.p, p.r};
          if (entity.state.road) {
            out.road = RoadPoint{entity.state.road->road, entity.state.road->s,
                                 entity.state.road->t, entity.state.road->lane};
          }
          return out;
        } else {
          const RoutePath path = build_route_path(*position.route, state, self);
          if (path.steps.empty()) {
            fail(position.source, "the route has no length");
          }
          const RouteLocation at = locate_on_route(path, in_route.path_s);
          double t = 0.0;
          std::optional<int> lane;
          if constexpr (std::is_same_v<T, xosc::PositionInRoadCoordinates>) {
            t = in_route.t;
          } else {
            lane = parse_lane_id(in_route.lane_id, in_route.source);
            t = need_lane_center(map, at.lane.road, at.s, *lane, in_route.source) +
                in_route.lane_offset.value_or(0.0);
          }
          ResolvedPosition out = on_road(map, at.lane.road, at.s, t, lane, position.orientation);
          if (!position.orientation) {
            // Without an orientation the entity faces along the route.
            out.pose.h = wrap_angle(map.reference(at.lane.road, at.s).hdg +
                                    (at.dir < 0 ? std::numbers::pi : 0.0));
          }
          return out;
        }
      },
      position.in_route);
}

}  // namespace corsa::engine::detail
