#include "actions/action.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {

[[gnu::hot]] Entity& ActionContext::entity() const { return state.world.entities[*actor]; }

void stop_domain_owners(Entity& entity, uint8_t domains, const ActionInstance* keep) {
  for (int slot = 0; slot < kDomainSlots; ++slot) {
    ActionInstance* previous = entity.owners[slot];
    if ((domains & (1u << slot)) == 0 || previous == nullptr || previous == keep) {
      continue;
    }
    // Overridden: the previous action stops and loses every domain it held on this entity.
    if (!previous->done()) {
      previous->mark_stopped();
    }
    for (auto& owner : entity.owners) {
      if (owner == previous) {
        owner = nullptr;
      }
    }
  }
}

}  // namespace corsa::engine::detail
