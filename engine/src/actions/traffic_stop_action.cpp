// TrafficStopAction (OpenSCENARIO 1.3 §7.5.6): the traffic generators started under this
// trafficName stop (no more vehicles appear or disappear through them); the vehicles already
// spawned stay and drive on.

#include <algorithm>

#include "actions/action_makers.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class TrafficStopInstance final : public InstantAction {
 public:
  explicit TrafficStopInstance(const xosc::TrafficStopAction& action) : action_(action) {}
  void start(ActionContext& context) override {
    auto& generators = context.state.traffic.generators;
    const auto before = generators.size();
    std::erase_if(generators, [&](const std::unique_ptr<TrafficGenerator>& g) {
      return g->name() == action_.traffic_name;
    });
    if (generators.size() == before) {
      context.state.diagnostics.add_once(
          "traffic-stop:" + action_.traffic_name.value_or(""),
          action_.source.warning("no running traffic action is called '" +
                                 action_.traffic_name.value_or("") + "'"));
    }
  }

 private:
  const xosc::TrafficStopAction& action_;
};

}  // namespace

std::unique_ptr<ActionInstance> make_traffic_stop_action(const xosc::TrafficStopAction& action) {
  return std::make_unique<TrafficStopInstance>(action);
}

}  // namespace corsa::engine::detail
