// TrafficSignalStateAction and TrafficSignalControllerAction (OpenSCENARIO 1.3 §7.5.2
// InfrastructureAction): a signal takes a state now (until its controller's next phase sets
// it); a controller jumps to a phase now, which then lasts its full duration. A state action
// naming a signal group instead of a signal (a TrafficSignalController's name or an OpenDRIVE
// <controller> id that is no signal's id) sets every signal of the group, as a
// TrafficSignalGroupState would, with a `(read as ...)` warning.

#include <string>
#include <vector>

#include "actions/action_makers.h"
#include "corsa/xosc/scenario.h"
#include "state/lenient.h"
#include "state/sim_state.h"
#include "traffic/signal_groups.h"
#include "traffic/traffic_update.h"

namespace corsa::engine::detail {
namespace {

/// The signals of the group `name` names when it is no signal: a TrafficSignalController's group
/// or the map's <controller> of that id. Empty when `name` is a signal (of the map, or named by
/// a phase) or names nothing known.
std::vector<std::string> state_action_group(const SimState& state, const std::string& name) {
  if (map_has_signal(state.map, name)) {
    return {};
  }
  for (const SignalControllerRun& run : state.traffic.controllers) {
    for (const xosc::Phase& phase : run.definition->phases) {
      for (const xosc::TrafficSignalState& signal : phase.states) {
        if (signal.traffic_signal_id == name) {
          return {};
        }
      }
    }
  }
  if (const auto controller = state.traffic.find_controller(name)) {
    return signal_group(state.map, *state.traffic.controllers[*controller].definition);
  }
  return map_controller_signals(state.map, name);
}

class SignalStateInstance final : public InstantAction {
 public:
  explicit SignalStateInstance(const xosc::TrafficSignalStateAction& action) : action_(action) {}
  void start(ActionContext& context) override {
    SimState& state = context.state;
    const std::vector<std::string> group = state_action_group(state, action_.name);
    if (group.empty()) {
      state.traffic.signals[action_.name] = action_.state;
      return;
    }
    lenient(state, action_.source,
            "TrafficSignalStateAction names the signal group '" + action_.name + "', not a signal",
            "the state of each of its " + std::to_string(group.size()) + " signals");
    for (const std::string& id : group) {
      state.traffic.signals[id] = action_.state;
    }
  }

 private:
  const xosc::TrafficSignalStateAction& action_;
};

class SignalPhaseInstance final : public InstantAction {
 public:
  explicit SignalPhaseInstance(const xosc::TrafficSignalControllerAction& action)
      : action_(action) {}
  void start(ActionContext& context) override {
    SimState& state = context.state;
    const auto controller = state.traffic.find_controller(action_.traffic_signal_controller_ref);
    if (!controller || !set_signal_phase(state, *controller, action_.phase)) {
      state.diagnostics.add_once(
          "signal-phase:" + action_.traffic_signal_controller_ref + ":" + action_.phase,
          action_.source.warning("no traffic signal controller '" +
                                 action_.traffic_signal_controller_ref + "' with a phase '" +
                                 action_.phase + "': nothing changes"));
    }
  }

 private:
  const xosc::TrafficSignalControllerAction& action_;
};

}  // namespace

std::unique_ptr<ActionInstance> make_traffic_signal_state_action(
    const xosc::TrafficSignalStateAction& action) {
  return std::make_unique<SignalStateInstance>(action);
}

std::unique_ptr<ActionInstance> make_traffic_signal_controller_action(
    const xosc::TrafficSignalControllerAction& action) {
  return std::make_unique<SignalPhaseInstance>(action);
}

}  // namespace corsa::engine::detail
