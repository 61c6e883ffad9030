#include "motion/pose_command.h"

#include <cmath>

#include "geometry/angle.h"
#include "lanes/lane_follow.h"
#include "positions/position_resolver.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {

namespace {

// The pose's own part of a move to `target`, written into `state` (the entity's, or a copy of
// it): speed, accelerations, yaw rate and odometers. Returns the distance moved (m).
double take_pose(EntityMotion& entity, EntityState& state, const Pose& target, double dt) {
  const double dx = target.x - state.pose.x;
  const double dy = target.y - state.pose.y;
  // hypot(+-0, +-0) is +0: a model at rest (esmini's, whose speed only nears 0) moves by none.
  const double moved = dx == 0.0 && dy == 0.0 ? 0.0 : std::hypot(dx, dy);
  const double h0 = state.pose.h;
  const double v0 = state.speed;
  const double v1 = entity.speed_command;
  state.pose = target;
  state.acceleration = (v1 - v0) / dt;
  state.speed = v1;
  entity.lateral_acceleration = -state.lateral_speed / dt;
  state.lateral_speed = 0.0;
  state.yaw_rate = remainder_full_turn(target.h - h0) / dt;
  state.odometer += moved;
  entity.longitudinal_distance += moved;
  entity.end_of_road = false;
  return moved;
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
  // Made on a copy and written only if it differs: a model at rest whose speed no longer changes
  // (esmini's, once the engine brake rounds the speed to itself) then leaves the state as it is,
  // and its count of writes stands (the memos and the recorder pass over the entity).
  EntityState held = entity.state();
  const Pose pose = held.pose;
  take_pose(entity, held, pose, context.dt);
  if (!entity.lane.on_road) {
    // leave_lanes with no answer of the map.
    entity.lateral_command = 0.0;
    held.road.reset();
  }
  if (!same_bits(held, entity.state())) {
    entity.write_state() = held;
  }
}

}  // namespace corsa::engine::detail
