#include "staggered_ends.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "road_plan.h"
#include "road_reference.h"

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

/// m: lane ends of two roads this close are one (the same node).
constexpr double kSameEnd = 0.05;
/// m: lanes ending farther off their neighbours' end line than this are left alone (another
/// mechanism, or none, must take them: a lane section's worth of difference is not a stop line).
constexpr double kMaxOffLine = 4.0;

/// A cut of one road end: which lanes are cut, and the line they are cut along.
struct OffLineCut {
  std::vector<bool> cut;
  Vec2 point;
  Vec2 normal;  ///< square to the cut line (crossing_u's direction)
};

/// The lane ends beside the others of the ordinary roads on the other side of road `r`'s end
/// (`at_end`) or start: the roads with a lane starting where one of its lanes ends (ending where
/// one starts), their other lanes included.
std::vector<Vec2> far_side_ends(const NetworkPlan& plan, const LaneIndex& index, size_t r,
                                bool at_end) {
  std::vector<int> roads;
  for (const PlanLane& lane : plan.roads[r].lanes) {
    const int key = at_end ? lane.end_node : lane.start_node;
    if (key < 0) {
      continue;
    }
    for (const LaneIndex::Ref& ref : at_end ? index.starting[static_cast<size_t>(key)]
                                            : index.ending[static_cast<size_t>(key)]) {
      const RoadPlan& other = plan.roads[static_cast<size_t>(ref.road)];
      if (ref.road != static_cast<int>(r) && !other.removed && other.junction < 0 &&
          std::find(roads.begin(), roads.end(), ref.road) == roads.end()) {
        roads.push_back(ref.road);
      }
    }
  }
  std::vector<Vec2> out;
  for (const int o : roads) {
    const RoadPlan& other = plan.roads[static_cast<size_t>(o)];
    for (size_t k = 0; k < other.lanes.size(); ++k) {
      if (effective_end(other, k, at_end) == LaneEnd::kBeside) {
        const PlanLane& lane = other.lanes[k];
        out.push_back(xy(at_end ? lane.points.front() : lane.points.back()));
      }
    }
  }
  return out;
}

/// The line `ends` (one road's lane ends) are cut along: the line through the most of them, or,
/// where the roads on the other side (`far`) give a line through more ends of the joint that
/// still runs through two or more of the road's own, that one. Within the 0.25 m end_line
/// allows, three lane ends of which one ends 0.39 m short of the others' stop line lie on a line
/// tilted by 4 degrees (Sangam's road 557, before the 0.39 m link that continues its third
/// lane); the roads after the joint start on the stop line, and the lanes between the two lines
/// left a wedge 0.25 m deep at the joint. Against the joint's line the short lane is stray.
std::optional<EndLine> cut_line(const std::vector<Vec2>& ends, const std::vector<Vec2>& far) {
  std::optional<EndLine> own = end_line(ends);
  std::vector<Vec2> all = ends;
  for (const Vec2& p : far) {
    const bool repeated = std::any_of(ends.begin(), ends.end(),
                                      [&](const Vec2& e) { return norm(e - p) < kSameEnd; });
    if (!repeated) {
      all.push_back(p);
    }
  }
  const std::optional<EndLine> joint = all.size() > ends.size() ? end_line(all) : std::nullopt;
  if (!own || !joint) {
    return own;
  }
  const auto on = [&](const EndLine& line) {
    return std::count_if(ends.begin(), ends.end(), [&](Vec2 e) { return on_end_line(line, e); });
  };
  return on(*joint) >= 2 && on(*joint) < on(*own) ? joint : own;
}

