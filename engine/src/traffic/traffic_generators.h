#pragma once

// The traffic generators of OpenSCENARIO 1.3 §7.5.6 TrafficAction: a swarm of vehicles around a
// central entity, sources that emit vehicles at a rate, sinks that absorb them. Vehicles are
// new entities appended to the world (named `<trafficName or swarm|source>_<n>`, document order
// kept for the scenario's own), driven by the car-following controller so that they do not run
// into each other (or by `--controller`). Every draw comes from a stream of the run seed.

#include <memory>

#include "corsa/xosc/global_actions.h"
#include "state/traffic_state.h"

namespace corsa::engine::detail {

std::unique_ptr<TrafficGenerator> make_swarm(const xosc::TrafficSwarmAction& action,
                                             SimState& state);
std::unique_ptr<TrafficGenerator> make_source(const xosc::TrafficSourceAction& action,
                                              SimState& state);
std::unique_ptr<TrafficGenerator> make_sink(const xosc::TrafficSinkAction& action, SimState& state);
/// TrafficAreaAction (traffic/traffic_area.cpp).
std::unique_ptr<TrafficGenerator> make_area(const xosc::TrafficAreaAction& action, SimState& state);
/// `--npc` (SimulationOptions::npc, traffic/npc_traffic.cpp): places the NPCs once all Init
/// placements are done, at tick 0.
void place_npcs(SimState& state);

}  // namespace corsa::engine::detail
