#pragma once

// One whole run as `corsa run` performs it: load the scenario (parameters overridden) and its
// road network, simulate to the end, write the requested outputs. The command line only parses
// arguments and prints.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/engine/simulation.h"
#include "corsa/engine/trajectory_file.h"

namespace corsa::xosc {
struct Scenario;
}

namespace corsa::engine {

struct RunOptions {
  std::filesystem::path scenario;
  /// Global parameter values from outside (`--param name=value`), in order.
  std::vector<std::pair<std::string, std::string>> parameters;
  SimulationOptions simulation;
  /// The trajectory: binary when the extension is .corsatraj (corsa/engine/trajectory_file.h),
  /// CSV otherwise.
  std::optional<std::filesystem::path> record;
  int64_t record_every = 1;
  /// Where a binary trajectory is encoded: kAuto (with SimulationOptions::threads >= 2; the
  /// caller's thread with one) or as given.
  RecordingThread record_thread = RecordingThread::kAuto;
  std::optional<std::filesystem::path> summary;  ///< run summary JSON
  std::optional<std::filesystem::path> log;      ///< storyboard event log CSV
  /// Called once with the simulation before its first step, e.g. to add observers and custom
  /// command handlers (the capture timeline of `corsa run --rig`). Optional.
  std::function<void(Simulation&)> prepare;
  /// Asked after every step whether to stop now (e.g. a signal arrived). When it says so the
  /// run ends as EndReason::kInterrupted and its outputs (trajectories, log, summary) are
  /// written for what was simulated. Optional.
  std::function<bool()> stop;
};

struct RunReport {
  EndReason end_reason = EndReason::kRunning;
  double sim_time = 0.0;  ///< s
  /// s the run started at: 0, or the negative head start of esmini's followGhost ghost.
  double start_time = 0.0;
  int64_t steps = 0;          ///< steps taken, from start_time to sim_time
  double wall_seconds = 0.0;  ///< loading, simulating and writing
  size_t collisions = 0;
  /// Each collision for people: "5.18 s: Cutter and npc_vehicle_0", in order.
  std::vector<std::string> collision_texts;
  size_t entities = 0;
};

/// Prints up to `limit` collision texts of a report, one a line ("  collision at ..."), and
/// how many more there were.
std::string collision_lines(const RunReport& report, size_t limit = 10);

/// The scenario's road network (its LogicFile), or null when it has none. Throws InputError,
/// located at the LogicFile element, when the map cannot be read.
std::shared_ptr<const xodr::Map> load_road_network(const xosc::Scenario& scenario,
                                                   Diagnostics& diagnostics);

/// When the run will end at the latest (s): the earliest time at which the storyboard's stop
/// trigger fires by a condition group made only of SimulationTime conditions (greaterThan,
/// greaterOrEqual or equalTo, plus their delays), else `duration` (the --duration cap). For
/// progress bars: the default cap of 3600 s says nothing about a 20 s scenario.
double expected_end_time(const xosc::Scenario& scenario, double duration);

/// Loads, runs and writes as `options` say. `on_step` (optional) sees the simulation after
/// every step, e.g. for a progress bar. Throws InputError for bad input; outputs are written
/// when the run ended by itself or was stopped (RunOptions::stop), not when it threw.
RunReport run_scenario(const RunOptions& options, Diagnostics& diagnostics,
                       const std::function<void(const Simulation&)>& on_step = {});

}  // namespace corsa::engine
