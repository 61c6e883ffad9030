#pragma once

// Ordinary lanes of different widths joined end to start (a road ending where the next roads
// start: a lane-count change, a split into one-lane roads, a road cut in two). Each road takes
// its lanes' widths from the marks naming its own links, right up to its ends, and at a joint
// the two links' marks often give widths 0.2-1.5 m apart (in both sample areas mostly measured
// within a metre of the node on both sides: a lane flaring where the next lanes split off, a
// road edge that steps): the wider lane's end then stuck out beyond the narrower one's, unpaved
// ground beside the joint. Here the borders on both sides of the joint are given one place
// there, which both roads' borders meet (road_builder.h EndBorders) and ease back from to their
// own within a metre or two, as a lane whose cubic width reaches the joined lane's width at the
// link would (OpenDRIVE 1.8 §9.5.2 lane width, §9.3 lane offset).

#include <functional>
#include <vector>

#include "corsa/xodr/model.h"
#include "network_plan.h"
#include "road_builder.h"

namespace corsa::ngii::detail {

/// The lane borders of a built road (one lane section, lanes on the right) where it starts or
/// (`at_end`) ends, as horizontal map points, left to right: b_0 at the laneOffset, then each
/// lane's right border.
std::vector<Vec2> built_border_points(const xodr::Road& road, bool at_end);

/// The built ordinary road of plan road r, or nullptr (junction paths, roads not built).
using BuiltOrdinaryRoad = std::function<const xodr::Road*(size_t r)>;

/// Per plan road, where its lane borders are to lie at its ends so that the ordinary lanes
/// joined there meet edge to edge. For each pair of lanes joined end to start (both at least
/// 0.5 m wide there, the roads' headings within 20 degrees, the lanes' centres within 0.1 m of
/// each other across the road and 0.5 m along it), each of the two borders on one side:
/// - inner borders (between two lanes of a road) stay: the lane beside covers the ground;
/// - an outer border (no lane of 0.5 m beyond it in its road) moves onto the other lane's inner
///   border, or onto the other lane's outer border where that lies further out, so that the
///   narrower lane widens to the wider one's edge and no ground either lane covered is left;
///   where that moves a lane's centre more than 3 cm (lanes differing in width on one side),
///   two outer borders meet halfway instead, and where that still does, the outer of two outer
///   borders moves onto the inner one (the wider lane narrows to the narrower one's edges: a
///   narrower lane with a lane of its road beside it cannot widen there without moving its
///   centre, while a wider lane meeting both its borders keeps its own).
/// Two roads whose lanes continue one to one (every lane of one into the lane of the other in
/// the same place, the centres within 3 cm) meet with all their borders instead: the road whose
/// lanes span less takes the other's, the borders between its lanes too.
/// A pair is left alone where a lane's centre still moves more than 3 cm, the two centres end
/// up further apart than they were (and than 0.1 m), a border would move more than 0.75 m (a
/// lane at the tip of a painted island, not a lane's width) or none moves as much as 8 cm. The
/// borders of a lane under 0.5 m wide (starting or ending at zero width beside a neighbour)
/// move together, so that it stays that narrow. Empty EndBorders where nothing moves.
std::vector<EndBorders> joint_borders(const NetworkPlan& plan, const LaneIndex& index,
                                      const BuiltOrdinaryRoad& built);

}  // namespace corsa::ngii::detail
