#pragma once

// Starting, stepping and ending action instances on their actors, with the override rule: an
// action that takes a domain (longitudinal, lateral) of an entity stops the running action that
// held it (OpenSCENARIO 1.3 §7.4, "conflicting actions").

#include <cstdint>
#include <memory>
#include <optional>

#include "actions/action.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {

/// One running instance and the entity it acts on.
struct RunningInstance {
  std::unique_ptr<ActionInstance> action;
  std::optional<uint32_t> actor;
  /// False while the start waits for its actor: one that stands while a ghost has its head
  /// start begins its actions at time 0, as esmini (its rows of test_ghost_restart2).
  bool started = true;
};

/// Claims the actor's domains (stopping their previous owners) and starts the action; for an
/// actor that stands during a ghost's head start, that waits until its first step at time >= 0.
void start_instance(SimState& state, RunningInstance& running, bool init);
/// Starts an instance whose start waited (start_instance); false when it is done at once.
bool start_waiting(SimState& state, RunningInstance& running);
/// Steps the instance unless it is done (starting it first if its start waited), and tells
/// whether it is done then. Inline: every running action takes it at every step.
///
/// An instance becomes done only in its start, its step, a teleport of its actor or a stop
/// (actions starting, the storyboard's transitions): between this step and the next storyboard
/// update nothing makes one done, so the instances this found done are all there are to settle.
inline bool step_instance(SimState& state, RunningInstance& running) {
  ActionInstance& action = *running.action;
  if (action.done()) {
    return true;
  }
  if (running.actor && state.frozen(*running.actor)) {
    // An entity that stands while a ghost has its head start waits with its actions too.
    return false;
  }
  if (!running.started && !start_waiting(state, running)) {
    return true;
  }
  ActionContext context{state, running.actor, false};
  action.step(context);
  return action.done();
}
/// Gives the instance's domains back (call when it is done, before destroying it).
void release_instance(SimState& state, RunningInstance& running);
/// Stops a running instance (overridden or its element stopped) and releases it.
void stop_instance(SimState& state, RunningInstance& running);

}  // namespace corsa::engine::detail
