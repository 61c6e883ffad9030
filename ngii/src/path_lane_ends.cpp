#include "path_lane_ends.h"

#include <algorithm>
#include <cmath>

#include "lane_joints.h"
#include "road_plan.h"

namespace corsa::ngii::detail {
namespace {

constexpr double kPathShortOfLane = 0.1;    // m: a border inside the lane's end by more is moved
constexpr double kPathBorderMaxMove = 1.0;  // m a side: a path keeps about its own width
constexpr double kPathEaseMaxSlant = 2.0;   // sideways metres per metre forward (as mouth fills)
// A smoothstep's steepest slope is 1.5 times its rise over its run.
constexpr double kSmoothstepSteepest = 1.5;

/// `from` moved towards `to` by at most `most` (m).
Vec2 towards(Vec2 from, Vec2 to, double most) {
  const double d = norm(to - from);
  return d <= most ? to : from + (to - from) * (most / d);
}

/// The lane's end borders and the path's (left, right) at one end of path r, and how far the
/// path's lie inside the lane's.
struct PathJoint {
  Vec2 lane_left, lane_right, path_left, path_right;
  PathEndShortfall shortfall;
};

/// An end of a path whose borders are moved: the lane across the joint, and how far the path's
/// borders lay inside that lane's before (PathEndShortfall::most).
struct MovedPathEnd {
  bool at_end = false;
  LaneIndex::Ref lane;
  double shortfall = 0.0;
};

std::optional<PathJoint> path_joint(const xodr::Road& lane_road, size_t k, const xodr::Road& path,
                                    bool at_end) {
  const std::vector<Vec2> lane = built_border_points(lane_road, !at_end);
  const std::vector<Vec2> own = built_border_points(path, at_end);
  if (lane.size() < k + 2 || own.size() != 2) {
    return std::nullopt;
  }
  const auto shortfall = path_end_shortfall(lane[k], lane[k + 1], own[0], own[1]);
  if (!shortfall) {
    return std::nullopt;
  }
  return PathJoint{lane[k], lane[k + 1], own[0], own[1], *shortfall};
}

/// Whether a road built again (`again`) is kept over `before`: it neither folds, gains a kink,
/// moves a lane's end more than kLaneEndMoveLimit off its link (or further than before) nor
/// folds on its fitted records where it did not.
bool rebuild_kept(const BuiltRoad& again, const BuiltRoad& before) {
  return !again.folds && again.kinks <= before.kinks &&
         again.end_error <= std::max(kLaneEndMoveLimit, before.end_error) &&
         (!fitted_road_folds(again.road) || fitted_road_folds(before.road));
}

}  // namespace

bool same_end_line(const std::optional<EndLine>& a, const std::optional<EndLine>& b) {
  return a.has_value() == b.has_value() &&
         (!a || (norm(a->point - b->point) < 1e-9 && norm(a->across - b->across) < 1e-9));
}

std::optional<LaneIndex::Ref> single_ordinary_lane_across(
    const NetworkPlan& plan, const LaneIndex& index, size_t r, bool at_end,
    const std::vector<std::optional<BuiltRoad>>& built) {
  const RoadPlan& path = plan.roads[r];
  const int key = at_end ? path.lanes[0].end_node : path.lanes[0].start_node;
  if (key < 0) {
    return std::nullopt;
  }
  const auto& across =
      at_end ? index.starting[static_cast<size_t>(key)] : index.ending[static_cast<size_t>(key)];
  const auto& beside =
      at_end ? index.ending[static_cast<size_t>(key)] : index.starting[static_cast<size_t>(key)];
  if (across.size() != 1 || beside.size() != 1 || beside.front().road != static_cast<int>(r)) {
    return std::nullopt;
  }
  const size_t o = static_cast<size_t>(across.front().road);
  const RoadPlan& road = plan.roads[o];
  // The road's end at the joint: its start after the path's end, its end before its start.
  if (road.removed || (road.junction >= 0 && !road.absorbed) || !built[o] ||
      effective_end(road, static_cast<size_t>(across.front().lane), at_end) != LaneEnd::kBeside) {
    return std::nullopt;
  }
  return across.front();
}

std::optional<PathEndShortfall> path_end_shortfall(Vec2 lane_left, Vec2 lane_right, Vec2 path_left,
                                                   Vec2 path_right) {
  // Across the path's end, + left.
  const Vec2 across_end = path_left - path_right;
  const double span = norm(across_end);
  if (span <= 0.0) {
    return std::nullopt;
  }
  const Vec2 left = across_end * (1.0 / span);
  return PathEndShortfall{dot(lane_left - path_left, left), dot(path_right - lane_right, left)};
}

PathEndTargets path_end_targets(Vec2 lane_left, Vec2 lane_right, Vec2 path_left, Vec2 path_right,
                                double path_length) {
  double most = kPathBorderMaxMove;
  // The ease back is longer for a larger move, except where the path's length caps it: there
  // the move is held to what that ease slants across at kPathEaseMaxSlant.
  const double ramp = end_border_ramp(most, path_length);
  most = std::min(most, kPathEaseMaxSlant * ramp / kSmoothstepSteepest);
  return {towards(path_left, lane_left, most), towards(path_right, lane_right, most)};
}

void paths_meet_lane_ends(const NetworkPlan& plan, const LaneIndex& index,
                          const std::vector<RoadEndLines>& offered,
                          const std::vector<RoadEndLines>& used, const RebuildPath& rebuild,
                          std::vector<std::optional<BuiltRoad>>& built) {
  for (size_t r = 0; r < plan.roads.size(); ++r) {
    const RoadPlan& path = plan.roads[r];
    if (path.removed || path.junction < 0 || path.absorbed || path.lanes.size() != 1 || !built[r]) {
      continue;
    }
    EndBorders targets;
    std::vector<MovedPathEnd> moved;
    for (const bool at_end : {false, true}) {
      const std::optional<EndLine>& given = at_end ? offered[r].end : offered[r].start;
      if (!given || !same_end_line(given, at_end ? used[r].end : used[r].start)) {
        continue;  // on its own line, or never given one
      }
      const auto lane = single_ordinary_lane_across(plan, index, r, at_end, built);
      if (!lane) {
        continue;
      }
      const size_t k = static_cast<size_t>(lane->lane);
      const auto joint =
          path_joint(built[static_cast<size_t>(lane->road)]->road, k, built[r]->road, at_end);
      if (!joint || joint->shortfall.most() <= kPathShortOfLane) {
        continue;
      }
      const PathEndTargets to =
          path_end_targets(joint->lane_left, joint->lane_right, joint->path_left, joint->path_right,
                           built[r]->road.length);
      (at_end ? targets.end : targets.start) = {to.left, to.right};
      moved.push_back({at_end, *lane, joint->shortfall.most()});
    }
    if (targets.empty()) {
      continue;
    }
    BuiltRoad again = rebuild(r, targets);
    if (!rebuild_kept(again, *built[r])) {
      continue;
    }
    // The joint's gap probe: the rebuilt path's borders lie no further inside the lane's.
    const bool no_worse = std::all_of(moved.begin(), moved.end(), [&](const MovedPathEnd& end) {
      const auto joint = path_joint(built[static_cast<size_t>(end.lane.road)]->road,
                                    static_cast<size_t>(end.lane.lane), again.road, end.at_end);
      return joint && joint->shortfall.most() <= end.shortfall;
    });
    if (no_worse) {
      built[r] = std::move(again);
    }
  }
}

void ordinary_ends_on_paths(const NetworkPlan& plan, const LaneIndex& index,
                            const std::vector<RoadEndLines>& offered,
                            const std::vector<RoadEndLines>& used, const BuiltEndOf& end_of,
                            const RebuildRoad& rebuild, std::vector<RoadEndLines>& lines,
                            std::vector<std::optional<BuiltRoad>>& built) {
  for (size_t r = 0; r < plan.roads.size(); ++r) {
    const RoadPlan& path = plan.roads[r];
    if (path.removed || path.junction < 0 || path.absorbed || path.lanes.size() != 1) {
      continue;
    }
    for (const bool at_end : {false, true}) {
      const std::optional<EndLine>& given = at_end ? offered[r].end : offered[r].start;
      if (same_end_line(given, at_end ? used[r].end : used[r].start)) {
        continue;  // on the joined line, or never given one
      }
      const auto across = single_ordinary_lane_across(plan, index, r, at_end, built);
      if (!across) {
        continue;
      }
      const size_t o = static_cast<size_t>(across->road);
      const RoadPlan& road = plan.roads[o];
      // The road's end at the joint: its start after the path's end, its end before its start.
      const bool road_start = at_end;
      if (lanes_beside(road, road_start) != 1) {
        continue;
      }
      const auto end = end_of(r, at_end);
      if (!end) {
        continue;
      }
      RoadEndLines moved = lines[o];
      (road_start ? moved.start : moved.end) =
          EndLine{end->point, Vec2{-std::sin(end->heading), std::cos(end->heading)}};
      (road_start ? moved.start_shared : moved.end_shared) = true;
      BuiltRoad again = rebuild(o, moved);
      if (rebuild_kept(again, *built[o])) {
        built[o] = std::move(again);
        lines[o] = moved;
      }
    }
  }
}

}  // namespace corsa::ngii::detail
