#pragma once

// The contacts between the entities' bounding boxes, updated once the entities have moved
// (collisions, OpenSCENARIO CollisionCondition).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "corsa/engine/oriented_box.h"

namespace corsa::engine::detail {

struct SimState;

/// What the contact sweep keeps from one update to the next: the entities in the order of the
/// last sweep and its axis. The next sweep starts from that order, which a step's small moves
/// hardly change, instead of sorting afresh.
struct ContactSweep {
  std::vector<uint32_t> order;
  bool along_y = false;
  /// The strips across its axis the last sweep over all boxes was cut into (1: one sweep).
  uint32_t strips = 1;
  /// The strips' storage, kept between sweeps: where each strip's members end, each box's last
  /// strip, and the members (positions in the sweep's order), strip after strip.
  std::vector<uint32_t> strip_start, strip_last, strip_members;
  /// Calls work(begin, end) for ranges covering [0, count), each once, possibly on several
  /// threads at a time (the mover's, controllers/controllers.h); null: work(0, count) here.
  /// The boxes of the entities are made through it.
  std::function<void(size_t count, const std::function<void(size_t, size_t)>& work)> share;
  /// The boxes' extents along x and y at the last update, by entity (the boxes themselves are
  /// kept in ContactSet::boxes).
  std::vector<Interval> x_extent, y_extent;
  /// Whether the pairs, boxes and extents of the last update are those of every entity then
  /// (a sweep over finite extents, or an update of the moved boxes after one): the next update
  /// may then test only the boxes that have moved since.
  bool complete = false;
  /// The entities whose boxes changed since the last update, and a mark per entity for them
  /// (kept between updates for their storage, every mark 0 between them).
  std::vector<uint32_t> moved;
  std::vector<uint8_t> moved_mark;
  /// The pairs of the moved boxes in an update of those alone (kept for its storage).
  std::vector<std::pair<uint32_t, uint32_t>> moved_pairs;
  /// The pairs of the update before, while an update makes the new ones (kept between updates
  /// for its storage, as ContactSet::pairs: an update then allocates nothing).
  std::vector<std::pair<uint32_t, uint32_t>> previous;
};

/// Recomputes which placed entities overlap now, and records the pairs that just started to.
void update_contacts(SimState& state, ContactSweep& sweep);

/// Makes entity `i`'s contact box as it stands now into state.contacts.premade[i] (sized by the
/// caller): for the movers, each right after its own entity's move, so that the boxes are made
/// on the moves' threads. It writes that slot alone.
void premake_contact_box(SimState& state, uint32_t i);

}  // namespace corsa::engine::detail
