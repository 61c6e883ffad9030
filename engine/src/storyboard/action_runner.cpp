#include "storyboard/action_runner.h"

#include "state/sim_state.h"

namespace corsa::engine::detail {

void start_instance(SimState& state, RunningInstance& running, bool init) {
  if (!init && running.actor && state.frozen(*running.actor)) {
    running.started = false;
    return;
  }
  running.started = true;
  ActionContext context{state, running.actor, init};
  const uint8_t domains = running.action->domains();
  if (running.actor && domains != kDomainNone) {
    Entity& entity = state.world.entities[*running.actor];
    stop_domain_owners(entity, domains, running.action.get());
    for (int slot = 0; slot < kDomainSlots; ++slot) {
      if ((domains & (1u << slot)) != 0) {
        entity.owners[slot] = running.action.get();
      }
    }
  }
  running.action->start(context);
}

[[gnu::hot]] void step_instance(SimState& state, RunningInstance& running) {
  if (running.action->done() || (running.actor && state.frozen(*running.actor))) {
    // An entity that stands while a ghost has its head start waits with its actions too.
    return;
  }
  if (!running.started) {
    start_instance(state, running, false);
    if (running.action->done()) {
      return;
    }
  }
  ActionContext context{state, running.actor, false};
  running.action->step(context);
}

void release_instance(SimState& state, RunningInstance& running) {
  if (!running.actor) {
    return;
  }
  for (auto& owner : state.world.entities[*running.actor].owners) {
    if (owner == running.action.get()) {
      owner = nullptr;
    }
  }
}

void stop_instance(SimState& state, RunningInstance& running) {
  running.action->mark_stopped();
  release_instance(state, running);
}

}  // namespace corsa::engine::detail