/// Where lanes of `road` end off the line through the others' ends at that end (all lanes
/// ending beside each other, the stray ones on one side of the line by about the same amount);
/// `far`: the lane ends on the other side of the joint (cut_line).
std::optional<OffLineCut> off_line_cut(const RoadPlan& road, bool at_end,
                                       const std::vector<Vec2>& far) {
  const size_t n = road.lanes.size();
  std::vector<Vec2> ends;
  for (size_t k = 0; k < n; ++k) {
    if (effective_end(road, k, !at_end) != LaneEnd::kBeside) {
      return std::nullopt;
    }
    const PlanLane& lane = road.lanes[k];
    ends.push_back(xy(at_end ? lane.points.back() : lane.points.front()));
  }
  const std::optional<EndLine> line = cut_line(ends, far);
  if (!line) {
    return std::nullopt;
  }
  // Outward (beyond the road's end) along the road.
  const Polyline first(road.lanes[0].points);
  const Vec2 out = (at_end ? 1.0 : -1.0) * first.direction(at_end ? first.length() : 0.0);
  Vec2 normal{line->across.y, -line->across.x};
  if (dot(normal, out) < 0.0) {
    normal = -1.0 * normal;
  }
  if (dot(normal, out) < 0.5) {
    return std::nullopt;  // an end line along the road: nothing sensible to cut
  }
  std::vector<double> off(n);
  std::vector<size_t> stray;
  for (size_t k = 0; k < n; ++k) {
    off[k] = dot(ends[k] - line->point, normal);  // > 0: beyond the line
    if (!on_end_line(*line, ends[k])) {
      stray.push_back(k);
    }
  }
  if (stray.empty() || stray.size() + 2 > n + 1) {
    return std::nullopt;
  }
  const auto [low, high] = std::minmax_element(stray.begin(), stray.end(),
                                               [&](size_t a, size_t b) { return off[a] < off[b]; });
  if ((off[*low] < 0.0) != (off[*high] < 0.0) || off[*high] - off[*low] > 0.25 ||
      std::max(std::abs(off[*low]), std::abs(off[*high])) > kMaxOffLine) {
    return std::nullopt;
  }
  OffLineCut cut{std::vector<bool>(n, false), line->point, normal};
  if (off[*low] > 0.0) {
    // Reaching beyond: the stray lanes are cut on the line.
    for (const size_t k : stray) {
      cut.cut[k] = true;
    }
  } else {
    // Ending short: the others are cut on the parallel through the stray ends.
    cut.point = line->point + off[*high] * normal;
    for (size_t k = 0; k < n; ++k) {
      cut.cut[k] = std::find(stray.begin(), stray.end(), k) == stray.end();
    }
  }
  return cut;
}

/// Cuts the lanes `cut` of road `r` at that end along the line; each run of neighbouring cut
/// lanes becomes a road of its own (appended to `plan`).
void cut_off_lane_runs(NetworkPlan& plan, size_t r, bool at_end, const std::vector<bool>& cut,
                       Vec2 point, Vec2 normal) {
  for (size_t k = 0; k < cut.size();) {
    if (!cut[k]) {
      ++k;
      continue;
    }
    RoadPlan piece;
    for (; k < cut.size() && cut[k]; ++k) {
      PlanLane& lane = plan.roads[r].lanes[k];
      const Polyline line(lane.points);
      const double u = crossing_u(line, point, normal, at_end ? line.length() : 0.0);
      auto [front, back] = split_lane(lane, u, plan.node_keys++);
      piece.lanes.push_back(std::move(at_end ? back : front));
      lane = std::move(at_end ? front : back);
    }
    plan.roads.push_back(std::move(piece));
  }
}

}  // namespace

void trim_off_line_ends(NetworkPlan& plan) {
  const size_t count = plan.roads.size();
  // The far sides' lane ends before any cut (a cut moves the cut road's lane ends).
  const LaneIndex index(plan);
  std::vector<std::vector<Vec2>> far(2 * count);
  for (size_t r = 0; r < count; ++r) {
    if (!plan.roads[r].removed && plan.roads[r].junction < 0) {
      far[2 * r] = far_side_ends(plan, index, r, false);
      far[2 * r + 1] = far_side_ends(plan, index, r, true);
    }
  }
  for (size_t r = 0; r < count; ++r) {
    for (const bool at_end : {false, true}) {
      const RoadPlan& road = plan.roads[r];
      if (road.removed || road.junction >= 0 || road.lanes.size() < 3) {
        continue;
      }
      if (const auto cut = off_line_cut(road, at_end, far[2 * r + (at_end ? 1 : 0)])) {
        cut_off_lane_runs(plan, r, at_end, cut->cut, cut->point, cut->normal);
      }
    }
  }
}

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
      cut_off_lane_runs(plan, r, at_end, stagger.protrudes, stagger.cut_point, stagger.direction);
    }
  }
}

}  // namespace corsa::ngii::detail
