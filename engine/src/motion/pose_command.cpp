#include "motion/pose_command.h"

#include <bit>
#include <cmath>
#include <cstdint>

#include "geometry/angle.h"
#include "lanes/lane_follow.h"
#include "positions/position_resolver.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {

namespace {

// What a move from `state` to `target` at the speed command `speed` (m/s) makes of the state
// besides the pose, over a step of `dt` s.
struct PoseStep {
  double moved = 0.0;         ///< m
  double acceleration = 0.0;  ///< m/s^2
  double speed = 0.0;         ///< m/s
  double yaw_rate = 0.0;      ///< rad/s
  double odometer = 0.0;      ///< m
};

PoseStep pose_step(const EntityState& state, const Pose& target, double speed, double dt) {
  const double dx = target.x - state.pose.x;
  const double dy = target.y - state.pose.y;
  // hypot(+-0, +-0) is +0: a model at rest (esmini's, whose speed only nears 0) moves by none.
  const double moved = dx == 0.0 && dy == 0.0 ? 0.0 : std::hypot(dx, dy);
  return {moved, (speed - state.speed) / dt, speed,
          remainder_full_turn(target.h - state.pose.h) / dt, state.odometer + moved};
}

// The move's writes besides the state (which it reads as it was before the move).
void take_motion(EntityMotion& entity, const EntityState& before, double moved, double dt) {
  entity.lateral_acceleration = -before.lateral_speed / dt;
  entity.longitudinal_distance += moved;
  entity.end_of_road = false;
}

void write_step(EntityState& state, const Pose& target, const PoseStep& step) {
  state.pose = target;
  state.acceleration = step.acceleration;
  state.speed = step.speed;
  state.lateral_speed = 0.0;
  state.yaw_rate = step.yaw_rate;
  state.odometer = step.odometer;
}

// The pose's own part of a move to `target`, written into the entity's `state`: speed,
// accelerations, yaw rate and odometers. Returns the distance moved (m).
double take_pose(EntityMotion& entity, EntityState& state, const Pose& target, double dt) {
  const PoseStep step = pose_step(state, target, entity.speed_command, dt);
  take_motion(entity, state, step.moved, dt);
  write_step(state, target, step);
  return step.moved;
}

// Off its lanes: no lane to follow, and the road coordinates of the map's answer at its point.
void leave_lanes(Entity& entity, const std::optional<xodr::LanePosition>& located) {
  entity.lane.on_road = false;
  entity.lateral_command = 0.0;
  update_road_from_located(entity, located);
}

}  // namespace

[[gnu::hot]] void move_to_pose_command(Entity& entity, const MotionContext& context) {
  EntityState& state = entity.write_state();
  const Pose target = *entity.pose_command;
  entity.pose_command.reset();
  const double h0 = state.pose.h;
  const double moved = take_pose(entity, state, target, context.dt);
  if (context.map == nullptr) {
    return;
  }
  // Held where it stands (esmini's teleport, which takes its step): the followed lane was set
  // with the pose, and a LaneChangeAction started in the same step may since have switched it
  // to its target lane, keeping the place; that lane and offset stay.
  if (moved == 0.0 && target.h == h0 && entity.lane.on_road) {
    return;
  }
  // Keep the followed lane in step with the pose (half a metre of slack off the lane edges),
  // so that the lane, s and t are recorded and lane following can take over at the end.
  const auto& located = locate_near(entity, *context.map, target.x, target.y);
  const auto at = road_point_within(located, 0.5);
  if (at && at->lane &&
      attach_to_lane(*context.map, entity.lane, at->road, at->s, at->t, *at->lane, target.h)) {
    entity.lateral_command = entity.lane.lateral;
    state.road = RoadCoordinates{at->road,
                                 static_cast<uint32_t>(context.map->section_index(at->road, at->s)),
                                 *at->lane, at->s, at->t};
  } else {
    // The pose is the target: the map's answer for its point is at hand.
    leave_lanes(entity, located);
  }
}

[[gnu::hot]] bool keeps_pose_on_lane(const Entity& entity, double x, double y, double h,
                                     double surface_within, const MotionContext& context) {
  const Pose& pose = entity.state().pose;
  const PointLocateMemo& memo = entity.point_memo;
  // The differences by value as well: an infinite coordinate moves by a NaN (and asks the map).
  if (context.map == nullptr || !entity.lane.on_road || !same_bits(x, pose.x) ||
      !same_bits(y, pose.y) || !same_bits(h, pose.h) || x - pose.x != 0.0 || y - pose.y != 0.0 ||
      h != pose.h || !memo.valid || !same_bits(memo.x, x) || !same_bits(memo.y, y)) {
    return false;
  }
  // A lane at the point (so that keeps_pose_off_lanes, which needs none, does not hold too), and
  // surface_near's answer from the memo (road_point_within): none that near keeps z and p.
  if (!memo.located) {
    return false;
  }
  if (!(memo.located->distance <= surface_within)) {
    return true;
  }
  return memo.surface_valid && same_bits(memo.surface.z, pose.z) &&
         same_bits(memo.surface.p, pose.p);
}

[[gnu::hot]] void hold_pose_on_lane(Entity& entity, const MotionContext& context) {
  // move_to_pose_command to the pose the entity has, up to its return for a move by nothing on
  // the followed lane.
  entity.pose_command.reset();
  EntityState& state = entity.write_state();
  const Pose here = state.pose;
  take_pose(entity, state, here, context.dt);
}

[[gnu::hot]] bool keeps_pose_off_lanes(const Entity& entity, double x, double y, double h,
                                       const MotionContext& context) {
  const EntityState& state = entity.state();
  // Compared by value too: a NaN coordinate takes the move (its distance is no 0, its turn no 0).
  return context.map != nullptr && x == state.pose.x && y == state.pose.y && h == state.pose.h &&
         same_bits(x, state.pose.x) && same_bits(y, state.pose.y) && same_bits(h, state.pose.h) &&
         clear_of_lanes_at(entity.point_memo, x, y);
}

[[gnu::hot]] void hold_pose_off_lanes(Entity& entity, const MotionContext& context) {
  // move_to_pose_command to the pose the entity has: it moves by +0 and turns by +0, and the
  // map's answer at its point is none.
  entity.pose_command.reset();
  const EntityState& now = entity.state();
  const PoseStep step = pose_step(now, now.pose, entity.speed_command, context.dt);
  const bool off = !entity.lane.on_road;
  // The state is written only where the move changes it (the pose it keeps, bit for bit): a
  // model at rest whose speed no longer changes (esmini's, once the engine brake rounds the
  // speed to itself) then leaves the state as it is, and its count of writes stands (the memos
  // and the recorder pass over the entity). The values are compared, not a copy of the state.
  const auto bits = [](double v) { return std::bit_cast<uint64_t>(v); };
  const uint64_t diff = (bits(step.acceleration) ^ bits(now.acceleration)) |
                        (bits(step.speed) ^ bits(now.speed)) | bits(now.lateral_speed) |
                        (bits(step.yaw_rate) ^ bits(now.yaw_rate)) |
                        (bits(step.odometer) ^ bits(now.odometer));
  const bool changes = diff != 0 || (off && now.road.has_value());
  take_motion(entity, now, step.moved, context.dt);
  if (off) {
    // leave_lanes with no answer of the map.
    entity.lateral_command = 0.0;
  }
  if (changes) {
    EntityState& state = entity.write_state();
    write_step(state, state.pose, step);
    if (off) {
      state.road.reset();
    }
  }
}

}  // namespace corsa::engine::detail
