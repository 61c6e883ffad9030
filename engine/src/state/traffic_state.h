#pragma once

// The traffic side of the run state: traffic signal controllers cycling through their phases
// and the signals' states (OpenSCENARIO 1.3 §6.5 RoadNetwork/TrafficSignals, §7.5.2
// TrafficSignalAction), and the traffic generators (TrafficSwarm, TrafficSource, TrafficSink)
// with the scenario objects of the entities they spawned. The state only: traffic/ updates it
// (traffic/traffic_update.h) and implements the generators behind TrafficGenerator.

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "corsa/engine/simulation.h"
#include "corsa/xosc/entities.h"

namespace corsa::xosc {
struct TrafficSignalController;
}

namespace corsa::engine::detail {

struct SimState;

/// One TrafficSignalController during the run: the current phase and when it began.
struct SignalControllerRun {
  const xosc::TrafficSignalController* definition = nullptr;
  size_t phase = 0;
  double phase_start = 0.0;  ///< s, simulation time
  bool started = false;      ///< false while waiting for its delay
};

/// Something that adds or removes traffic every step (swarm, source, sink).
class TrafficGenerator {
 public:
  virtual ~TrafficGenerator() = default;
  virtual void step(SimState& state) = 0;
  /// The TrafficAction's trafficName (TrafficStopAction stops generators by it).
  virtual const std::optional<std::string>& name() const = 0;
  /// Set by an action that runs as long as its generator does (TrafficState::generators_made):
  /// unique within a run, so that the action finds out when a TrafficStopAction removed it.
  uint64_t serial = 0;
};

struct TrafficState {
  std::vector<SignalControllerRun> controllers;
  /// Current state of each traffic signal (OpenDRIVE signal id -> state string, e.g.
  /// "off;off;on"), from controller phases and TrafficSignalStateActions.
  std::map<std::string, std::string, std::less<>> signals;
  std::vector<std::unique_ptr<TrafficGenerator>> generators;
  /// Serials handed out to generators (TrafficGenerator::serial).
  uint64_t generators_made = 0;
  /// Objects of the entities the generators spawned (Entity::object points here; a deque
  /// keeps the addresses).
  std::deque<xosc::ScenarioObject> spawned_objects;
  uint64_t spawned_count = 0;
  /// When each generated entity appeared and left (by entity index; a generator may respawn
  /// one of its entities that left), for the summary.
  std::map<uint32_t, std::vector<Lifetime>> lifetimes;
  /// Entities removed so far (remove_entity), and the count the lifetimes were last updated at:
  /// without a removal in between, no lifetime can have ended.
  uint64_t removals = 0;
  uint64_t removals_seen = 0;

  /// Index of the signal controller named `name`, or nothing.
  std::optional<size_t> find_controller(std::string_view name) const;
};

}  // namespace corsa::engine::detail
