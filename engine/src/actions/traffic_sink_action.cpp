// TrafficSinkAction (OpenSCENARIO 1.3 §7.5.6): starts a traffic generator
// (traffic/traffic_generators.h) that works every step until a TrafficStopAction names it.

#include "actions/action_makers.h"
#include "state/sim_state.h"
#include "traffic/traffic_generators.h"

namespace corsa::engine::detail {
namespace {

class TrafficSinkInstance final : public InstantAction {
 public:
  explicit TrafficSinkInstance(const xosc::TrafficSinkAction& action) : action_(action) {}
  void start(ActionContext& context) override {
    context.state.traffic.generators.push_back(make_sink(action_, context.state));
  }

 private:
  const xosc::TrafficSinkAction& action_;
};

}  // namespace

std::unique_ptr<ActionInstance> make_traffic_sink_action(const xosc::TrafficSinkAction& action) {
  return std::make_unique<TrafficSinkInstance>(action);
}

}  // namespace corsa::engine::detail
