#include "positions/route_path.h"

#include <cmath>
#include <numbers>
#include <type_traits>

#include "corsa/core/strings.h"
#include "geometry/angle.h"
#include "positions/position_common.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {

namespace {

// Speed (m/s) assumed on a road without a speed record, for the fastest route: an urban limit.
constexpr double kDefaultSpeed = 50.0 / 3.6;
// Cost (in metres of the shortest-route measure) of entering a junction, for the route through
// the fewest intersections: larger than any detour on a map.
constexpr double kJunctionEntryCost = 1.0e6;

// Speed limit (m/s) of a lane node: the lane's own speed record, else the road type's.
double node_speed(const xodr::Map& map, const xodr::LaneGraph::NodeInfo& info) {
  const xodr::Road& road = map.road(info.lane.road);
  const xodr::LaneSection& section = road.lane_sections[info.lane.section];
  for (const xodr::Lane& lane : section.lanes) {
    if (lane.id == info.lane.lane && !lane.speeds.empty() && lane.speeds.front().max_speed > 0.0) {
      return lane.speeds.front().max_speed;
    }
  }
  double speed = kDefaultSpeed;
  for (const xodr::RoadType& type : road.types) {
    if (type.s <= info.s_start + 1e-9 && type.max_speed && *type.max_speed > 0.0) {
      speed = *type.max_speed;
    }
  }
  return speed;
}

// SplitMix64 (Steele et al. 2014): a small, portable, seedable generator, so that a random
// route is the same on every platform for the same seed.
uint64_t split_mix(uint64_t& state) {
  uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// The warning for a leg that drives some lane against its direction of travel, naming the
// first such lane.
void warn_against_traffic(const SimState& state, const xosc::Route& route, size_t leg_index,
                          const xodr::Map& map, const xodr::Route& leg) {
  const xodr::LaneGraph& graph = map.lane_graph();
  for (const xodr::RouteStep& step : leg.steps) {
    const auto node = graph.find(step.lane);
    if (!node || step.s_to == step.s_from) continue;
    const xodr::TravelDirection direction = graph.info(*node).direction;
    const bool forward = step.s_to > step.s_from;
    if (direction == xodr::TravelDirection::kBoth ||
        (direction == xodr::TravelDirection::kForward) == forward) {
      continue;
    }
    const xosc::Source& where = route.waypoints[leg_index].source;
    const std::string text =
        "route '" + route.name + "': waypoint " + std::to_string(leg_index + 1) +
        " can be reached from waypoint " + std::to_string(leg_index) +
        " only against the direction of travel (lane " + std::to_string(step.lane.lane) +
        " of road " + map.road(step.lane.road).id + " driven toward " + (forward ? "+s" : "-s") +
        "); the route drives it so";
    state.diagnostics.add_once(
        "route-against-traffic:" + where.file_name() + ":" + std::to_string(where.line),
        where.warning(text));
    return;
  }
}

}  // namespace

xodr::RouteOptions route_options(const xodr::Map& map, xosc::RouteStrategy strategy,
                                 uint64_t seed) {
  xodr::RouteOptions options;
  const xodr::LaneGraph& graph = map.lane_graph();
  switch (strategy) {
    case xosc::RouteStrategy::kShortest:
      break;
    case xosc::RouteStrategy::kFastest:
      // Cost in seconds at each lane's speed limit (times a speed scale so that the lane change
      // cost keeps its meaning in metres at the default speed).
      options.lane_cost_scale.resize(graph.size());
      for (xodr::LaneNode node = 0; node < graph.size(); ++node) {
        options.lane_cost_scale[node] = kDefaultSpeed / node_speed(map, graph.info(node));
      }
      break;
    case xosc::RouteStrategy::kLeastIntersections:
      options.lane_entry_cost.resize(graph.size());
      for (xodr::LaneNode node = 0; node < graph.size(); ++node) {
        options.lane_entry_cost[node] =
            map.road(graph.info(node).lane.road).in_junction() ? kJunctionEntryCost : 0.0;
      }
      break;
    case xosc::RouteStrategy::kRandom: {
      // Every lane's length weighted by a factor drawn uniformly from [1, 4): the shortest
      // route under random weights, reproducible with the seed.
      uint64_t state = seed;
      options.lane_cost_scale.resize(graph.size());
      for (xodr::LaneNode node = 0; node < graph.size(); ++node) {
        const double u = static_cast<double>(split_mix(state) >> 11) * 0x1.0p-53;
        options.lane_cost_scale[node] = 1.0 + 3.0 * u;
      }
      break;
    }
  }
  return options;
}

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
    // §6.6: a waypoint's routeStrategy is how to reach it from the previous one. Random draws
    // depend on the run seed and the leg, so two legs do not share their weights.
    xodr::RouteOptions options =
        route_options(map, route.waypoints[i].route_strategy, state.options.seed * 1000003u + i);
    auto leg = xodr::find_route(map, points[i - 1], points[i], options);
    if (!leg) {
      // §6.8.2 leaves the way between waypoints to the simulator and does not forbid driving a
      // lane against its direction of travel; esmini routes along roads either way (its
      // route_lane_change drives a left lane toward the junction). Only when no route follows
      // the lanes' directions.
      options.against_traffic = true;
      leg = xodr::find_route(map, points[i - 1], points[i], options);
      if (leg) {
        warn_against_traffic(state, route, i, map, *leg);
      }
    }
    if (!leg) {
      fail(route.waypoints[i].source, "route '" + route.name + "': waypoint " +
                                          std::to_string(i + 1) + " cannot be reached from " +
                                          "waypoint " + std::to_string(i));
    }
    for (const xodr::RouteStep& step : leg->steps) {
      path.steps.push_back(step);
      path.length += std::abs(step.s_to - step.s_from);
    }
    if (!path.steps.empty()) {
      path.waypoint_steps.push_back(path.steps.size() - 1);
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

namespace {

// A RoutePosition FromCurrentEntity: where the entity is. 1.3 RoutePosition: the relative
// reference context refers "to the orientation of the reference entity"; a missing Orientation is
// a relative one of 0, the entity's own.
ResolvedPosition route_position_of_entity(const xosc::RoutePosition& position,
                                          const xosc::PositionOfCurrentEntity& in_route,
                                          const SimState& state) {
  const Entity& entity = need_entity(state, in_route.entity_ref, in_route.source);
  ResolvedPosition out;
  const Pose& p = entity.state().pose;
  out.pose = {p.x, p.y, p.z, p.h, p.p, p.r};
  orient_on_road(out.pose, position.orientation, false);
  if (entity.state().road) {
    out.road = RoadPoint{entity.state().road->road, entity.state().road->s, entity.state().road->t,
                         entity.state().road->lane};
  }
  return out;
}

// The Orientation of a RoutePosition in road coordinates, for on_road in the road frame: a
// missing one is a relative one of 0, facing the road's +s whichever way the route runs there,
// under either reading (esmini's SetRouteRefRoadCoord: a missing h as 0 from +s, never along
// the route). esmini turns any Orientation given in road coordinates from the road's +s, an
// absolute one too.
xosc::Orientation route_road_orientation(const std::optional<xosc::Orientation>& given,
                                         bool esmini) {
  xosc::Orientation orientation = given.value_or(xosc::Orientation{});
  if (!given || esmini) {
    orientation.type = xosc::ReferenceContext::kRelative;
  }
  return orientation;
}

// esmini's reading of a RoutePosition in lane coordinates (its OSCPositionRoute and reader, with
// esmini's default `--align_routepositions` off): a given Orientation, of either type, turns from
// the lane's direction of travel (an absolute one too); a missing one is a relative pi from the
// road's +s on a lane of positive id, else 0, whatever the map's traffic rule says.
ResolvedPosition esmini_route_lane_position(const xodr::Map& map, uint32_t road, double s, double t,
                                            int lane,
                                            const std::optional<xosc::Orientation>& given) {
  if (given) {
    xosc::Orientation relative = *given;
    relative.type = xosc::ReferenceContext::kRelative;
    return on_road(map, road, s, t, lane, relative, OrientationFrame::kLane);
  }
  xosc::Orientation from_s;
  from_s.type = xosc::ReferenceContext::kRelative;
  from_s.h = lane > 0 ? std::numbers::pi : 0.0;
  return on_road(map, road, s, t, lane, from_s, OrientationFrame::kRoad);
}

}  // namespace

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
          return route_position_of_entity(position, in_route, state);
        } else {
          const RoutePath path = build_route_path(*position.route, state, self);
          if (path.steps.empty()) {
            fail(position.source, "the route has no length");
          }
          const RouteLocation at = locate_on_route(path, in_route.path_s);
          // 1.3 RoutePosition: "The relative reference context refers to the referenced road's s
          // and t coordinates, to the current lane's s and t coordinates [...]. Missing
          // Orientation property is interpreted as the relative reference context with
          // Heading=Pitch=Roll=0." In road coordinates a relative heading turns from the road's
          // +s, and a missing one faces it, whichever way the route runs there; in lane
          // coordinates from the lane's direction of travel (a lane's s-axis as for a
          // LanePosition).
          if constexpr (std::is_same_v<T, xosc::PositionInRoadCoordinates>) {
            return on_road(map, at.lane.road, at.s, in_route.t, std::nullopt,
                           route_road_orientation(position.orientation, esmini_reading(state)));
          } else {
            const int lane = parse_lane_id(in_route.lane_id, in_route.source);
            const double t = need_lane_center(map, at.lane.road, at.s, lane, in_route.source) +
                             in_route.lane_offset.value_or(0.0);
            if (esmini_reading(state)) {
              return esmini_route_lane_position(map, at.lane.road, at.s, t, lane,
                                                position.orientation);
            }
            // Without an Orientation: the lane's direction of travel, which is along the route
            // except where the route drives the lane against its traffic; an absolute one is
            // the world's heading.
            return on_road(map, at.lane.road, at.s, t, lane, position.orientation,
                           OrientationFrame::kLane);
          }
        }
      },
      position.in_route);
}

}  // namespace corsa::engine::detail
