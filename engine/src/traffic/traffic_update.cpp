// Traffic signal controllers (OpenSCENARIO 1.3 §6.5.2 TrafficSignalController: phases cycle in
// document order, each for its duration; a controller with a `reference` starts `delay` seconds
// after the referenced one), the per-step update of the traffic generators, and entities removed
// or spawned.

#include "traffic/traffic_update.h"

#include "controllers/controllers.h"
#include "corsa/xosc/scenario.h"
#include "state/sim_state.h"
#include "traffic/signal_groups.h"

namespace corsa::engine::detail {
namespace {

// `map`: the road network (null: none), whose <controller>s are the signal groups.
void apply_phase(TrafficState& traffic, const xodr::Map* map, const SignalControllerRun& run) {
  const xosc::Phase& phase = run.definition->phases[run.phase];
  if (phase.group_state) {
    // TrafficSignalGroupState: the observable state of every signal of the controller's group
    // (looked up at each phase change, which is rare); a TrafficSignalState of the phase then
    // sets its own signal's.
    for (const std::string& id : signal_group(map, *run.definition)) {
      traffic.signals[id] = *phase.group_state;
    }
  }
  for (const xosc::TrafficSignalState& signal : phase.states) {
    traffic.signals[signal.traffic_signal_id] = signal.state;
  }
}

// Start time (s) of a controller: its delay, plus its reference's start (chains followed, a
// cycle of references broken at the first repeat).
double start_time(const TrafficState& traffic, size_t index) {
  double start = 0.0;
  std::vector<bool> seen(traffic.controllers.size(), false);
  std::optional<size_t> at = index;
  while (at && !seen[*at]) {
    seen[*at] = true;
    const xosc::TrafficSignalController& definition = *traffic.controllers[*at].definition;
    start += definition.delay.value_or(0.0);
    at = definition.reference ? traffic.find_controller(*definition.reference) : std::nullopt;
  }
  return start;
}

// A TrafficSignalGroupState that reaches no signal: the map has no <controller> of the
// controller's name and its phases name no signal.
void warn_groupless(SimState& state, const xosc::TrafficSignalController& controller) {
  if (!signal_group(state.map, controller).empty()) {
    return;
  }
  for (const xosc::Phase& phase : controller.phases) {
    if (phase.group_state) {
      state.diagnostics.add_once(
          "signal-group:" + controller.name,
          phase.source.warning("TrafficSignalGroupState of TrafficSignalController '" +
                               controller.name + "' sets no signal: the road network has no " +
                               "<controller id=\"" + controller.name +
                               "\"> and its phases name no signal"));
      return;
    }
  }
}

}  // namespace

void init_traffic(SimState& state) {
  TrafficState& traffic = state.traffic;
  for (const xosc::TrafficSignalController& controller :
       state.scenario.road_network.traffic_signal_controllers) {
    SignalControllerRun run;
    run.definition = &controller;
    warn_groupless(state, controller);
    traffic.controllers.push_back(run);
  }
  for (size_t i = 0; i < traffic.controllers.size(); ++i) {
    traffic.controllers[i].phase_start = start_time(traffic, i);
  }
  // Phases at time 0.
  for (SignalControllerRun& run : traffic.controllers) {
    if (!run.definition->phases.empty() && run.phase_start <= 0.0) {
      run.started = true;
      apply_phase(traffic, state.map, run);
    }
  }
}

bool set_signal_phase(SimState& state, size_t controller, std::string_view phase) {
  SignalControllerRun& run = state.traffic.controllers[controller];
  const auto& phases = run.definition->phases;
  for (size_t i = 0; i < phases.size(); ++i) {
    if (phases[i].name == phase) {
      run.phase = i;
      run.phase_start = state.now();
      run.started = true;
      apply_phase(state.traffic, state.map, run);
      return true;
    }
  }
  return false;
}

[[gnu::hot]] void update_traffic(SimState& state) {
  TrafficState& traffic = state.traffic;
  // Half a step of slack: phase ends fall on the tick grid despite rounding.
  const double now = state.now() + 0.5 * state.time.dt();
  for (SignalControllerRun& run : traffic.controllers) {
    const auto& phases = run.definition->phases;
    if (phases.empty()) {
      continue;
    }
    if (!run.started) {
      if (now < run.phase_start) {
        continue;
      }
      run.started = true;
      apply_phase(traffic, state.map, run);
    }
    // Phases of zero duration are passed through; a whole cycle of them stops the cycling.
    for (size_t guard = 0; guard < phases.size(); ++guard) {
      const double duration = phases[run.phase].duration;
      if (!(duration > 0.0) && guard > 0) {
        break;
      }
      if (now < run.phase_start + duration) {
        break;
      }
      run.phase_start += duration;
      run.phase = (run.phase + 1) % phases.size();
      apply_phase(traffic, state.map, run);
    }
  }
  // Generators may add entities: index, not iterators, and only those present now.
  const size_t count = traffic.generators.size();
  for (size_t i = 0; i < count; ++i) {
    traffic.generators[i]->step(state);
  }
  // Generated entities removed this step (by a generator, a sink, a DeleteEntityAction).
  if (traffic.removals == traffic.removals_seen) {
    return;
  }
  traffic.removals_seen = traffic.removals;
  for (auto& [index, lives] : traffic.lifetimes) {
    if (!lives.empty() && !lives.back().removed && !state.world.entities[index].state().placed) {
      lives.back().removed = state.now();
    }
  }
}

void remove_entity(SimState& state, uint32_t index) {
  ++state.traffic.removals;
  Entity& entity = state.world.entities[index];
  entity.removed = entity.state().placed || entity.removed;
  if (entity.state().placed) {
    entity.removed_road = entity.state().road;
    entity.removed_speed = entity.state().speed;
  }
  EntityState& written = entity.write_state();
  written.placed = false;
  written.speed = 0.0;
  written.acceleration = 0.0;
  written.lateral_speed = 0.0;
  written.yaw_rate = 0.0;
  written.road.reset();
  entity.speed_command = 0.0;
  entity.lateral_command = 0.0;
  control_of(state, index).dynamics.reset();
}

void note_spawned(SimState& state, uint32_t index) {
  auto& lives = state.traffic.lifetimes[index];
  if (!lives.empty() && !lives.back().removed) {
    lives.back().removed = state.now();
  }
  lives.push_back(Lifetime{state.now(), std::nullopt});
}

}  // namespace corsa::engine::detail
