#pragma once

// Dead ends whose lanes end metres apart. Where a road ends and no lane continues (the start
// grid of K-City's track), the survey may end one lane 8 m beyond its neighbour: more than a
// skewed end line can follow (road_reference.h turns road ends up to 50 degrees). The part of
// such a lane beyond where its neighbour ends is cut off into a road of its own, linked road to
// road, so that every lane still ends where its link does.

#include "network_plan.h"

namespace corsa::ngii::detail {

/// Cuts the protruding lane ends of every ordinary road's dead ends into roads of their own
/// (appended to `plan`; the cut points get fresh topology keys).
void trim_staggered_ends(NetworkPlan& plan);

}  // namespace corsa::ngii::detail
