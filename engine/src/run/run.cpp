#include "corsa/engine/run.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <variant>

#include "corsa/core/strings.h"
#include "corsa/engine/outputs.h"
#include "corsa/engine/trajectory_file.h"
#include "corsa/xodr/map.h"
#include "corsa/xosc/scenario.h"

namespace corsa::engine {

std::shared_ptr<const xodr::Map> load_road_network(const xosc::Scenario& scenario,
                                                   Diagnostics& diagnostics) {
  const xosc::RoadNetwork& network = scenario.road_network;
  if (!network.logic_file || network.logic_file_path.empty()) {
    return nullptr;
  }
  if (!std::filesystem::exists(network.logic_file_path)) {
    throw InputError(network.logic_file->source.error(
        "road network '" + network.logic_file->filepath + "' not found (looked for " +
        network.logic_file_path.string() + ")"));
  }
  return std::make_shared<const xodr::Map>(xodr::Map::load(network.logic_file_path, diagnostics));
}

std::string collision_lines(const RunReport& report, size_t limit) {
  std::string out;
  for (size_t i = 0; i < report.collision_texts.size() && i < limit; ++i) {
    out += "  collision at " + report.collision_texts[i] + "\n";
  }
  if (report.collision_texts.size() > limit) {
    out += "  ... and " + std::to_string(report.collision_texts.size() - limit) +
           " more (the run summary lists them all)\n";
  }
  return out;
}

double expected_end_time(const xosc::Scenario& scenario, double duration) {
  double end = duration;
  const auto& stop = scenario.storyboard.stop_trigger;
  if (!stop) {
    return end;
  }
  for (const xosc::ConditionGroup& group : stop->groups) {
    // A group holds when all its conditions do: by time alone it holds from the latest of them.
    std::optional<double> holds_from;
    for (const xosc::Condition& condition : group.conditions) {
      const auto* by_value = std::get_if<xosc::ByValueCondition>(&condition.kind);
      const auto* time =
          by_value == nullptr ? nullptr : std::get_if<xosc::SimulationTimeCondition>(by_value);
      if (time == nullptr ||
          (time->rule != xosc::Rule::kGreaterThan && time->rule != xosc::Rule::kGreaterOrEqual &&
           time->rule != xosc::Rule::kEqualTo)) {
        holds_from.reset();
        break;
      }
      holds_from = std::max(holds_from.value_or(0.0), time->value + condition.delay);
    }
    if (holds_from && *holds_from >= 0.0) {
      end = std::min(end, *holds_from);
    }
  }
  return end;
}

RunReport run_scenario(const RunOptions& options, Diagnostics& diagnostics,
                       const std::function<void(const Simulation&)>& on_step) {
  const auto start = std::chrono::steady_clock::now();
  xosc::LoadOptions load;
  load.parameters = options.parameters;
  load.strict = options.simulation.strict;
  load.esmini_booleans = options.simulation.semantics == Semantics::kEsmini;
  const xosc::Scenario scenario = xosc::load_scenario(options.scenario, load, diagnostics);
  Simulation simulation(scenario, load_road_network(scenario, diagnostics), options.simulation,
                        diagnostics);
  // The trajectory: binary for a .corsatraj path, CSV otherwise.
  std::optional<TrajectoryRecorder> recorder;
  std::optional<BinaryTrajectoryRecorder> binary;
  if (options.record && is_binary_trajectory(*options.record)) {
    // With a second thread to spare, the recorder may encode and write on it (kAuto: when the
    // ticks' work pays for it).
    const RecordingThread thread =
        options.simulation.threads < 2 && options.record_thread == RecordingThread::kAuto
            ? RecordingThread::kCaller
            : options.record_thread;
    binary.emplace(*options.record, options.record_every, thread);
    simulation.add_observer(*binary);
  } else if (options.record) {
    recorder.emplace(*options.record, options.record_every);
    simulation.add_observer(*recorder);
  }
  if (options.prepare) {
    options.prepare(simulation);
  }
  while (simulation.step()) {
    if (on_step) {
      on_step(simulation);
    }
    if (options.stop && options.stop()) {
      simulation.interrupt();
    }
  }
  if (recorder) {
    recorder->finish(simulation);
  }
  if (binary) {
    binary->finish(simulation);
  }
  if (options.log) {
    write_event_log(simulation, *options.log);
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (options.summary) {
    write_summary(simulation, *options.summary, wall);
  }
  RunReport report;
  report.end_reason = simulation.end_reason();
  report.sim_time = simulation.time();
  report.steps = simulation.steps();
  report.start_time = simulation.time_of(simulation.start_tick());
  report.wall_seconds = wall;
  report.collisions = simulation.collisions().size();
  for (const CollisionRecord& c : simulation.collisions()) {
    report.collision_texts.push_back(format_fixed(c.time, 2) +
                                     " s: " + simulation.entity(c.first).name + " and " +
                                     simulation.entity(c.second).name);
  }
  report.entities = simulation.entity_count();
  return report;
}

}  // namespace corsa::engine
