// TrafficSourceAction (OpenSCENARIO 1.3 §7.5.6): starts a traffic generator
// (traffic/traffic_generators.h) that works every step until a TrafficStopAction names it.

#include "actions/action_makers.h"
#include "state/sim_state.h"
#include "traffic/traffic_generators.h"

namespace corsa::engine::detail {
namespace {

class TrafficSourceInstance final : public InstantAction {
 public:
  explicit TrafficSourceInstance(const xosc::TrafficSourceAction& action) : action_(action) {}
  void start(ActionContext& context) override {
    context.state.traffic.generators.push_back(make_source(action_, context.state));
  }

 private:
  const xosc::TrafficSourceAction& action_;
};

}  // namespace

std::unique_ptr<ActionInstance> make_traffic_source_action(
    const xosc::TrafficSourceAction& action) {
  return std::make_unique<TrafficSourceInstance>(action);
}

}  // namespace corsa::engine::detail
