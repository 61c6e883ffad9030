#pragma once

// The lines across the road that each road starts and ends on. Roads meeting at a joint (one
// road's lanes ending where the next roads' lanes start, at a split of six lanes into five and
// one, say) share one line through all the lane ends there, so that the lanes end and start on
// the same line and meet without a gap; a road whose own lane ends are not all on that shared
// line (within 0.25 m) keeps the line through its own (road_reference.h). Junction paths (one
// lane) take the shared line where their lane's end lies on it, and otherwise end square.

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

/// Per road of `plan` (removed ones get no lines).
std::vector<RoadEndLines> road_end_lines(const NetworkPlan& plan, const Origin& origin);

}  // namespace corsa::ngii::detail
