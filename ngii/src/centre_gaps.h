#pragma once

// The strip between the two directions of a road. K-City's double yellow centre lines are often
// two B2 marks 0.5-1.0 m apart (Sangam's 0.3-0.5 m), each naming only the lane on its own side
// (R_linkID), so each direction's road ends at its own line and the strip between them belongs
// to no road (a renderer draws terrain there). Where the leftmost lanes of two opposing roads
// are both bounded on the left by a centre mark (yellow, or Kind 501; junction roads too: the
// straight 10 m of an ordinary link taken into a junction keeps its marks) and their left edges
// face each other less than 1.6 m apart, each road gets a lane of type `restricted` (id +1;
// OpenDRIVE 1.8 lane types: as high as the driving lanes, not to be driven on) half the gap
// wide, so the two meet in the middle. Lane centres, the reference line and the laneOffset stay
// as they are.

#include <vector>

#include "corsa/ngii/convert.h"
#include "corsa/ngii/layers.h"
#include "corsa/xodr/model.h"

namespace corsa::ngii::detail {

/// Largest gap (m) between opposing roads' left edges read as a painted centre strip; wider
/// strips are left to what lies there (an island, a kerbed median).
constexpr double kCentreStripMaxGap = 1.6;

/// Adds the centre-strip lanes to the roads of `roads` that have one lane section and no left
/// lanes;
/// returns how many roads got one.
size_t close_centre_gaps(std::vector<xodr::Road>& roads,
                         const std::vector<LinkPlacement>& placements, const Layers& layers);

}  // namespace corsa::ngii::detail
