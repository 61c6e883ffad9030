// TrafficSignalCondition and TrafficSignalControllerCondition (OpenSCENARIO 1.3 §8.3.3): a
// signal is in the named state (the state string compared exactly, e.g. "off;off;on"); a
// controller is in the named phase.

#include "conditions/condition_makers.h"
#include "corsa/xosc/scenario.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class SignalStateCondition final : public ValueCondition {
 public:
  explicit SignalStateCondition(const xosc::TrafficSignalCondition& c) : c_(c) {}
  bool holds(const SimState& state) override {
    const auto it = state.traffic.signals.find(c_.name);
    return it != state.traffic.signals.end() && it->second == c_.state;
  }

 private:
  const xosc::TrafficSignalCondition& c_;
};

class SignalPhaseCondition final : public ValueCondition {
 public:
  SignalPhaseCondition(const xosc::TrafficSignalControllerCondition& c, std::optional<size_t> at)
      : c_(c), controller_(at) {}
  bool holds(const SimState& state) override {
    if (!controller_) {
      return false;
    }
    const SignalControllerRun& run = state.traffic.controllers[*controller_];
    return run.started && run.definition->phases[run.phase].name == c_.phase;
  }

 private:
  const xosc::TrafficSignalControllerCondition& c_;
  std::optional<size_t> controller_;
};

}  // namespace

std::unique_ptr<ValueCondition> make_traffic_signal_condition(const xosc::TrafficSignalCondition& c,
                                                              const SimState& state) {
  (void)state;
  return std::make_unique<SignalStateCondition>(c);
}

std::unique_ptr<ValueCondition> make_traffic_signal_controller_condition(
    const xosc::TrafficSignalControllerCondition& c, const SimState& state) {
  // An unknown controller never holds; the loader already warned about it, located.
  return std::make_unique<SignalPhaseCondition>(
      c, state.traffic.find_controller(c.traffic_signal_controller_ref));
}

}  // namespace corsa::engine::detail
