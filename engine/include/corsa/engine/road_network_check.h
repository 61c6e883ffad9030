#pragma once

// The road and lane references of a scenario checked against its map while the scenario is read
// (xosc::LoadOptions::road_network_check), with the rules the engine applies when it places
// something there: `corsa validate` then reports them with the document's other errors in one
// pass, including those in events a run never reaches.

#include "corsa/xosc/scenario.h"

namespace corsa::engine {

/// Loads the scenario's LogicFile and checks each RoadPosition and LanePosition: the road
/// exists, a laneId is a lane id and the lane exists at s. An s outside the road is read as its
/// end with the warning a run gives at the same line, an error when `strict`; the map's own
/// lenient readings are errors when `strict` too, as in a run. A scenario without a LogicFile:
/// each such position is an error. A map that does not load: its errors. A LogicFile that is
/// missing was reported already: nothing more.
class MapReferenceCheck final : public xosc::RoadNetworkCheck {
 public:
  explicit MapReferenceCheck(bool strict) : strict_(strict) {}
  std::vector<Diagnostic> check(const xosc::RoadNetwork& network,
                                const std::vector<xosc::RoadReference>& references,
                                Diagnostics& diagnostics) const override;

 private:
  bool strict_;
};

}  // namespace corsa::engine
