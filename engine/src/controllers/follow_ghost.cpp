// esmini's followGhost controller and its ghost (controllers/follow_ghost.h).

#include "controllers/follow_ghost.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "controllers/controllers.h"
#include "controllers/esmini_vehicle.h"
#include "corsa/xodr/map.h"
#include "corsa/xosc/scenario.h"
#include "motion/placement.h"
#include "motion/pose_command.h"
#include "positions/position_resolver.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

constexpr double kGhostFullTurn = 2.0 * std::numbers::pi;
// esmini's vehicle model (its vehicle.cpp) as the followGhost controller sets it up.
constexpr double kFollowerMaxAcceleration = 10.0;  // m/s^2, also the speed loop's gain (1/s)
constexpr double kFollowerMaxSpeed = 100.0;        // m/s

void read_properties(SimState& state, const xosc::ObjectController& oc, GhostLink& link) {
  const xosc::Controller& c = oc.controller;
  link.headstart =
      nonnegative_property(state, c, "headstartTime", "followGhost").value_or(link.headstart);
  link.lookahead_speed = nonnegative_property(state, c, "lookaheadSpeed", "followGhost")
                             .value_or(link.lookahead_speed);
  link.min_lookahead_speed = nonnegative_property(state, c, "minLookaheadSpeed", "followGhost")
                                 .value_or(link.min_lookahead_speed);
  link.lookahead_steering = nonnegative_property(state, c, "lookaheadSteering", "followGhost")
                                .value_or(link.lookahead_steering);
  link.min_lookahead_steering =
      nonnegative_property(state, c, "minLookaheadSteering", "followGhost")
          .value_or(link.min_lookahead_steering);
  link.steering_speed_inertia =
      nonnegative_property(state, c, "steeringSpeedInertia", "followGhost")
          .value_or(link.steering_speed_inertia);
  for (const xosc::Property& property : c.properties.properties) {
    if (property.name != "followMode") continue;
    if (property.value == "position") {
      link.by_position = true;
    } else if (property.value != "time") {
      // esmini falls back to time too, with a message.
      state.diagnostics.add(
          property.source.warning("followGhost followMode '" + property.value +
                                  "' is neither time nor position: read as time"));
    }
  }
}

// How the follower's model is told where to go this step.
struct GhostAim {
  double speed = 0.0;                 // m/s
  double x = 0.0, y = 0.0;            // the steering aim, map frame
  std::optional<TrailPoint> jump_to;  // the ghost jumped there: the follower jumps too
};

// The trail's point `distance` m along it from sample `from`, not across a jump: the last sample
// before a jump, or the trail's end, holds.
TrailPoint trail_ahead(const std::vector<TrailPoint>& trail, size_t from, double distance) {
  size_t k = from;
  while (k + 1 < trail.size() && !trail[k + 1].jump && trail[k + 1].s < distance) ++k;
  if (k + 1 >= trail.size() || trail[k + 1].jump) return trail[k];
  const TrailPoint& a = trail[k];
  const TrailPoint& b = trail[k + 1];
  const double w = b.s > a.s ? std::clamp((distance - a.s) / (b.s - a.s), 0.0, 1.0) : 0.0;
  TrailPoint out = a;
  out.x = a.x + w * (b.x - a.x);
  out.y = a.y + w * (b.y - a.y);
  out.speed = a.speed + w * (b.speed - a.speed);
  out.s = distance;
  return out;
}

// Trail samples searched ahead of the last nearest one in position mode (50 s of trail): keeps a
// step's search bounded however long the run; the entity does not drive past that in one step.
constexpr size_t kNearestWindow = 250;

