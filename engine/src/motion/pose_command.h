#pragma once

// Motion by a commanded pose (FollowTrajectoryAction, OpenSCENARIO 1.3 §7.4.4.3): an action that
// drives the entity along its own path sets Entity::pose_command for the end of the step; the
// controller puts the entity there, derives speed, yaw rate and odometer from the move, and
// keeps the lane it is on up to date so that lane following resumes where the path ends.

#include "motion/controller.h"
#include "state/entity.h"

namespace corsa::engine::detail {

/// Moves `entity` to its pose command (consumed: lane following resumes when no action sets
/// one). The speed is the commanded speed_command (m/s), signed as the action gives it.
void move_to_pose_command(Entity& entity, const MotionContext& context);

/// Whether a pose command of (x, y, h) would leave `entity` where it is without asking the map:
/// (x, y, h) are its pose's own, bit for bit, and its point memo says no lane is near that point
/// (so the command's z and p, taken from a road there, stay too).
bool keeps_pose_off_lanes(const Entity& entity, double x, double y, double h,
                          const MotionContext& context);

/// move_to_pose_command for such a command (keeps_pose_off_lanes): the speed, accelerations,
/// yaw rate and odometers of a move by nothing, and no lane.
void hold_pose_off_lanes(Entity& entity, const MotionContext& context);

/// Whether a pose command of (x, y, h), its height and pitch read from the road surface within
/// `surface_within` m (surface_near), would put `entity`, which follows its lane, where it stands
/// without asking the map: (x, y, h) are its pose's own, bit for bit, its point memo holds the
/// map's answer for that point, a lane (so keeps_pose_off_lanes does not hold), and that
/// answer's surface (or none that near) leaves the pose's z and p as they are.
bool keeps_pose_on_lane(const Entity& entity, double x, double y, double h, double surface_within,
                        const MotionContext& context);

/// move_to_pose_command for such a command (keeps_pose_on_lane): the speed, accelerations, yaw
/// rate and odometers of a move by nothing; the followed lane stays as it is.
void hold_pose_on_lane(Entity& entity, const MotionContext& context);

}  // namespace corsa::engine::detail
