// Options of the plugin's `corsa run ... --rig` (see run_rig.h).

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "corsa/core/strings.h"
#include "corsa/geo/crs_transform.h"
#include "output_paths.h"
#include "run_options.h"
#include "run_rig.h"

namespace corsa::cli {
void declare_rig_run_options(ArgParser& parser) {
  declare_run_options(parser);
  declare_dataset_options(parser);
}

RigRunOptions read_rig_run_options(const ParsedArgs& parsed) {
  RigRunOptions options;
  collect::DatasetRunOptions& dataset = options.dataset;
  dataset.run = read_run_options(parsed);
  dataset.run.simulation.geo_projection = geo::geographic_to_projected;
  const auto rig = parsed.value("--rig");
  if (!rig || rig->empty()) {
    throw UsageError("missing --rig RIG.xml");
  }
  dataset.rig = *rig;
  dataset.output = required_output_folder(parsed, "-o", "DIR (the dataset folder to write)");
  if (parsed.choice("--format", {"corsa", "kitti"}) == "kitti") {
    dataset.format = sensors::DatasetFormat::kKitti;
  }
  if (const auto height = parsed.number("--kitti-min-height")) {
    if (!(*height >= 0.0) || *height > 1e5) {
      throw UsageError("--kitti-min-height expects a height in pixels, 0 or more");
    }
    dataset.kitti.min_height_px = *height;
  }
  if (const auto distance = parsed.number("--kitti-max-distance")) {
    if (!(*distance > 0.0) || !std::isfinite(*distance)) {
      throw UsageError("--kitti-max-distance expects a distance in metres above 0");
    }
    dataset.kitti.max_distance_m = *distance;
  }
  if ((parsed.flag("--kitti-min-height") || parsed.flag("--kitti-max-distance")) &&
      dataset.format != sensors::DatasetFormat::kKitti) {
    throw UsageError("--kitti-min-height and --kitti-max-distance need --format kitti");
  }
  dataset.replace = parsed.flag("--force");
  dataset.preview = parsed.flag("--preview");
  options.quiet = parsed.flag("--quiet");
  try {
    if (const auto time = parsed.value("--time-of-day")) {
      engine::parse_time_of_day(*time, dataset.environment);
      dataset.time_of_day_text = *time;
    }
    if (const auto weather = parsed.value("--weather")) {
      engine::parse_weather(*weather, dataset.environment);
      dataset.weather_text = *weather;
    }
  } catch (const std::invalid_argument& error) {
    throw UsageError(error.what());
  }
  // --npc is the engine's (run_options.cpp): the NPCs are simulation entities; the text is kept
  // for run.json.
  if (const auto npc = parsed.value("--npc")) {
    dataset.npc_text = *npc;
  }
  for (const std::string& model : parsed.values("--model")) {
    try {
      dataset.models.push_back(collect::parse_model_spec(model));
    } catch (const std::invalid_argument& error) {
      throw UsageError(std::string("--model ") + error.what());
    }
  }
  for (const std::string& model : parsed.values("--entity-model")) {
    try {
      dataset.entity_models.push_back(collect::parse_entity_model_spec(model));
    } catch (const std::invalid_argument& error) {
      throw UsageError(std::string("--entity-model ") + error.what());
    }
  }
  return options;
}

}  // namespace corsa::cli
