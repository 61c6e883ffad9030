// TrafficAreaAction (OpenSCENARIO 1.3 §7.5.6): starts a traffic generator
// (traffic/traffic_generators.h) that works every step until a TrafficStopAction names it.

#include "actions/action_makers.h"
#include "state/sim_state.h"
#include "traffic/traffic_generators.h"

namespace corsa::engine::detail {
namespace {

class TrafficAreaInstance final : public InstantAction {
 public:
  explicit TrafficAreaInstance(const xosc::TrafficAreaAction& action) : action_(action) {}
  void start(ActionContext& context) override {
    context.state.traffic.generators.push_back(make_area(action_, context.state));
  }

 private:
  const xosc::TrafficAreaAction& action_;
};

}  // namespace

std::unique_ptr<ActionInstance> make_traffic_area_action(const xosc::TrafficAreaAction& action) {
  return std::make_unique<TrafficAreaInstance>(action);
}

}  // namespace corsa::engine::detail
