#pragma once

// Simulation's private parts (simulation.h): the run state and the pieces that act on it.

#include <vector>

#include "controllers/controllers.h"
#include "motion/controller.h"
#include "state/sim_state.h"
#include "state/world_contacts.h"
#include "storyboard/init_actions.h"
#include "storyboard/storyboard.h"

namespace corsa::engine {

struct Simulation::Impl {
  Impl(const xosc::Scenario& scenario, std::shared_ptr<const xodr::Map> map,
       const SimulationOptions& options, Diagnostics& diagnostics);

  detail::SimState state;
  detail::InitActions init;
  std::unique_ptr<detail::Storyboard> storyboard;
  detail::DefaultController default_controller;
  detail::EntityMover mover;
  detail::ContactSweep contact_sweep;
  std::vector<xodr::LaneSpan> scratch;
  std::vector<SimulationObserver*> observers;
  bool announced = false;  ///< observers have seen tick 0
  EndReason end = EndReason::kRunning;

  void announce(const Simulation& owner);
  /// One step: actions, controllers, tick + 1, contacts, timers, settling.
  void advance();
};

}  // namespace corsa::engine
