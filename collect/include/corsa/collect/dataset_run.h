#pragma once

// A data-collection run as one library call: the scenario runs (engine::run_scenario) with a
// sensor rig; the capture timeline (corsa:capture windows, sensor rates) hands world snapshots to
// the sensor system, whose frames the dataset writer puts into a dataset folder (Corsa layout or
// KITTI; docs/datasets.md), optionally with a preview. `corsa run --rig` is this call plus
// argument parsing and printing; a library user (or the Python module) fills the options.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "corsa/collect/run_scene.h"
#include "corsa/core/diagnostic.h"
#include "corsa/engine/environment_override.h"
#include "corsa/engine/run.h"
#include "corsa/sensors/dataset_writer.h"
#include "corsa/sensors/kitti.h"
#include "corsa/sensors/preview.h"

namespace corsa::collect {

struct DatasetRunOptions {
  /// Scenario, parameters, step, duration, seed, NPCs and the run's own outputs (trajectories,
  /// summary, log). `run.prepare`, when set, is called before the dataset is set up.
  engine::RunOptions run;
  std::filesystem::path rig;     ///< sensor rig file (schemas/sensor-rig.xsd)
  std::filesystem::path output;  ///< dataset folder: absent, empty, or a dataset to `replace`
  sensors::DatasetFormat format = sensors::DatasetFormat::kCorsa;
  sensors::KittiOptions kitti;  ///< DontCare regions of the KITTI labels (format kKitti)
  bool replace = false;         ///< replace a previous dataset (a folder holding a run.json)
  bool preview = false;         ///< also write output/preview/ (contact sheet, video)
  /// Time of day and weather over the scenario's own environment.
  engine::EnvironmentOverride environment;
  std::vector<ModelSpec> models;  ///< building models added to the scene
  /// Entity models from the command line; they come before the rig's <EntityModel>s (an
  /// entity's model3d still wins, then a model naming the entity, then one for its category).
  std::vector<EntityModelSpec> entity_models;
  /// How the user gave the overrides, recorded in run.json (empty: not given).
  std::string time_of_day_text;
  std::string weather_text;
  std::string npc_text;
};

struct DatasetRunReport {
  /// The engine's report (end reason kInterrupted when the run was stopped).
  engine::RunReport run;
  bool interrupted = false;
  std::string interruption;      ///< what stopped it, e.g. "interrupted by SIGINT"
  bool dataset_started = false;  ///< the dataset folder was created (the run got to its start)
  int64_t captures = 0;          ///< complete captures in the dataset's index
  int64_t files = 0;             ///< files in the index
  std::optional<sensors::PreviewReport> preview;
};

/// What a caller sees of a run while it goes on; every member is optional.
struct DatasetRunHooks {
  /// Sees the simulation after every step (e.g. a progress bar).
  std::function<void(const engine::Simulation&)> on_step;
  /// Asked between steps whether to stop; a value is the reason ("interrupted by SIGINT"). The
  /// run then ends after the capture in progress, leaving a consistent dataset whose run.json
  /// says "interrupted" with that reason; the run's --record, --summary and --log are written
  /// for what was simulated (end reason "interrupted").
  std::function<std::optional<std::string>()> stop;
  /// Called once the simulation is over (ended or stopped), before the dataset is completed and
  /// the preview written (e.g. to close a progress bar before anything else is printed).
  std::function<void()> on_simulated;
  /// Sees the preview video being encoded: (frames done, frames in all).
  sensors::PreviewProgress on_preview;
};

/// Runs the scenario with the rig and writes the dataset as `options` say. Throws InputError for
/// bad input (the rig, the scenario, a model, an unusable output folder); the dataset folder
/// appears only once the run has started.
DatasetRunReport run_dataset(const DatasetRunOptions& options, Diagnostics& diagnostics,
                             const DatasetRunHooks& hooks = {});

}  // namespace corsa::collect
