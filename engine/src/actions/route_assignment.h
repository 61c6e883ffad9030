#pragma once

// Giving an entity a route to follow (AssignRouteAction, AcquirePositionAction).

#include <memory>
#include <vector>

#include "corsa/xodr/route.h"
#include "motion/route_chooser.h"
#include "state/entity.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {

/// From now on `entity` takes the route's lanes at lane ends and changes lanes where the route
/// needs it (motion/route_lanes.h), replacing any earlier route.
inline void assign_route(Entity& entity, RoutePlan plan) {
  auto chooser = std::make_shared<const RouteChooser>(std::move(plan));
  entity.chooser = chooser.get();
  // The memo compares the route by address: the old route may be freed and its address
  // reused by a later one, so a standing entity takes its next step anew.
  entity.still_step_valid = false;
  entity.route = std::move(chooser);
  entity.route_progress = RouteProgress{};
}

/// The same for an entity of `state`, which from then on makes the step's pass over the routes.
inline void assign_route(SimState& state, Entity& entity, RoutePlan plan) {
  state.routes_assigned = true;
  assign_route(entity, std::move(plan));
}

}  // namespace corsa::engine::detail
