#include "state/world_update.h"

#include <algorithm>
#include <cmath>

#include "geometry/oriented_box.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {

void update_contacts(SimState& state) {
  const auto& entities = state.world.entities;
  std::vector<std::pair<uint32_t, uint32_t>> previous;
  previous.swap(state.contacts.pairs);
  // Sweep and prune along x: boxes sorted by their lowest x; only those whose x ranges overlap
  // are tested exactly.
  struct Item {
    double low, high;
    uint32_t index;
    OrientedBox box;
  };
  std::vector<Item> items;
  items.reserve(entities.size());
  for (uint32_t i = 0; i < entities.size(); ++i) {
    if (!entities[i].state.placed || entities[i].info.box.length <= 0.0) {
      continue;
    }
    const OrientedBox box = box_of(entities[i].info.box, entities[i].state.pose);
    const Interval x = project(box, 1.0, 0.0);
    items.push_back({x.low, x.high, i, box});
  }
  std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) {
    return a.low < b.low || (a.low == b.low && a.index < b.index);
  });
  auto& now = state.contacts.pairs;
  for (size_t a = 0; a < items.size(); ++a) {
    for (size_t b = a + 1; b < items.size() && items[b].low <= items[a].high; ++b) {
      if (overlap(items[a].box, items[b].box)) {
        now.emplace_back(std::min(items[a].index, items[b].index),
                         std::max(items[a].index, items[b].index));
      }
    }
  }
  // Entity order, independent of the sweep order; new contacts are recorded in that order.
  std::sort(now.begin(), now.end());
  for (const auto& pair : now) {
    if (!std::binary_search(previous.begin(), previous.end(), pair)) {
      state.collisions.push_back({state.tick, state.now(), pair.first, pair.second});
    }
  }
}

void update_timers(SimState& state, bool advance) {
  const double dt = advance ? state.time.dt() : 0.0;
  for (Entity& entity : state.world.entities) {
    // Each timer counts the time since its condition began: 0 at the first tick it holds.
    // Standing still: no speed at all (actions that stop an entity command exactly 0).
    const bool was_still = entity.standing_still;
    entity.standing_still = std::abs(entity.state.speed) < 1e-9;
    entity.standstill_time =
        entity.standing_still ? (was_still ? entity.standstill_time + dt : 0.0) : 0.0;
    const bool offroad = !entity.state.road;
    entity.offroad_time = offroad ? (entity.was_offroad ? entity.offroad_time + dt : 0.0) : 0.0;
    entity.was_offroad = offroad;
    entity.end_of_road_time =
        entity.end_of_road ? (entity.was_at_end ? entity.end_of_road_time + dt : 0.0) : 0.0;
    entity.was_at_end = entity.end_of_road;
  }
}

}  // namespace corsa::engine::detail
