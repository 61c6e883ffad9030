// RandomRouteAction (OpenSCENARIO 1.3 §7.4.4): the actor drives a random route from now on. At
// every lane end with several drivable successors it takes one of them at random, each equally
// likely, from a stream of the run seed and the entity's name, so the same seed gives the same
// route. (The element has no attributes: the route is endless, chosen as the entity drives.)

#include "actions/action_makers.h"
#include "corsa/core/random.h"
#include "corsa/xodr/map.h"
#include "lanes/lane_follow.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class RandomChooser final : public LaneChooser {
 public:
  explicit RandomChooser(RandomStream stream) : stream_(stream) {}
  size_t choose(const xodr::Map& map, const LaneFollow& lane,
                std::span<const xodr::LaneEnd> candidates) const override {
    // Drivable successors entered in their own direction, as the straightest choice prefers;
    // when there are none of those, any.
    std::vector<size_t> usable;
    for (size_t i = 0; i < candidates.size(); ++i) {
      const auto& info = map.lane_graph().info(candidates[i].node);
      if (xodr::is_drivable(info.type)) usable.push_back(i);
    }
    if (usable.empty()) return choose_straightest(map, lane, candidates);
    return usable[static_cast<size_t>(stream_.next_u64() % usable.size())];
  }

 private:
  mutable RandomStream stream_;
};

class RandomRouteInstance final : public InstantAction {
 public:
  explicit RandomRouteInstance(const xosc::RandomRouteAction& action) : action_(action) {}
  void start(ActionContext& context) override {
    Entity& entity = context.entity();
    auto chooser = std::make_shared<const RandomChooser>(
        RandomStream::derive(context.state.options.seed, "random-route:" + entity.info.name));
    entity.chooser = chooser.get();
    // The memo compares the route by address: the old route may be freed and its address
    // reused by a later one, so a standing entity takes its next step anew.
    entity.still_step_valid = false;
    entity.route = std::move(chooser);
    entity.route_progress = RouteProgress{};
    (void)action_;
  }

 private:
  const xosc::RandomRouteAction& action_;
};

}  // namespace

std::unique_ptr<ActionInstance> make_random_route_action(const xosc::RandomRouteAction& action) {
  return std::make_unique<RandomRouteInstance>(action);
}

}  // namespace corsa::engine::detail
