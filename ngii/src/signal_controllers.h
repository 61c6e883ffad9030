#pragma once

// Signal controllers for the converted traffic lights (OpenDRIVE 1.8 §14.6): the lights of each
// intersection are grouped by the approach road they stand on (or the connecting road, for
// lights inside the intersection), one <controller> per approach, and the junction lists its
// controllers in a fixed order (`sequence`). Lights of one approach show the same state, so a
// scenario drives an intersection phase by phase (OpenSCENARIO TrafficSignalController phases
// naming the signals of one controller each).

#include "corsa/xodr/model.h"

namespace corsa::ngii::detail {

/// Adds the controllers to `map` and to its junctions; returns how many were made.
size_t add_signal_controllers(xodr::MapData& map);

}  // namespace corsa::ngii::detail
