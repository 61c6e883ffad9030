#pragma once

// Unpaved wedges and slivers where lanes join (a junction path starting square beside an
// approach road that ends on a skewed stop line, a path narrower than the lane it leaves): for
// each join of two lanes in the lane graph, the lane's end edge is moved 5 cm on beyond its end
// (and the next lane's start edge 5 cm back before its start), sampled every 2.5 cm from 5 cm
// inside one border to 5 cm inside the other, and each sample looked up on the map (Map::locate,
// any lane type). The longest run of samples on no lane is the gap at that lane end. Lane ends
// at splits and merges (a lane beginning at zero width beside its neighbour) are left out, as are
// the centre strips (strip_joins.h). Computed from the map and the A2 nodes only.
// CORSA_MEASURE_LIST=1 lists each gap over 10 cm with its map position; CORSA_MEASURE_DETAIL=1
// as well adds the lane ends joined to it (widths, borders along its end edge, heading
// difference), which tells a width step from a corner.

#include <cstddef>
#include <functional>
#include <string>

#include "corsa/xodr/map.h"

namespace corsa::test {

struct MouthGapFigures {
  size_t ends = 0;    ///< joined lane ends looked at (each join: two ends)
  size_t over = 0;    ///< of those, with an unpaved run over 10 cm
  double max = 0.0;   ///< longest run (m)
  std::string worst;  ///< "road R lane L end|start"
};

/// `skip(road, lane)`: lanes whose joins are not looked at (splits and merges, strips).
MouthGapFigures mouth_gaps(const xodr::Map& map,
                           const std::function<bool(const xodr::LaneRef&, bool at_start)>& skip);

}  // namespace corsa::test