// Position mode (esmini's FOLLOW_MODE_POSITION): the trail point nearest the entity, searched
// from the last one on, then the speed and steering targets max(min, lookahead * speed) m ahead
// of it along the trail.
GhostAim position_target(GhostLink& link, double speed) {
  const auto& trail = link.trail;
  GhostFollower& car = link.follower;
  size_t best = car.follow_index;
  double best_s = trail[best].s;
  double best_distance = std::hypot(car.x - trail[best].x, car.y - trail[best].y);
  const size_t end = std::min(trail.size() - 1, car.follow_index + kNearestWindow);
  for (size_t k = car.follow_index; k < end; ++k) {
    if (trail[k + 1].jump) break;
    const TrailPoint& a = trail[k];
    const TrailPoint& b = trail[k + 1];
    const double ex = b.x - a.x, ey = b.y - a.y;
    const double length2 = ex * ex + ey * ey;
    const double u = length2 > 1e-12
                         ? std::clamp(((car.x - a.x) * ex + (car.y - a.y) * ey) / length2, 0.0, 1.0)
                         : 0.0;
    const double distance = std::hypot(car.x - (a.x + u * ex), car.y - (a.y + u * ey));
    if (distance < best_distance) {
      best = k;
      best_distance = distance;
      best_s = a.s + u * (b.s - a.s);
    }
  }
  car.follow_index = best;
  GhostAim target;
  // At the end of a stretch that a jump ends, the follower jumps after the ghost.
  size_t last = best;
  while (last + 1 < trail.size() && !trail[last + 1].jump) ++last;
  if (last + 1 < trail.size() && best_s >= trail[last].s - 1e-6) {
    target.jump_to = trail[last + 1];
    car.follow_index = last + 1;
    return target;
  }
  const TrailPoint at_speed = trail_ahead(
      trail, best, best_s + std::max(link.min_lookahead_speed, link.lookahead_speed * speed));
  const TrailPoint aim = trail_ahead(
      trail, best, best_s + std::max(link.min_lookahead_steering, link.lookahead_steering * speed));
  target.speed = at_speed.speed;
  target.x = aim.x;
  target.y = aim.y;
  return target;
}

// Time mode (esmini's default): the trail points lookahead s after the ghost's time of
// `follower_time` (the end of this step minus the head start).
GhostAim time_target(const SimState& state, double follower_time, double dt) {
  const GhostLink& link = *state.ghost;
  const auto& trail = link.trail;
  GhostAim target;
  // A jump of the ghost that the follower's time passed this step.
  const auto after = std::upper_bound(trail.begin(), trail.end(), follower_time - dt,
                                      [](double t, const TrailPoint& p) { return t < p.time; });
  for (auto it = after; it != trail.end() && it->time <= follower_time; ++it) {
    if (it->jump) {
      target.jump_to = *it;
      return target;
    }
  }
  target.speed =
      trail_at(state, follower_time + std::max(link.min_lookahead_speed, link.lookahead_speed))
          .speed;
  const TrailPoint aim = trail_at(
      state, follower_time + std::max(link.min_lookahead_steering, link.lookahead_steering));
  target.x = aim.x;
  target.y = aim.y;
  return target;
}

}  // namespace

bool is_follow_ghost(const xosc::ObjectController& oc) {
  return esmini_type(oc.controller) == "FollowGhostController";
}

void setup_ghost(SimState& state) {
  if (state.options.disable_controllers) {
    return;
  }
  const auto count = static_cast<uint32_t>(state.world.entities.size());
  for (uint32_t i = 0; i < count; ++i) {
    const Entity& entity = state.world.entities[i];
    if (entity.object == nullptr) continue;
    for (const xosc::ObjectController& oc : entity.object->controllers) {
      if (!is_follow_ghost(oc)) continue;
      if (state.ghost) {
        state.diagnostics.add(oc.source.warning(
            "only the first entity under followGhost gets a ghost (as in esmini); '" +
            entity.info.name + "' runs under a stand-in"));
        break;
      }
      GhostLink link;
      link.entity = i;
      read_properties(state, oc, link);
      link.headstart_ticks = state.time.ticks(link.headstart);
      EntityInfo info = entity.info;
      info.name += "_ghost";
      Entity ghost(std::move(info));
      ghost.object = nullptr;  // no controllers, no trailer of its own
      ghost.ghost = true;
      ghost.write_state().visible = false;
      link.ghost = static_cast<uint32_t>(state.world.entities.size());
      if (!state.world.by_name.emplace(ghost.info.name, link.ghost).second) {
        throw InputError(oc.source.error("the ghost of '" + entity.info.name +
                                         "' would be called '" + ghost.info.name +
                                         "', which another entity is called"));
      }
      state.world.entities.push_back(std::move(ghost));
      state.tick = -link.headstart_ticks;
      state.environment_tick = state.tick;
      state.ghost = std::move(link);
      break;
    }
  }
}

bool ghost_performs(const xosc::PrivateAction& action) {
  return std::holds_alternative<xosc::SpeedAction>(action) ||
         std::holds_alternative<xosc::SpeedProfileAction>(action) ||
         std::holds_alternative<xosc::LaneChangeAction>(action) ||
         std::holds_alternative<xosc::LaneOffsetAction>(action) ||
         std::holds_alternative<xosc::SynchronizeAction>(action) ||
         std::holds_alternative<xosc::FollowTrajectoryAction>(action) ||
         std::holds_alternative<xosc::AssignRouteAction>(action) ||
         std::holds_alternative<xosc::TeleportAction>(action);
}

