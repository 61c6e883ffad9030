#pragma once

// What is updated once the entities have moved: contacts between bounding boxes (collisions,
// OpenSCENARIO CollisionCondition) and the per-entity timers of the duration conditions.

namespace corsa::engine::detail {

struct SimState;

/// Recomputes which placed entities overlap now, and records the pairs that just started to.
void update_contacts(SimState& state);
/// Advances the StandStill / Offroad / EndOfRoad timers by one step (`advance`: false at tick 0,
/// where they only start).
void update_timers(SimState& state, bool advance);

}  // namespace corsa::engine::detail
