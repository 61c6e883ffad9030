// AcquirePositionAction (OpenSCENARIO 1.3 §7.4.4.2): a route with two waypoints, the actor's
// current position and the target position, assigned at once (the shortest lane route; the
// actor then drives it at whatever speed the longitudinal actions give it).

#include "actions/action_makers.h"
#include "actions/route_assignment.h"
#include "positions/position_common.h"
#include "positions/route_path.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class AcquirePositionInstance final : public InstantAction {
 public:
  explicit AcquirePositionInstance(const xosc::AcquirePositionAction& action) : action_(action) {}

  void start(ActionContext& context) override {
    const SimState& state = context.state;
    const xodr::Map& map = need_map(state, action_.source, "AcquirePositionAction");
    Entity& entity = context.entity();
    if (!entity.state().road) {
      fail(action_.source, "AcquirePositionAction: entity '" + entity.info.name +
                               "' is not on a lane, so no route can start from it");
    }
    const ResolvedPosition target = resolve_position(action_.position, state, context.actor);
    if (!target.road || !target.road->lane) {
      fail(action_.position.source, "AcquirePositionAction: the target is not on a lane");
    }
    const xodr::LanePoint from{entity.state().road->road, entity.state().road->lane,
                               entity.state().road->s};
    const xodr::LanePoint to{target.road->road, *target.road->lane, target.road->s};
    auto route = xodr::find_route(map, from, to);
    if (!route) {
      fail(action_.position.source,
           "AcquirePositionAction: the target cannot be reached from the lane of '" +
               entity.info.name + "'");
    }
    const size_t last = route->steps.empty() ? 0 : route->steps.size() - 1;
    RoutePlan plan{std::move(route->steps), {last}, "AcquirePositionAction", action_.source};
    assign_route(context.state, entity, std::move(plan));
  }

 private:
  const xosc::AcquirePositionAction& action_;
};

}  // namespace

std::unique_ptr<ActionInstance> make_acquire_position_action(
    const xosc::AcquirePositionAction& action) {
  return std::make_unique<AcquirePositionInstance>(action);
}

}  // namespace corsa::engine::detail
