#include "motion/route_lanes.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "corsa/core/strings.h"
#include "lanes/lane_follow.h"
#include "motion/route_chooser.h"
#include "motion/transition_shape.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

// Metres past a waypoint after which the next lane the route needs counts.
constexpr double kPassed = 0.01;

// A route step is in the lane section the entity drives in, on its side of the road (lanes on
// one side are driven the same way).
bool matches(const xodr::RouteStep& step, const LaneFollow& lane) {
  return step.lane.road == lane.road && step.lane.section == lane.section &&
         (step.lane.lane > 0) == (lane.lane > 0);
}

// Index of the last step of the group of consecutive steps in the same section as `first`.
size_t group_end(const RoutePlan& plan, size_t first) {
  const xodr::LaneRef& ref = plan.steps[first].lane;
  size_t last = first;
  while (last + 1 < plan.steps.size()) {
    const xodr::LaneRef& next = plan.steps[last + 1].lane;
    if (next.road != ref.road || next.section != ref.section || (next.lane > 0) != (ref.lane > 0)) {
      break;
    }
    ++last;
  }
  return last;
}

void warn(SimState& state, const Entity& entity, const RoutePlan& plan, const std::string& why) {
  state.diagnostics.add_once(
      "route-lanes:" + entity.info.name,
      plan.source.warning("'" + entity.info.name + "' cannot follow its route '" + plan.name +
                          "': " + why +
                          "; it leaves the route and takes its lane's straightest successor "
                          "(it stops where there is none)"));
}

// Whether an entity off the route's lanes, in the section `exit` leaves the route from (a
// lateral action holds it in another lane, maybe across the centre line), is still carried on
// along the route at its lane's end: to the road of the step after `exit`, either as the lane's
// own successor or from the route's lane beside it (LaneChooser::redirect).
bool leads_on(const xodr::Map& map, const Entity& entity, const RoutePlan& plan, size_t exit) {
  const LaneFollow& lane = entity.lane;
  const xodr::RouteStep& here = plan.steps[exit];
  if (entity.chooser == nullptr || here.lane.road != lane.road ||
      here.lane.section != lane.section) {
    return false;
  }
  const xodr::LaneGraph& graph = map.lane_graph();
  const auto ends = graph.ends(lane.node, lane.dir < 0);
  if (ends.empty()) {
    return false;
  }
  if (entity.chooser->redirect(map, lane, ends)) {
    return true;
  }
  const xodr::LaneEnd& next = ends[entity.chooser->choose(map, lane, ends)];
  return graph.info(next.node).lane.road == plan.steps[exit + 1].lane.road;
}

// Finds the route steps of the section the entity is in (RouteProgress::step), from where it
// was along the route. Warns once when it has left the route before its end (not while it is
// still carried on along the route at its lane's end).
bool locate(SimState& state, Entity& entity, const RoutePlan& plan) {
  RouteProgress& progress = entity.route_progress;
  const auto& steps = plan.steps;
  if (progress.joined && progress.step < steps.size() &&
      matches(steps[progress.step], entity.lane)) {
    return true;
  }
  for (size_t i = progress.joined ? progress.step + 1 : 0; i < steps.size(); ++i) {
    if (matches(steps[i], entity.lane)) {
      progress.step = i;
      progress.joined = true;
      return true;
    }
  }
  if (progress.joined && !progress.lost && progress.step < steps.size()) {
    const size_t last = group_end(plan, progress.step);
    if (last + 1 < steps.size() && !leads_on(*state.map, entity, plan, last)) {
      progress.lost = true;
      const xodr::Map& map = *state.map;
      warn(state, entity, plan,
           "it left road '" + map.road(steps[last].lane.road).id +
               "' from a lane that does not lead on to road '" +
               map.road(steps[last + 1].lane.road).id + "' (lane " +
               std::to_string(steps[last].lane.lane) + " does)");
    }
  }
  return false;
}

// The next lane the route needs in this section: on a waypoint's lane at the waypoint, on the
// lane that leads on at the section's end. `ahead` is the distance (m) to it along the lane.
struct Need {
  int lane = 0;
  double ahead = 0.0;
};

std::optional<Need> next_need(const RoutePlan& plan, size_t first, const LaneFollow& lane) {
  const size_t last = group_end(plan, first);
  for (size_t k = first; k <= last; ++k) {
    const bool waypoint =
        std::binary_search(plan.waypoint_steps.begin(), plan.waypoint_steps.end(), k);
    const bool exit = k == last && last + 1 < plan.steps.size();
    if (!waypoint && !exit) {
      continue;
    }
    const double ahead = (plan.steps[k].s_to - lane.s) * lane.dir;
    if (ahead > -kPassed) {
      return Need{plan.steps[k].lane.lane, std::max(0.0, ahead)};
    }
  }
  return std::nullopt;
}

