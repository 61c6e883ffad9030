#pragma once

// Road and junction plans -> MapData: fits every road (road_builder), numbers roads and
// junctions, and writes the links: road-to-road where one road leads to exactly one other,
// default junctions with connections and laneLinks for intersections (§10.4), direct junctions
// for splits and merges of ordinary lanes (§10.5).

#include <vector>

#include "corsa/ngii/convert.h"
#include "network.h"
#include "network_plan.h"
#include "road_builder.h"

namespace corsa::ngii::detail {

struct Assembly {
  std::vector<xodr::Road> roads;
  std::vector<xodr::Junction> junctions;
  std::vector<LinkPlacement> placements;
  ConversionSummary summary;  ///< road/junction/lane counts and fit errors filled in
};

Assembly assemble(const NetworkPlan& plan, const Network& network, const Origin& origin,
                  const ConvertOptions& options, Diagnostics& diagnostics);

}  // namespace corsa::ngii::detail
