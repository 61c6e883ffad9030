#pragma once

// esmini's vehicle property `refpoint_x_offset` (a Property of the Vehicle, not part of the
// standard): the vehicle's reference point lies that many metres ahead of the axle its body
// turns about (the front axle over the rear one, say). The reference point goes where the
// actions and controllers put it, as for any entity; the body trails it: after every move the
// turning axle moves straight toward the reference point's new place, keeping its distance (a
// towed axle's tractrix, as motion/trailers.h moves trailers), and the heading is the direction
// from that axle to the reference point. Read as esmini's recorded headings have it under both
// readings, since the standard leaves vendor properties to the simulator (docs/openscenario.md).

#include <cstdint>

namespace corsa::engine::detail {

struct Entity;
struct SimState;

/// Reads the property of every vehicle entity and lists those that have one in
/// SimState::refpoint_trailing. A value that is no number >= 0 is ignored with a
/// warning at the property. An entity that is not placed yet waits at the origin facing +x
/// (its axle `length` behind it), where esmini moves it from.
void read_refpoint_offsets(SimState& state);

/// Marks a jump of `entity` to a given pose (motion/placement.h): its body keeps the pose's
/// heading, and the next move trails from it.
void mark_refpoint_jump(SimState& state, const Entity& entity);
/// Takes back such a mark: `entity` was moved to its place from where it stood, so its body
/// trails to it.
void mark_refpoint_moved(SimState& state, const Entity& entity);

/// Turns each listed entity's body after a move over `dt` seconds (0 at Init).
void trail_refpoints(SimState& state, double dt);

}  // namespace corsa::engine::detail
