#include "end_lines.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "polyline.h"
#include "union_find.h"

namespace corsa::ngii::detail {
namespace {

/// The lane's end point (`at_end`) or start point in the map frame.
Vec2 end_point(const PlanLane& lane, bool at_end, const Origin& origin) {
  const Point3& p = at_end ? lane.points.back() : lane.points.front();
  return Vec2{p.x - origin.x, p.y - origin.y};
}

constexpr double kMergeInLine = 10.0 * M_PI / 180.0;  // rad: merge_in_line's largest turn

/// Of the one-lane ordinary roads `joined` ending where `lane` starts (a merge of one-lane
/// roads), the end of the one whose end heading lies closest to the lane's start heading, where
/// within kMergeInLine. K-City's road 317 starts where road 318 ends 4.3 degrees off its course
/// and road 316 32 degrees off: started square to its own course, it left a wedge beside both
/// (0.82 m along its start edge); on the end line of the road in line with it, that road's end
/// covers its start edge, and the other road's end meets the two at its corner.
std::optional<BuiltEnd> merge_in_line(const NetworkPlan& plan, const std::set<int>& joined,
                                      const PlanLane& lane, const BuiltEndOf& end_of) {
  const Polyline line(lane.points);
  if (line.length() <= 0.0) {
    return std::nullopt;
  }
  const Vec2 d = line.direction(0.0);
  const double heading = std::atan2(d.y, d.x);
  std::optional<BuiltEnd> best;
  double best_off = kMergeInLine;
  for (const int road : joined) {
    if (lanes_beside(plan.roads[static_cast<size_t>(road)], false) != 1) {
      return std::nullopt;
    }
    const auto end = end_of(static_cast<size_t>(road), true);
    if (!end) {
      return std::nullopt;
    }
    const double off = std::abs(std::remainder(end->heading - heading, 2.0 * M_PI));
    if (off < best_off) {
      best = end;
      best_off = off;
    }
  }
  return best;
}

/// Road end slots: 2r for the start of road r, 2r + 1 for its end; topology keys follow.
size_t slot(size_t road, bool at_end) { return 2 * road + (at_end ? 1 : 0); }

}  // namespace

/// How many lanes of `road` start (`at_start`) or end beside the others (not at zero width).
size_t lanes_beside(const RoadPlan& road, bool at_start) {
  size_t count = 0;
  for (size_t k = 0; k < road.lanes.size(); ++k) {
    count += effective_end(road, k, at_start) == LaneEnd::kBeside;
  }
  return count;
}

std::vector<RoadEndLines> road_end_lines(const NetworkPlan& plan, const Origin& origin) {
  const size_t roads = plan.roads.size();
  // Road ends and the keys of their lanes' ends beside the others, joined into joints.
  UnionFind joints(2 * roads + static_cast<size_t>(plan.node_keys));
  std::vector<std::optional<Vec2>> key_point(static_cast<size_t>(plan.node_keys));
  for (size_t r = 0; r < roads; ++r) {
    const RoadPlan& road = plan.roads[r];
    if (road.removed) {
      continue;
    }
    for (size_t k = 0; k < road.lanes.size(); ++k) {
      for (const bool at_end : {false, true}) {
        if (effective_end(road, k, !at_end) != LaneEnd::kBeside) {
          continue;
        }
        const PlanLane& lane = road.lanes[k];
        const size_t key = static_cast<size_t>(at_end ? lane.end_node : lane.start_node);
        joints.unite(slot(r, at_end), 2 * roads + key);
        if (!key_point[key]) {
          key_point[key] = end_point(lane, at_end, origin);
        }
      }
    }
  }
  // Every joint's points (one per key), and the line through them.
  std::map<size_t, std::vector<Vec2>> points;
  for (size_t key = 0; key < key_point.size(); ++key) {
    if (key_point[key]) {
      points[joints.find(2 * roads + key)].push_back(*key_point[key]);
    }
  }
  std::map<size_t, std::optional<EndLine>> shared;
  for (const auto& [joint, p] : points) {
    shared[joint] = end_line(p);
  }
  std::vector<RoadEndLines> out(roads);
  for (size_t r = 0; r < roads; ++r) {
    const RoadPlan& road = plan.roads[r];
    // Connecting roads (one lane each) end on the line of the road they leave or enter where
    // their lane end lies on it, so that they start where the approach's lanes end, with no
    // wedge between a skewed stop line and a square start; the bend's even turn (road_end_bend)
    // keeps their inner edge from folding. Elsewhere they end square.
    if (road.removed) {
      continue;
    }
    for (const bool at_end : {false, true}) {
      std::vector<Vec2> own;
      for (size_t k = 0; k < road.lanes.size(); ++k) {
        if (effective_end(road, k, !at_end) == LaneEnd::kBeside) {
          own.push_back(end_point(road.lanes[k], at_end, origin));
        }
      }
      std::optional<EndLine>& line = at_end ? out[r].end : out[r].start;
      const auto found = shared.find(joints.find(slot(r, at_end)));
      const std::optional<EndLine>* joint = found == shared.end() ? nullptr : &found->second;
      if (joint != nullptr && *joint && !own.empty() &&
          std::all_of(own.begin(), own.end(), [&](Vec2 p) { return on_end_line(**joint, p); })) {
        line = **joint;
        (at_end ? out[r].end_shared : out[r].start_shared) = true;
      } else {
        line = end_line(own);
      }
    }
  }
  return out;
}

std::vector<size_t> join_ends(const NetworkPlan& plan, const BuiltEndOf& end_of, JoinedEnds which,
                              std::vector<RoadEndLines>& lines) {
  const LaneIndex index(plan);
  const auto ordinary = [&](int road) {
    const RoadPlan& p = plan.roads[static_cast<size_t>(road)];
    return !p.removed && (p.junction < 0 || p.absorbed);
  };
  const bool paths = which == JoinedEnds::kJunctionPaths;
  std::vector<size_t> changed;
  for (size_t r = 0; r < plan.roads.size(); ++r) {
    const RoadPlan& road = plan.roads[r];
    if (road.removed || ordinary(static_cast<int>(r)) == paths) {
      continue;
    }
    // The road's one lane; an ordinary road's other lanes may start at zero width beside it
    // (splitting off it: their start lies on that lane's, so the road's start line is its).
    if (road.lanes.size() != 1 && (paths || lanes_beside(road, true) != 1)) {
      continue;
    }
    size_t beside = 0;
    while (!paths && beside + 1 < road.lanes.size() &&
           effective_end(road, beside, true) != LaneEnd::kBeside) {
      ++beside;
    }
    const PlanLane& lane = road.lanes[beside];
    bool any = false;
    for (const bool at_end : {false, true}) {
      // Ordinary roads: only their start, and only where no line is shared there
      // (a joint of one lane on either side).
      if (!paths && (at_end || lines[r].start_shared)) {
        continue;
      }
      // The lanes on the other side of the joint: ending where the road starts, starting where
      // it ends; only ordinary ones that end there beside their neighbours (not at zero width).
      // Before an ordinary road, a lane merging into its neighbour there ends on that lane's
      // end, so the road it belongs to has one lane end there, and its end line.
      const int key = at_end ? lane.end_node : lane.start_node;
      if (key < 0) {
        continue;
      }
      const auto& refs = at_end ? index.starting[static_cast<size_t>(key)]
                                : index.ending[static_cast<size_t>(key)];
      std::set<int> joined;
      bool usable = true;
      for (const LaneIndex::Ref& ref : refs) {
        if (!ordinary(ref.road)) {
          continue;
        }
        const RoadPlan& other = plan.roads[static_cast<size_t>(ref.road)];
        const bool beside =
            effective_end(other, static_cast<size_t>(ref.lane), at_end) == LaneEnd::kBeside;
        usable = usable && ref.road != static_cast<int>(r) && (beside || !paths);
        joined.insert(ref.road);
      }
      // An ordinary road joins only a road with one lane there beside the others (a piece cut
      // off a wider road's end keeps the line it was cut on); where several such roads merge
      // into it, the one most in line with it (merge_in_line).
      std::optional<BuiltEnd> end;
      if (usable && joined.size() == 1 &&
          (paths || lanes_beside(plan.roads[static_cast<size_t>(*joined.begin())], at_end) == 1)) {
        // The road's start meets that road's end, and its end that road's start.
        end = end_of(static_cast<size_t>(*joined.begin()), !at_end);
      } else if (usable && !paths && joined.size() > 1) {
        end = merge_in_line(plan, joined, lane, end_of);
      }
      if (!end) {
        continue;
      }
      (at_end ? lines[r].end : lines[r].start) =
          EndLine{end->point, Vec2{-std::sin(end->heading), std::cos(end->heading)}};
      (at_end ? lines[r].end_shared : lines[r].start_shared) = true;
      any = true;
    }
    if (any) {
      changed.push_back(r);
    }
  }
  return changed;
}

}  // namespace corsa::ngii::detail
