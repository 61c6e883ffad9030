#pragma once

// The lines across the road that each road starts and ends on. Roads meeting at a joint (one
// road's lanes ending where the next roads' lanes start, at a split of six lanes into five and
// one, say) share one line through all the lane ends there, so that the lanes end and start on
// the same line and meet without a gap; a road whose own lane ends are not all on that shared
// line (within 0.25 m) keeps the line through its own (road_reference.h). Junction paths (one
// lane) take the shared line where their lane's end lies on it, and otherwise end square; once
// the ordinary roads are built, join_ends puts them (and one-lane roads after a road with one lane
// ending there) on the cross-section of the road they join.

#include <functional>
#include <optional>
#include <vector>

#include "network_plan.h"
#include "road_reference.h"

namespace corsa::ngii::detail {

struct RoadEndLines {
  std::optional<EndLine> start;  ///< map frame
  std::optional<EndLine> end;
  /// Whether the line is shared with the roads on the other side: the road then ends on the
  /// line itself, else on its parallel through the reference lane's own end.
  bool start_shared = false;
  bool end_shared = false;
};

/// How many lanes of `road` start (`at_start`) or end beside the others (not at zero width).
size_t lanes_beside(const RoadPlan& road, bool at_start);

/// Per road of `plan` (removed ones get no lines).
std::vector<RoadEndLines> road_end_lines(const NetworkPlan& plan, const Origin& origin);

/// Where a built road's reference line starts or (`at_end`) ends, and its heading (rad) there:
/// the normal through that point is the line its lanes end on. Nothing for a road not built.
struct BuiltEnd {
  Vec2 point;  ///< map frame
  double heading = 0.0;
};
using BuiltEndOf = std::function<std::optional<BuiltEnd>(size_t road, bool at_end)>;

enum class JoinedEnds {
  /// Junction paths (connecting roads of one lane; not the ordinary pieces moved into a
  /// junction), at both ends.
  kJunctionPaths,
  /// Ordinary roads with one lane starting beside the others (any other lanes split off it at
  /// zero width), at their start where no line is shared and the road before them has one
  /// lane ending beside the others (any others merge into it at zero width): one lane on
  /// either side of the joint. Where several such roads merge into it, the one whose end
  /// heading is within 10 degrees of its start and closest to it.
  kOrdinaryStarts,
};

/// The roads `which` names end on the cross-section of the ordinary road their lane leaves or
/// enters, where exactly one does (`end_of`: that road's end normal). Where the surveyed links
/// meet at a corner (10-20 degrees at many junction mouths) a road ending square to its own
/// course left a wedge of unpaved ground on one side of the joint, up to half the lane wide; on
/// the same line the two lane ends meet edge to edge. Replaces those ends' lines in `lines`
/// and returns the roads changed.
std::vector<size_t> join_ends(const NetworkPlan& plan, const BuiltEndOf& end_of, JoinedEnds which,
                              std::vector<RoadEndLines>& lines);

}  // namespace corsa::ngii::detail