// Sets this step's lateral command of the lane change under way (progress by the distance
// driven at the end of the step, which travels its end speed times dt).
void continue_change(Entity& entity, double dt) {
  RouteProgress& progress = entity.route_progress;
  const double travelled =
      entity.longitudinal_distance - progress.start_distance + std::abs(entity.speed_command) * dt;
  const double p = progress.length > 0.0 ? std::min(1.0, travelled / progress.length) : 1.0;
  entity.lateral_command = progress.from + shape_value(xosc::DynamicsShape::kSinusoidal, p) *
                                               (progress.to - progress.from);
  progress.last_command = entity.lateral_command;
  progress.changing = p < 1.0;
}

// Starts a lane change to the neighbour toward `need`. False when there is none to change to
// (the centre lane lies between, or the neighbour is not a drivable lane).
bool start_change(const xodr::Map& map, Entity& entity, const Need& need) {
  LaneFollow& lane = entity.lane;
  const int next = step_lane_id(lane.lane, need.lane > lane.lane ? 1 : -1);
  if ((next > 0) != (lane.lane > 0)) {
    return false;
  }
  const auto node = map.lane_graph().find(xodr::LaneRef{lane.road, lane.section, next});
  const auto own_center = followed_lane_center_t(map, lane, lane.lane);
  const auto next_center = followed_lane_center_t(map, lane, next);
  if (!node || !own_center || !next_center ||
      !xodr::is_drivable(map.lane_graph().info(*node).type)) {
    return false;
  }
  const double t_now = *own_center + lane.dir * lane.lateral;
  const int changes = std::abs(need.lane - lane.lane);  // this one and those after it
  lane.lane = next;
  lane.node = *node;
  lane.lateral = (t_now - *next_center) * lane.dir;
  RouteProgress& progress = entity.route_progress;
  progress.from = lane.lateral;
  progress.to = entity.lateral_command;  // the offset the actions asked for, kept
  progress.start_distance = entity.longitudinal_distance;
  const double speed = std::max(
      {std::abs(entity.state().speed), std::abs(entity.speed_command), kRouteLaneChangeMinSpeed});
  const double room = need.ahead / std::max(1, changes);
  progress.length =
      std::clamp(room, speed * kRouteLaneChangeShortestTime, speed * kRouteLaneChangeTime);
  progress.changing = true;
  return true;
}

void follow_route(SimState& state, Entity& entity, const RoutePlan& plan, double dt) {
  RouteProgress& progress = entity.route_progress;
  // A lateral action, a pose command or a teleport (a lateral command we did not give) takes
  // over: the lane change ends where the entity is.
  const bool blocked = entity.owners[1] != nullptr || entity.pose_command.has_value();
  if (progress.changing && (blocked || entity.lateral_command != progress.last_command)) {
    progress.changing = false;
  }
  if (!entity.lane.on_road || !locate(state, entity, plan)) {
    return;
  }
  if (progress.changing) {
    continue_change(entity, dt);
    return;
  }
  if (blocked) {
    return;
  }
  const auto need = next_need(plan, progress.step, entity.lane);
  if (!need || need->lane == entity.lane.lane) {
    return;
  }
  if (!start_change(*state.map, entity, *need)) {
    warn(state, entity, plan,
         "it cannot change from lane " + std::to_string(entity.lane.lane) + " to lane " +
             std::to_string(need->lane) + " of road '" + state.map->road(entity.lane.road).id +
             "' at s = " + format_double(entity.lane.s));
    return;
  }
  continue_change(entity, dt);
}

}  // namespace

[[gnu::hot]] void follow_route_lanes(SimState& state, const MotionContext& motion) {
  // Only a route of AssignRouteAction or AcquirePositionAction (a RouteChooser) is followed here:
  // until one is given, no entity's record is read (with hundreds of vehicles, each is a line
  // the step's other passes have pushed out of the cache).
  if (state.map == nullptr || !state.routes_assigned) {
    return;
  }
  for (Entity& entity : state.world.entities) {
    if (!entity.route || !entity.state().placed) {
      continue;
    }
    if (const auto* chooser = dynamic_cast<const RouteChooser*>(entity.route.get())) {
      follow_route(state, entity, chooser->plan(), motion.dt);
    }
  }
}

}  // namespace corsa::engine::detail
