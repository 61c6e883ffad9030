#pragma once

// What the contacts' update (state/world_contacts.h) must find, by testing every pair: for the
// tests of the contacts (contacts_test.cpp, traffic_scale_test.cpp).

#include <cstdint>
#include <utility>
#include <vector>

#include "corsa/engine/oriented_box.h"
#include "state/sim_state.h"

namespace corsa::test {

// The overlapping pairs of placed entities with a box, by testing every pair (what the contacts'
// sweep must find), in entity order.
inline std::vector<std::pair<uint32_t, uint32_t>> pairs_by_testing_all(
    const std::vector<corsa::engine::detail::Entity>& entities) {
  const auto usable = [](const corsa::engine::detail::Entity& e) {
    return e.state().placed && e.info.box.length > 0.0;
  };
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  for (uint32_t a = 0; a < entities.size(); ++a) {
    for (uint32_t b = a + 1; b < entities.size(); ++b) {
      if (usable(entities[a]) && usable(entities[b]) &&
          corsa::engine::overlap(
              corsa::engine::box_of(entities[a].info.box, entities[a].state().pose),
              corsa::engine::box_of(entities[b].info.box, entities[b].state().pose))) {
        pairs.emplace_back(a, b);
      }
    }
  }
  return pairs;
}

}  // namespace corsa::test
