#pragma once

// Where junction paths of one lane meet the one ordinary lane across their ends, edge to edge.
// A path on the joined road's line takes the width of the lane it leaves or enters
// (match_path_ends: the lane's end width times the cosine of the angle its link's first segment
// makes with the road's end heading, which the road builder divides by the cosine of the angle
// its lane's direction, a chord of its own stretch of its smoothed line, makes with the bent
// reference line at the end station). Where a path turns sharply right after its first vertex
// the two still leave it narrower than the lane: K-City's path 460 leaves road 322's 6.58 m lane
// end 50 degrees off by its first segment and started 0.20 / 0.12 m inside the lane's borders,
// a shoulder beside it on each side. Its borders there are moved onto the lane's (road_builder.h
// EndBorders), at most a metre a side, so that a path far narrower than a flared lane end keeps
// about its own width rather than widening to the whole end and easing back over a metre or
// two. A path that keeps its own line at an end has the ordinary road take that line instead.

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "end_lines.h"
#include "network_plan.h"
#include "road_builder.h"

namespace corsa::ngii::detail {

/// m: farthest a lane end may move off its link's end where a road is built again on other
/// lines or borders.
inline constexpr double kLaneEndMoveLimit = 0.1;

/// Whether two end lines are the same: both absent, or through the same point in the same
/// direction (within 1e-9 m).
bool same_end_line(const std::optional<EndLine>& a, const std::optional<EndLine>& b);

/// The one ordinary lane (or lane of an absorbed path) across the joint at junction path r's
/// start or (`at_end`) end, where r's one lane alone meets it there and that lane ends (or
/// starts) there beside the others of its road (not at zero width), and its road is built.
std::optional<LaneIndex::Ref> single_ordinary_lane_across(
    const NetworkPlan& plan, const LaneIndex& index, size_t r, bool at_end,
    const std::vector<std::optional<BuiltRoad>>& built);

/// How far a path's end borders lie inside a lane's end borders (m, + inside), measured across
/// the path's end; nothing where the path's end has no width.
struct PathEndShortfall {
  double left = 0.0;
  double right = 0.0;
  double most() const { return std::max(left, right); }
};
std::optional<PathEndShortfall> path_end_shortfall(Vec2 lane_left, Vec2 lane_right, Vec2 path_left,
                                                   Vec2 path_right);

/// Where a path's end borders (left, right) are to lie so that it meets the lane's end
/// borders: on them where each lies within kPathBorderMaxMove (1 m), else that far towards
/// them; and no further than the ease back to the path's own borders (road_builder.h
/// end_border_ramp over `path_length`) keeps within 2 m sideways per metre forward.
struct PathEndTargets {
  Vec2 left;
  Vec2 right;
};
PathEndTargets path_end_targets(Vec2 lane_left, Vec2 lane_right, Vec2 path_left, Vec2 path_right,
                                double path_length);

/// Junction path r built again with its end borders moved (EndBorders), on the lines it was
/// built on.
using RebuildPath = std::function<BuiltRoad(size_t r, const EndBorders& targets)>;

/// Each junction path of one lane on the joined road's line at an end (`offered`, `used`),
/// the only lane that ordinary lane leads into or comes from, whose border there lies more
/// than 0.1 m inside the lane's end is built again with its borders moved towards the lane's
/// (path_end_targets). Kept where the path neither folds, gains a kink nor moves its lane's end
/// more than kLaneEndMoveLimit off its link, and its shortfall at each moved end is no larger
/// than before.
void paths_meet_lane_ends(const NetworkPlan& plan, const LaneIndex& index,
                          const std::vector<RoadEndLines>& offered,
                          const std::vector<RoadEndLines>& used, const RebuildPath& rebuild,
                          std::vector<std::optional<BuiltRoad>>& built);

/// Road o built again on `lines` (its other borders as they were).
using RebuildRoad = std::function<BuiltRoad(size_t o, const RoadEndLines& lines)>;

/// Where a junction path keeps its own line at an end though it was given the joined road's
/// (`offered`, `used`: build_joined could not turn it onto that line within its length), the
/// ordinary road on the other side of the joint takes the path's line instead, bent to it at
/// its own end: the path and the road then meet edge to edge, where the path's square end
/// left a wedge on one side of the joint (K-City's start grid: a path 14 degrees off the
/// road it enters, 2.3 m of the road's start open). Only where the road has one lane there
/// beside the others and nothing but the path meets it there, and kept where the road neither
/// folds, gains a kink nor moves its lane's end off its link. The refit moves the road's other
/// end by a millimetre or so (the fit runs from the road's start, its end heading fitted),
/// where roads meeting it there were built on where it was: kept all the same, as the rebuild
/// closes a wedge of up to 0.75 m along the lane's edge at the path (K-City's road 187).
void ordinary_ends_on_paths(const NetworkPlan& plan, const LaneIndex& index,
                            const std::vector<RoadEndLines>& offered,
                            const std::vector<RoadEndLines>& used, const BuiltEndOf& end_of,
                            const RebuildRoad& rebuild, std::vector<RoadEndLines>& lines,
                            std::vector<std::optional<BuiltRoad>>& built);

}  // namespace corsa::ngii::detail
