#pragma once

// The strip between the two directions of a road. K-City's double yellow centre lines are often
// two B2 marks 0.5-1.0 m apart, each naming only the lane on its own side (R_linkID), so each
// direction's road ends at its own yellow line and the strip between them belongs to no road (a
// renderer draws terrain there). Where the leftmost lanes of two opposing ordinary roads are both
// bounded on the left by a yellow B2 mark and their left edges face each other less than 1.6 m
// apart, each road gets a `restricted` lane (id +1, OpenDRIVE 1.8 §9.5.x: same height as the
// driving lanes, not to be driven on) half the gap wide, so the two meet in the middle. Lane
// centres, the reference line and the laneOffset stay as they are.

#include <vector>

#include "corsa/ngii/convert.h"
#include "corsa/ngii/layers.h"
#include "corsa/xodr/model.h"

namespace corsa::ngii::detail {

/// Largest gap (m) between opposing roads' left edges read as a painted centre strip; wider
/// strips are left to what lies there (an island, a kerbed median).
constexpr double kCentreStripMaxGap = 1.6;

/// Adds the centre-strip lanes to the ordinary roads of `roads` (one lane section each);
/// returns how many roads got one.
size_t close_centre_gaps(std::vector<xodr::Road>& roads,
                         const std::vector<LinkPlacement>& placements, const Layers& layers);

}  // namespace corsa::ngii::detail
