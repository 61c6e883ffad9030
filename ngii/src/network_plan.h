#pragma once

// Roads and junctions before fitting. Ordinary lane runs become roads; chains of intersection
// links (LinkType 1) from an approach lane to an exit lane become single-lane connecting roads,
// grouped into one junction per intersection (shared links, shared approach or exit roads,
// crossing paths). Where an approach road also continues straight on an ordinary link (a
// "mixed" end), the start of that continuation is cut off and joins the junction as a
// connecting road too, so that every road end leads to one road or one junction (§8.2).

#include <vector>

#include "corsa/core/diagnostic.h"
#include "lateral.h"
#include "network.h"
#include "road_plan.h"

namespace corsa::ngii::detail {

struct JunctionPlan {
  std::vector<int> roads;  ///< connecting road plans
};

struct NetworkPlan {
  std::vector<RoadPlan> roads;
  std::vector<JunctionPlan> junctions;
  int node_keys = 0;  ///< topology keys in use (A1 nodes plus cut points)
};

/// `several_incoming`: a connecting road may take lanes from several incoming roads
/// (ConvertOptions::several_incoming_roads).
NetworkPlan plan_network(const Network& network, const LateralStructure& lateral,
                         bool several_incoming, Diagnostics& diagnostics);

/// Lanes of all plans indexed by the topology key of their start and of their end.
struct LaneIndex {
  struct Ref {
    int road = -1;
    int lane = -1;
  };
  std::vector<std::vector<Ref>> starting;  ///< per key
  std::vector<std::vector<Ref>> ending;
  explicit LaneIndex(const NetworkPlan& plan);
};

}  // namespace corsa::ngii::detail
