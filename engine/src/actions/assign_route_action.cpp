// AssignRouteAction (OpenSCENARIO 1.3 §7.4.4.1, routes §6.6): the actor follows the route's
// lanes from now on: at every lane end with several successors it takes the one on the route
// (motion/route_chooser.h), and it changes lanes where the route needs another lane
// (motion/route_lanes.h). The route (inline or from a catalog, expanded by the loader) is laid
// onto the map when the action starts, each leg by its waypoint's routeStrategy.

#include "actions/action_makers.h"
#include "actions/route_assignment.h"
#include "positions/route_path.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class AssignRouteInstance final : public InstantAction {
 public:
  explicit AssignRouteInstance(const xosc::AssignRouteAction& action) : action_(action) {}

  void start(ActionContext& context) override {
    RoutePath path = build_route_path(action_.route, context.state, context.actor);
    RoutePlan plan{std::move(path.steps), std::move(path.waypoint_steps), action_.route.name,
                   action_.route.source};
    assign_route(context.state, context.entity(), std::move(plan));
  }

 private:
  const xosc::AssignRouteAction& action_;
};

}  // namespace

std::unique_ptr<ActionInstance> make_assign_route_action(const xosc::AssignRouteAction& action) {
  return std::make_unique<AssignRouteInstance>(action);
}

}  // namespace corsa::engine::detail
