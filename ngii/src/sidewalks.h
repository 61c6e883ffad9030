#pragma once

// Optional sidewalks (NGII has none): a sidewalk lane of a given width on the outer (right) edge
// of every ordinary road that has nothing beside it there, raised 15 cm like a kerb (lane height,
// OpenDRIVE 1.8 §9.5.7), so that pedestrians have somewhere to walk. A road edge is free when
// its outermost lane's links have no right-hand neighbour (R_LinkID, after repair) and no lane of
// another ordinary road runs within a lane width plus the sidewalk to its right.

#include <vector>

#include "corsa/xodr/model.h"
#include "network.h"
#include "network_plan.h"

namespace corsa::ngii::detail {

/// Adds the sidewalk lanes; `road_slot[r]` is the index in `roads` of plan road r (-1 when
/// removed). Returns, per plan road, whether it got one.
std::vector<bool> add_sidewalks(std::vector<xodr::Road>& roads, const NetworkPlan& plan,
                                const std::vector<int>& road_slot, const Network& network,
                                double width);

/// The id of a road's sidewalk lane (its outermost lane once added).
int sidewalk_lane_id(const xodr::Road& road);

}  // namespace corsa::ngii::detail
