#pragma once

// Traffic over a run: signal controllers changing phase (OpenSCENARIO 1.3 §6.5.2), the traffic
// generators stepped, and generated or deleted entities coming and going. The data these update
// is state/traffic_state.h.

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace corsa::engine::detail {

struct SimState;

/// Sets up the signal controllers (phase 0 at their delay) before the run.
void init_traffic(SimState& state);
/// After the tick advanced: controllers change phase when theirs has lasted its duration, the
/// generators add and remove traffic; generated entities that left are recorded.
void update_traffic(SimState& state);
/// Makes entity `index` absent (DeleteEntityAction, a TrafficSink, a swarm vehicle leaving):
/// no motion, no rows, no contacts.
void remove_entity(SimState& state, uint32_t index);
/// Records that generated entity `index` appears now (closing a life it had not left yet).
void note_spawned(SimState& state, uint32_t index);
/// Switches a controller to `phase` now (TrafficSignalControllerAction). False: no such phase.
bool set_signal_phase(SimState& state, size_t controller, std::string_view phase);

}  // namespace corsa::engine::detail
