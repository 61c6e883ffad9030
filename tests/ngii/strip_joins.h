#pragma once

// Whether the centre strips (restricted lanes named `ngii:centre-strip`) continue into each other
// in the lane graph where they touch: for every strip lane end, the other strip lane ends whose
// inner edge (the border towards the reference line) lies within 0.3 m of its own, running the
// same way (one road's end at the other's start: strips are lane +1 of roads of one direction,
// so the same ends of two roads are the two halves of one double centre line); each such
// touching pair counts once, joined when the map's lane graph joins the two ends. Computed from
// the map only (Map::lane_graph, lane spans, world poses).

#include <cstddef>
#include <string>

#include "corsa/xodr/map.h"

namespace corsa::test {

struct StripJoinFigures {
  size_t strip_ends = 0;       ///< ends of strip lanes
  size_t touching = 0;         ///< pairs of strip ends that touch
  size_t joined = 0;           ///< of those, joined in the lane graph
  std::string unjoined;        ///< the first touching pair not joined ("road:lane end -> ...")
  double outer_gap_max = 0.0;  ///< largest distance (m) of the outer edges at a joined pair
  std::string outer_worst;     ///< where it is
};

StripJoinFigures strip_joins(const xodr::Map& map);

}  // namespace corsa::test
