#include "staggered_ends.h"

#include <cmath>

#include "road_plan.h"

namespace corsa::ngii::detail {
namespace {

/// tan(50 degrees): the steepest end line a road end is turned to (road_reference.h).
constexpr double kMaxSkewSlope = 1.19;
/// m: lanes ending this much beyond that line as well are cut.
constexpr double kStaggerMargin = 1.0;

/// Whether no lane of `road` continues at that end, and every lane ends beside the others.
bool dead_end(const LaneIndex& index, const RoadPlan& road, bool at_end) {
  for (const PlanLane& lane : road.lanes) {
    const int key = at_end ? lane.end_node : lane.start_node;
    const auto& other =
        at_end ? index.starting[static_cast<size_t>(key)] : index.ending[static_cast<size_t>(key)];
    if (!other.empty() || (at_end ? lane.end_shape : lane.start_shape) != LaneEnd::kBeside) {
      return false;
    }
  }
  return true;
}

/// Per lane: how far (m) it reaches beyond the lane that reaches least far, less the most a
/// skewed end line could take up; the cut point is across from that shortest lane's end.
struct Stagger {
  std::vector<bool> protrudes;
  Vec2 cut_point;
  Vec2 direction;  ///< the road's direction there (driving direction)
};

Stagger stagger_of(const RoadPlan& road, bool at_end) {
  const Polyline first(road.lanes[0].points);
  const Vec2 d = first.direction(at_end ? first.length() : 0.0);
  const auto end_of = [&](const PlanLane& lane) {
    return xy(at_end ? lane.points.back() : lane.points.front());
  };
  const Vec2 origin = end_of(road.lanes[0]);
  // Along the road, outward from the end: positive = reaching farther.
  const double sign = at_end ? 1.0 : -1.0;
  size_t shortest = 0;
  for (size_t k = 1; k < road.lanes.size(); ++k) {
    if (sign * dot(end_of(road.lanes[k]) - origin, d) <
        sign * dot(end_of(road.lanes[shortest]) - origin, d)) {
      shortest = k;
    }
  }
  const Vec2 base = end_of(road.lanes[shortest]);
  Stagger out{std::vector<bool>(road.lanes.size(), false), base, d};
  for (size_t k = 0; k < road.lanes.size(); ++k) {
    const Vec2 e = end_of(road.lanes[k]) - base;
    const double beyond = sign * dot(e, d);
    out.protrudes[k] = beyond > kMaxSkewSlope * std::abs(cross(d, e)) + kStaggerMargin;
  }
  return out;
}

}  // namespace

void trim_staggered_ends(NetworkPlan& plan) {
  const LaneIndex index(plan);
  const size_t count = plan.roads.size();
  for (size_t r = 0; r < count; ++r) {
    for (const bool at_end : {false, true}) {
      // Re-read every time: the pushes below may reallocate plan.roads.
      if (plan.roads[r].removed || plan.roads[r].junction >= 0 || plan.roads[r].lanes.size() < 2 ||
          !dead_end(index, plan.roads[r], at_end)) {
        continue;
      }
      const Stagger stagger = stagger_of(plan.roads[r], at_end);
      // Each run of neighbouring protruding lanes becomes one road.
      for (size_t k = 0; k < stagger.protrudes.size();) {
        if (!stagger.protrudes[k]) {
          ++k;
          continue;
        }
        RoadPlan piece;
        for (; k < stagger.protrudes.size() && stagger.protrudes[k]; ++k) {
          PlanLane& lane = plan.roads[r].lanes[k];
          const Polyline line(lane.points);
          const double u =
              crossing_u(line, stagger.cut_point, stagger.direction, at_end ? line.length() : 0.0);
          auto [front, back] = split_lane(lane, u, plan.node_keys++);
          piece.lanes.push_back(std::move(at_end ? back : front));
          lane = std::move(at_end ? front : back);
        }
        plan.roads.push_back(std::move(piece));
      }
    }
  }
}

}  // namespace corsa::ngii::detail
