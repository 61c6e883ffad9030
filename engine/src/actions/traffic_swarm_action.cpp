// TrafficSwarmAction (OpenSCENARIO 1.3 §7.5.6): starts a traffic generator
// (traffic/traffic_generators.h) that works every step until a TrafficStopAction names it.
//
// When the action itself ends the standard does not say. It runs as long as its swarm does,
// until a TrafficStopAction or the end of the run, and so keeps its Act and Story running, as
// esmini reads it (esmini's swarm example, whose Storyboard has an empty StopTrigger, runs on
// with its swarm instead of ending once the swarm has started).

#include <algorithm>

#include "actions/action_makers.h"
#include "state/sim_state.h"
#include "traffic/traffic_generators.h"

namespace corsa::engine::detail {
namespace {

class TrafficSwarmInstance final : public ActionInstance {
 public:
  explicit TrafficSwarmInstance(const xosc::TrafficSwarmAction& action) : action_(action) {}
  void start(ActionContext& context) override {
    auto swarm = make_swarm(action_, context.state);
    swarm->serial = ++context.state.traffic.generators_made;
    serial_ = swarm->serial;
    context.state.traffic.generators.push_back(std::move(swarm));
    running_ = true;
  }
  void step(ActionContext& context) override {
    const auto& generators = context.state.traffic.generators;
    running_ = std::any_of(generators.begin(), generators.end(),
                           [&](const auto& generator) { return generator->serial == serial_; });
  }
  bool finished() const override { return !running_; }

 private:
  const xosc::TrafficSwarmAction& action_;
  uint64_t serial_ = 0;
  bool running_ = false;
};

}  // namespace

std::unique_ptr<ActionInstance> make_traffic_swarm_action(const xosc::TrafficSwarmAction& action) {
  return std::make_unique<TrafficSwarmInstance>(action);
}

}  // namespace corsa::engine::detail