bool ghost_meets(const xosc::EntityCondition& condition) {
  return std::holds_alternative<xosc::CollisionCondition>(condition) ||
         std::holds_alternative<xosc::ReachPositionCondition>(condition) ||
         std::holds_alternative<xosc::TraveledDistanceCondition>(condition) ||
         std::holds_alternative<xosc::SpeedCondition>(condition) ||
         std::holds_alternative<xosc::AccelerationCondition>(condition) ||
         std::holds_alternative<xosc::EndOfRoadCondition>(condition) ||
         std::holds_alternative<xosc::OffroadCondition>(condition) ||
         std::holds_alternative<xosc::StandStillCondition>(condition);
}

bool ghost_restarts_on(const xosc::Trigger& trigger, const SimState& state) {
  if (!state.ghost) return false;
  const std::string& entity = state.world.entities[state.ghost->entity].info.name;
  for (const xosc::ConditionGroup& group : trigger.groups) {
    for (const xosc::Condition& condition : group.conditions) {
      if (const auto* by_value = std::get_if<xosc::ByValueCondition>(&condition.kind)) {
        // The ghost meets a simulation time headstartTime earlier; any other value it cannot.
        if (!std::holds_alternative<xosc::SimulationTimeCondition>(*by_value)) return true;
        continue;
      }
      const auto& by_entity = std::get<xosc::ByEntityCondition>(condition.kind);
      if (!ghost_meets(by_entity.condition)) return true;
      for (const std::string& name : by_entity.triggering_entities.entity_refs) {
        if (name != entity) return true;  // another entity's condition, met in its own time
      }
    }
  }
  return false;
}

bool restart_ghost(SimState& state) {
  GhostLink& link = *state.ghost;
  Entity& entity = state.world.entities[link.entity];
  Entity& ghost = state.world.entities[link.ghost];
  // The ghost takes the entity's place, lane and speed (a teleport; the storyboard has stopped
  // what ran on it), and the distance it has travelled: a TraveledDistanceCondition on the entity
  // reads the ghost, which must not count the jump back nor the ticks it runs again.
  const bool visible = ghost.state().visible;
  EntityState& ghost_state = ghost.write_state();
  ghost_state = entity.state();
  ghost_state.visible = visible;
  ghost.straight_travel = entity.straight_travel;
  mark_jump(ghost);
  ghost.lane = entity.lane;
  ghost.speed_command = entity.state().speed;
  ghost.lateral_command = entity.lateral_command;
  ghost.pose_command.reset();
  if (state.now() <= 1e-9) {
    return false;  // during the head start: a teleport only (esmini's restart waits for time 0)
  }
  link.trail.clear();
  link.follower.follow_index = 0;
  // A restart during a replay runs on to the latest tick the run had reached (esmini's true time).
  link.replay_end_tick = std::max(link.replay_end_tick, state.tick);
  link.replayed_ticks += link.headstart_ticks;
  state.tick -= link.headstart_ticks;
  return true;
}

bool ghost_copies_init(const xosc::PrivateAction& action) {
  return !std::holds_alternative<xosc::ActivateControllerAction>(action) &&
         !std::holds_alternative<xosc::AssignControllerAction>(action) &&
         !std::holds_alternative<xosc::OverrideControllerValueAction>(action);
}

[[gnu::hot]] void record_trail(SimState& state) {
  if (!state.ghost) return;
  GhostLink& link = *state.ghost;
  const Entity& ghost = state.world.entities[link.ghost];
  const double now = state.now();
  auto& trail = link.trail;
  if (!ghost.state().placed) return;
  const double since = trail.empty() ? 0.0 : now - trail.back().time;
  if (!trail.empty() && since <= kTrailSampleTime + 1e-9) return;
  // A ghost standing still adds nothing (the last sample holds); after a pause the last
  // sample is repeated just before the new one, so that the pause keeps its place in time.
  if (!trail.empty() && std::abs(trail.back().speed) < 1e-9 &&
      std::abs(ghost.state().speed) < 1e-9) {
    return;
  }
  if (!trail.empty() && since > 2.0 * kTrailSampleTime + 1e-9) {
    TrailPoint held = trail.back();
    held.time = now - kTrailSampleTime;
    trail.push_back(held);
  }
  const Pose& p = ghost.state().pose;
  TrailPoint point{now, p.x, p.y, p.z, p.h, ghost.state().speed, 0.0, false};
  if (!trail.empty()) {
    const TrailPoint& last = trail.back();
    const double moved = std::hypot(p.x - last.x, p.y - last.y);
    // Farther than twice the faster speed could take it, and a metre: the ghost jumped.
    const double reach =
        2.0 * std::max(std::abs(last.speed), std::abs(ghost.state().speed)) * (now - last.time);
    point.jump = moved > reach + 1.0;
    point.s = last.s + (point.jump ? 0.0 : moved);
  }
  trail.push_back(point);
}

