#pragma once

// The scenario's local date and time now: the TimeOfDay last set by an EnvironmentAction,
// advanced by the simulated time since then when its animation flag is set (OpenSCENARIO 1.3
// TimeOfDay.animation).

#include "state/date_time.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {

inline DateTime current_date_time(const SimState& state) {
  DateTime base;
  base.year = state.environment.year;
  base.month = state.environment.month;
  base.day = state.environment.day;
  base.seconds_of_day = state.environment.time_of_day;
  base.utc_offset_hours = state.environment.utc_offset_hours;
  if (!state.time_of_day_animated) {
    return base;
  }
  return advance(base, state.time.time(state.tick - state.environment_tick));
}

}  // namespace corsa::engine::detail
