#pragma once

// The paper's LaneNo rules, applied per road (lane run): left-turn pockets (9x) sit on the
// median side numbered outward from 91, and the other lanes read 1, 2, 3, ... from the centre
// line. Violations (a road not starting at 1, several roads sharing one sequence, repeated or
// skipped numbers, a pocket number in the middle of a road, a missing LaneNo) are repaired and
// reported.

#include "correction_log.h"
#include "lateral.h"
#include "network.h"

namespace corsa::ngii::detail {

/// LaneNo values of 90 and above mark left-turn pocket lanes.
inline bool is_pocket_number(int lane_no) { return lane_no > 90 && lane_no < 100; }

void correct_lane_numbers(Network& network, const LateralStructure& lateral, CorrectionLog& log);

}  // namespace corsa::ngii::detail
