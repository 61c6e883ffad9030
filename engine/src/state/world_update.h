#pragma once

// What is updated once the entities have moved: contacts between bounding boxes (collisions,
// OpenSCENARIO CollisionCondition) and the per-entity timers of the duration conditions.

#include <cstdint>
#include <vector>

namespace corsa::engine::detail {

struct SimState;

/// What the contact sweep keeps from one update to the next: the entities in the order of the
/// last sweep and its axis. The next sweep starts from that order, which a step's small moves
/// hardly change, instead of sorting afresh.
struct ContactSweep {
  std::vector<uint32_t> order;
  bool along_y = false;
};

/// Recomputes which placed entities overlap now, and records the pairs that just started to.
void update_contacts(SimState& state, ContactSweep& sweep);
/// Advances the StandStill / Offroad / EndOfRoad timers by one step (`advance`: false at tick 0,
/// where they only start).
void update_timers(SimState& state, bool advance);

}  // namespace corsa::engine::detail
