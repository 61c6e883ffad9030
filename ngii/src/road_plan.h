#pragma once

// What one OpenDRIVE road will be made of, before fitting: its lanes' centre polylines (left to
// right), the A2 links along each, and the topology keys of each lane's ends.

#include <string>
#include <vector>

#include "corsa/ngii/layers.h"
#include "lateral.h"

namespace corsa::ngii::detail {

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

}  // namespace corsa::ngii::detail
