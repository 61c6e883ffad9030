#pragma once

// Following a route through junctions (OpenSCENARIO 1.3 §6.6 routes, §7.4.4.1 AssignRouteAction):
// at a lane end with several successors the entity takes the one the route drives on.

#include <vector>

#include "corsa/xodr/route.h"
#include "motion/lane_follow.h"

namespace corsa::engine::detail {

class RouteChooser final : public LaneChooser {
 public:
  explicit RouteChooser(std::vector<xodr::RouteStep> steps) : steps_(std::move(steps)) {}

  /// The candidate on the route entered in the route's direction; else one on a road of the
  /// route (the route changes lanes there); else the straightest (the entity left its route).
  size_t choose(const xodr::Map& map, const LaneFollow& lane,
                std::span<const xodr::LaneEnd> candidates) const override;

  const std::vector<xodr::RouteStep>& steps() const { return steps_; }

 private:
  std::vector<xodr::RouteStep> steps_;
};

}  // namespace corsa::engine::detail
