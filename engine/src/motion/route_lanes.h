#pragma once

// Lane changes a route needs (OpenSCENARIO 1.3 §6.6 routes, §7.4.4.1 AssignRouteAction,
// §7.4.4.2 AcquirePositionAction): a route laid by xodr::find_route may leave a road from
// another lane than the one the entity drives in (a left turn only from the leftmost lane) or
// pass a waypoint on another lane. Before the controllers move the entities, each entity with a
// route is moved toward the lane its route needs next, one neighbouring lane at a time, as a
// LaneChangeAction would (the followed lane switches at once, the lateral offset goes from where
// the entity is to the lane's centre along a sinusoidal shape over a distance). All controllers
// then carry it out: the default controller exactly, acc on top of it, dynamics by steering
// toward the commanded offset.

#include "motion/controller.h"

namespace corsa::engine::detail {

struct SimState;

/// A lane change for a route is made over the distance driven in kRouteLaneChangeTime seconds
/// at the entity's speed (the larger of its speed and its commanded speed, at least
/// kRouteLaneChangeMinSpeed, so that a car pulling away does not jump sideways), squeezed down
/// to kRouteLaneChangeShortestTime when the lane that leads on ends sooner. Sinusoidal shape:
/// the largest lateral speed is (pi / 2) x lane width / time at that speed, 1.4 m/s for a
/// 3.5 m lane over 4 s, 2.2 m/s over 2.5 s.
inline constexpr double kRouteLaneChangeTime = 4.0;          // s
inline constexpr double kRouteLaneChangeShortestTime = 2.5;  // s
inline constexpr double kRouteLaneChangeMinSpeed = 5.0;      // m/s

/// For every present entity with a route: follows its progress along the route, starts or
/// continues the lane change the route needs (setting Entity::lateral_command and the followed
/// lane), and warns once (located at the route) when the entity cannot follow its route. Lane
/// changes wait while a lateral action runs on the entity or it is placed by a pose command.
void follow_route_lanes(SimState& state, const MotionContext& motion);

}  // namespace corsa::engine::detail
