#include "road_plan.h"

#include <algorithm>

namespace corsa::ngii::detail {

LaneEnd effective_end(const RoadPlan& plan, size_t k, bool at_start) {
  const LaneEnd shape = at_start ? plan.lanes[k].start_shape : plan.lanes[k].end_shape;
  if ((shape == LaneEnd::kFromLeft && k == 0) ||
      (shape == LaneEnd::kFromRight && k + 1 == plan.lanes.size())) {
    return LaneEnd::kBeside;
  }
  return shape;
}

double crossing_u(const Polyline& line, Vec2 c, Vec2 direction, double fallback) {
  double best = 1e300;
  double u = fallback;
  const auto& p = line.points();
  for (size_t i = 0; i + 1 < p.size(); ++i) {
    const double g0 = dot(xy(p[i]) - c, direction);
    const double g1 = dot(xy(p[i + 1]) - c, direction);
    if ((g0 <= 0.0) != (g1 <= 0.0)) {
      const double f = g0 / (g0 - g1);
      const Vec2 q = xy(p[i]) + f * (xy(p[i + 1]) - xy(p[i]));
      if (norm(q - c) < best) {
        best = norm(q - c);
        u = line.u()[i] + f * (line.u()[i + 1] - line.u()[i]);
      }
    }
  }
  return u;
}

std::pair<PlanLane, PlanLane> split_lane(const PlanLane& lane, double u, int key) {
  const Polyline line(lane.points);
  const double length = line.length();
  u = std::clamp(u, 0.01, std::max(0.01, length - 0.01));
  PlanLane front{line.slice(0.0, u), {}, {}, lane.start_node, key, {}, {}, lane.start_shape,
                 LaneEnd::kBeside};
  PlanLane back{line.slice(u, length), {}, {}, key, lane.end_node, {}, {}, LaneEnd::kBeside,
                lane.end_shape};
  for (size_t j = 0; j < lane.links.size(); ++j) {
    const double start = lane.link_starts[j];
    const double end = j + 1 < lane.links.size() ? lane.link_starts[j + 1] : length;
    if (start < u || j == 0) {
      front.links.push_back(lane.links[j]);
      front.link_starts.push_back(start);
    }
    if (end > u || j + 1 == lane.links.size()) {
      back.links.push_back(lane.links[j]);
      back.link_starts.push_back(std::max(0.0, start - u));
    }
  }
  return {std::move(front), std::move(back)};
}

}  // namespace corsa::ngii::detail
