// TrafficSwarmAction (OpenSCENARIO 1.3 §7.5.6): starts a traffic generator
// (traffic/traffic_generators.h) that works every step until a TrafficStopAction names it.

#include "actions/action_makers.h"
#include "state/sim_state.h"
#include "traffic/traffic_generators.h"

namespace corsa::engine::detail {
namespace {

class TrafficSwarmInstance final : public InstantAction {
 public:
  explicit TrafficSwarmInstance(const xosc::TrafficSwarmAction& action) : action_(action) {}
  void start(ActionContext& context) override {
    context.state.traffic.generators.push_back(make_swarm(action_, context.state));
  }

 private:
  const xosc::TrafficSwarmAction& action_;
};

}  // namespace

std::unique_ptr<ActionInstance> make_traffic_swarm_action(const xosc::TrafficSwarmAction& action) {
  return std::make_unique<TrafficSwarmInstance>(action);
}

}  // namespace corsa::engine::detail