TrailPoint trail_at(const SimState& state, double time) {
  const auto& trail = state.ghost->trail;
  if (time <= trail.front().time) return trail.front();
  if (time >= trail.back().time) return trail.back();
  const auto after = std::upper_bound(trail.begin(), trail.end(), time,
                                      [](double t, const TrailPoint& p) { return t < p.time; });
  const TrailPoint& b = *after;
  const TrailPoint& a = *(after - 1);
  if (b.jump) return a;  // the ghost stood at a until it jumped to b
  const double w = b.time > a.time ? (time - a.time) / (b.time - a.time) : 0.0;
  TrailPoint out;
  out.time = time;
  out.x = a.x + w * (b.x - a.x);
  out.y = a.y + w * (b.y - a.y);
  out.z = a.z + w * (b.z - a.z);
  out.h = a.h + w * std::remainder(b.h - a.h, kGhostFullTurn);
  out.speed = a.speed + w * (b.speed - a.speed);
  return out;
}

void step_follow_ghost(SimState& state, uint32_t index, const MotionContext& motion) {
  GhostLink& link = *state.ghost;
  Entity& entity = state.world.entities[index];
  GhostFollower& car = link.follower;
  const double dt = motion.dt;
  if (!car.started || car.last_tick + 1 != state.tick) {
    // First step, or the first after the controller was off or the entity away: the model
    // starts from the entity's pose and speed (esmini resets its vehicle on activation).
    car.started = true;
    car.x = entity.state().pose.x;
    car.y = entity.state().pose.y;
    car.h =
        entity.state().pose.h - kGhostFullTurn * std::floor(entity.state().pose.h / kGhostFullTurn);
    car.speed = entity.state().speed;
    car.length = entity.info.box.length > 0.0 ? entity.info.box.length : 5.0;
  }
  car.last_tick = state.tick;
  GhostAim target{0.0, car.x, car.y, std::nullopt};
  if (!link.trail.empty()) {
    // Time mode: behind the ghost by the head start, at the end of this step.
    target = link.by_position
                 ? position_target(link, car.speed)
                 : time_target(state, state.time.time(state.tick + 1) - link.headstart, dt);
  }
  if (target.jump_to) {
    car.x = target.jump_to->x;
    car.y = target.jump_to->y;
    car.h = target.jump_to->h - kGhostFullTurn * std::floor(target.jump_to->h / kGhostFullTurn);
    car.speed = target.jump_to->speed;
    target.speed = car.speed;
    target.x = car.x + std::cos(car.h);
    target.y = car.y + std::sin(car.h);
  }
  const double target_speed = target.speed;
  const double aim_x = target.x, aim_y = target.y;
  double dx = aim_x - car.x, dy = aim_y - car.y;
  const double len = std::hypot(dx, dy);
  dx = len > 1e-10 ? dx / len : 0.0;
  dy = len > 1e-10 ? dy / len : 0.0;
  // The heading error: asin of the cross product of the car's direction and the aim's.
  const double cross = std::cos(car.h) * dy - std::sin(car.h) * dx;
  const double heading_error = std::asin(std::clamp(cross, -1.0, 1.0));
  // Speed: a proportional loop within the model's acceleration; steering: the wheel turned
  // straight to the heading error, its range narrowing with speed.
  const double acceleration = std::clamp(kFollowerMaxAcceleration * (target_speed - car.speed),
                                         -kFollowerMaxAcceleration, kFollowerMaxAcceleration);
  car.speed = std::clamp(car.speed + acceleration * dt, -kFollowerMaxSpeed, kFollowerMaxSpeed);
  const double range =
      kEsminiMaxWheelAngle / (1.0 + link.steering_speed_inertia * car.speed * car.speed);
  const double wheel = std::clamp(heading_error, -range, range);
  // Kinematic single-track model about a point 15% of the length ahead of the rear axle.
  single_track_step(car.x, car.y, car.h, car.speed, wheel, car.length, dt);
  place_entity_at_model(car.x, car.y, car.h, car.speed, entity, motion);
}

}  // namespace corsa::engine::detail
