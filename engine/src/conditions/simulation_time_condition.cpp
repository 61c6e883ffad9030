// SimulationTimeCondition (OpenSCENARIO 1.3 §8.3.2): the simulation time (s since the start,
// on the tick grid) compared with a value.

#include "conditions/condition_makers.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class SimulationTimeCheck final : public ValueCondition {
 public:
  SimulationTimeCheck(const xosc::SimulationTimeCondition& c, double shift)
      : c_(c), shift_(shift) {}
  bool holds(const SimState& state) override {
    return compare(state.now(), c_.rule, c_.value + shift_);
  }

 private:
  const xosc::SimulationTimeCondition& c_;
  double shift_ = 0.0;
};

}  // namespace

std::unique_ptr<ValueCondition> make_simulation_time(const xosc::SimulationTimeCondition& c,
                                                     const SimState&) {
  return std::make_unique<SimulationTimeCheck>(c, 0.0);
}

std::unique_ptr<ValueCondition> make_shifted_simulation_time(const xosc::SimulationTimeCondition& c,
                                                             double shift) {
  return std::make_unique<SimulationTimeCheck>(c, shift);
}

}  // namespace corsa::engine::detail
