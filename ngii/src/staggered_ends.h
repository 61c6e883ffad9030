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

/// Lanes of an ordinary road that end off the line through the other lanes' ends (by more than
/// the 0.25 m end_line allows, road_reference.h): an OpenDRIVE road ends on one straight line
/// across it (§8.2), so either the lane reaching beyond that line or, for a lane ending short of
/// it, the other lanes are cut where they cross the line (its parallel through the short lane's
/// end), and the cut-off parts become a road of their own. Every lane then starts and ends where
/// its link does; the road ends meet in a direct junction where more than one road continues.
/// The line is the one through the most lane ends of the joint, the roads on its other side
/// included, where that one runs through two or more of the road's own.
void trim_off_line_ends(NetworkPlan& plan);

}  // namespace corsa::ngii::detail
