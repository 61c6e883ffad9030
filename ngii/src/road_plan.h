#pragma once

// What one OpenDRIVE road will be made of, before fitting: its lanes' centre polylines (left to
// right), the A2 links along each, and the topology keys of each lane's ends.

#include <string>
#include <utility>
#include <vector>

#include "corsa/ngii/layers.h"
#include "lateral.h"
#include "polyline.h"

namespace corsa::ngii::detail {

/// Shift of the map frame: map x = easting - x, map y = northing - y.
struct Origin {
  double x = 0.0;
  double y = 0.0;
};

struct PlanLane {
  std::vector<Point3> points;       ///< centre line, in the driving direction
  std::vector<int> links;           ///< source links along it, in order
  std::vector<double> link_starts;  ///< arc length along `points` where each link starts
  /// Topology keys of the lane's ends: an A1 node index, or a synthetic key (>= node count)
  /// where a road was cut in two.
  int start_node = -1;
  int end_node = -1;
  /// A few metres of the lane before it and after it (the best-aligned lane ending where this
  /// one starts, and starting where it ends), for measuring offsets near the ends; may be empty.
  std::vector<Point3> lead_in;
  std::vector<Point3> lead_out;
  /// Whether the lane starts (ends) beside the others or splits off (merges into) a
  /// neighbour at a shared node, where its width is zero.
  LaneEnd start_shape = LaneEnd::kBeside;
  LaneEnd end_shape = LaneEnd::kBeside;
};

struct RoadPlan {
  std::vector<PlanLane> lanes;  ///< left to right
  int junction = -1;            ///< junction plan index for a connecting road, else -1
  bool removed = false;         ///< merged into another plan
  bool absorbed = false;        ///< an ordinary road (or its cut-off end) moved into a junction
};

/// How lane k of `plan` effectively starts (`at_start`) or ends: a split or merge needs the
/// neighbour it shares its node with (a single-lane piece of such a lane is an ordinary lane).
LaneEnd effective_end(const RoadPlan& plan, size_t k, bool at_start);

/// Arc length on `line` where it crosses the line through `c` square to `direction` (the
/// crossing nearest `c`); `fallback` when it does not cross.
double crossing_u(const Polyline& line, Vec2 c, Vec2 direction, double fallback);

/// `lane` cut at arc length `u` into the part before and the part after; the cut point gets
/// topology key `key`. Each part names only the links along it.
std::pair<PlanLane, PlanLane> split_lane(const PlanLane& lane, double u, int key);

}  // namespace corsa::ngii::detail
