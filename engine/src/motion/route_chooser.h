#pragma once

// Following a route through junctions (OpenSCENARIO 1.3 §6.6 routes, §7.4.4.1 AssignRouteAction):
// at a lane end with several successors the entity takes the one the route drives on.

#include <optional>
#include <string>
#include <vector>

#include "corsa/xodr/route.h"
#include "corsa/xosc/common.h"
#include "lanes/lane_follow.h"

namespace corsa::engine::detail {

/// A route laid onto the map, as an entity follows it.
struct RoutePlan {
  std::vector<xodr::RouteStep> steps;
  /// Per waypoint after the first: the index of the step that ends at it (the last step of the
  /// leg leading there). The entity should be on that step's lane when it passes the waypoint.
  std::vector<size_t> waypoint_steps;
  std::string name;     ///< the route's name, for messages
  xosc::Source source;  ///< where the route (or the action that made it) is written
};

class RouteChooser final : public LaneChooser {
 public:
  explicit RouteChooser(RoutePlan plan) : plan_(std::move(plan)) {}

  /// The candidate on the route entered in the route's direction; else one on a road of the
  /// route (the route changes lanes there); else the straightest (the entity left its route).
  size_t choose(const xodr::Map& map, const LaneFollow& lane,
                std::span<const xodr::LaneEnd> candidates) const override;

  /// When no candidate is on a road of the route (a lateral action holds the entity in another
  /// lane): the successor on the route of the route's lane in the same section and direction,
  /// when the route leaves the section there. The entity takes the route's way from that lane,
  /// keeping its lateral place (a lane change under way across a junction goes on along the
  /// route's connecting road): §6.8, routes define the decision behaviour at junctions.
  std::optional<LaneRedirect> redirect(const xodr::Map& map, const LaneFollow& lane,
                                       std::span<const xodr::LaneEnd> candidates) const override;

  const std::vector<xodr::RouteStep>& steps() const { return plan_.steps; }
  const RoutePlan& plan() const { return plan_; }

 private:
  RoutePlan plan_;
};

}  // namespace corsa::engine::detail
