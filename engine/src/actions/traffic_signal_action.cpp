// TrafficSignalStateAction and TrafficSignalControllerAction (OpenSCENARIO 1.3 §7.5.2
// InfrastructureAction): a signal takes a state now (until its controller's next phase sets
// it); a controller jumps to a phase now, which then lasts its full duration.

#include "actions/action_makers.h"
#include "corsa/xosc/scenario.h"
#include "state/sim_state.h"
#include "traffic/traffic_update.h"

namespace corsa::engine::detail {
namespace {

class SignalStateInstance final : public InstantAction {
 public:
  explicit SignalStateInstance(const xosc::TrafficSignalStateAction& action) : action_(action) {}
  void start(ActionContext& context) override {
    context.state.traffic.signals[action_.name] = action_.state;
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
