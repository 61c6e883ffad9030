#pragma once

// Starting, stepping and ending action instances on their actors, with the override rule: an
// action that takes a domain (longitudinal, lateral) of an entity stops the running action that
// held it (OpenSCENARIO 1.3 §7.4, "conflicting actions").

#include <cstdint>
#include <memory>
#include <optional>

#include "actions/action.h"

namespace corsa::engine::detail {

struct SimState;

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
/// Steps the instance unless it is done (starting it first if its start waited).
void step_instance(SimState& state, RunningInstance& running);
/// Gives the instance's domains back (call when it is done, before destroying it).
void release_instance(SimState& state, RunningInstance& running);
/// Stops a running instance (overridden or its element stopped) and releases it.
void stop_instance(SimState& state, RunningInstance& running);

}  // namespace corsa::engine::detail
