#pragma once

// What is updated once the entities have moved, besides the contacts (state/world_contacts.h):
// the per-entity timers of the duration conditions.

namespace corsa::engine::detail {

struct SimState;

/// Advances the StandStill / Offroad / EndOfRoad timers by one step (`advance`: false at tick 0,
/// where they only start). Only while SimState::timers_wanted (a condition reads them).
void update_timers(SimState& state, bool advance);

}  // namespace corsa::engine::detail
