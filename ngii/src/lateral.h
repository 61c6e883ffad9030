#pragma once

// Lateral structure of the lane links: the L/R neighbour repairs, the lateral groups (walk
// L_LinkID to the leftmost link, then follow R_LinkID) and their split into runs of lanes that
// run side by side over the same stretch, which become roads (RoadNo is empty in real data).

#include <string>
#include <vector>

#include "correction_log.h"
#include "network.h"
#include "polyline.h"

namespace corsa::ngii::detail {

/// How a lane of a run begins or ends: at its own place beside the others, or out of (into)
/// its neighbour, sharing that neighbour's A1 node (a lane that splits off or merges in).
enum class LaneEnd : uint8_t {
  kBeside,
  kFromLeft,   ///< shares its end node with its left neighbour: width 0 there
  kFromRight,  ///< shares its end node with its right neighbour
};

/// Laterally adjacent links that run side by side from end to end: one road's lanes, left to
/// right. A lane that splits off a neighbour (both start at one node) or merges into one (both
/// end at one node) belongs to the same road; it widens from (narrows to) zero width there.
struct LaneRun {
  std::vector<int> links;
  std::vector<LaneEnd> starts;  ///< per link: how it begins
  std::vector<LaneEnd> ends;    ///< per link: how it ends
  int group = 0;                ///< index of the lateral group it came from
  int position = 0;             ///< index of its first link within that group
};

struct LateralStructure {
  std::vector<std::vector<int>> groups;  ///< lateral groups, left to right
  std::vector<LaneRun> runs;
};

/// How link b lies beside link a (b's samples projected onto a).
struct Side {
  bool overlap = false;        ///< some sample of b falls beside a (not past its ends)
  bool same_direction = true;  ///< b runs the same way wherever it is beside a
  double lat_start = 0.0;      ///< lateral offset (m, + left) of b's start from a
  double lat_end = 0.0;
  double lat_mid = 0.0;
  double lat_min = 0.0;
  double lat_max = 0.0;
  double stagger_start = 0.0;  ///< how far (m) b starts after a's start (negative: before)
  double stagger_end = 0.0;    ///< how far b ends before a's end (negative: after)
  double lat_mean = 0.0;       ///< mean |lateral| over the samples beside a
};

/// How polyline b lies beside polyline a, from 9 samples of b projected onto a.
Side side_of(const Polyline& a, const Polyline& b);

/// Clears L/R pointers that cannot be neighbours (a successor, the opposite direction, far
/// away), makes every pair reciprocal (choosing the geometrically better partner when two
/// disagree), and fills missing pointers between parallel same-direction ordinary links.
void repair_neighbours(Network& network, CorrectionLog& log);

/// Groups and runs from the repaired pointers, deterministic in link order.
LateralStructure lateral_structure(const Network& network);

}  // namespace corsa::ngii::detail
