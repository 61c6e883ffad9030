#pragma once

// `corsa run SCENARIO --rig RIG -o DIR` in the plugin (the corsa executable delegates every
// `run` with --rig here): what `corsa run` does (engine::run_scenario) plus the sensors, the
// capture timeline and the dataset folder.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "args.h"
#include "corsa/engine/environment_override.h"
#include "corsa/engine/run.h"
#include "corsa/sensors/dataset_writer.h"

namespace corsa::sensors {
class Scene;
}

namespace corsa::cli {

struct RigRunOptions {
  engine::RunOptions run;
  std::filesystem::path rig;
  std::filesystem::path output;
  sensors::DatasetFormat format = sensors::DatasetFormat::kCorsa;
  bool force = false;
  bool quiet = false;
  bool preview = false;
  engine::EnvironmentOverride environment;
  std::string time_of_day_text;
  std::string weather_text;
  std::string npc_text;  ///< --npc as given (the engine reads it into run.simulation.npc)
  std::vector<std::string> models;  ///< --model FILE[@X,Y[,HEADING_DEG]]
};

/// Declares the options of the plugin's `run` (the engine's options plus the sensor ones).
void declare_rig_run_options(ArgParser& parser);
/// Reads them; throws UsageError for bad values.
RigRunOptions read_rig_run_options(const ParsedArgs& parsed);

/// The static scene of a run: the map's road mesh, the scenario's SceneGraphFile and the
/// --model files, committed. `map` may be null.
std::unique_ptr<sensors::Scene> build_run_scene(const engine::Simulation& simulation,
                                                const std::vector<std::string>& models,
                                                Diagnostics& diagnostics);

/// The location of the map on Earth for the sun (a default with a warning when the map has no
/// usable geoReference).
sensors::GeoLocation run_location(const engine::Simulation& simulation, Diagnostics& diagnostics);

}  // namespace corsa::cli
