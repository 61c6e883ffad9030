// Options of the plugin's `corsa run ... --rig` (see run_rig.h).

#include <stdexcept>

#include "corsa/geo/crs_transform.h"
#include "output_paths.h"
#include "run_options.h"
#include "run_rig.h"

namespace corsa::cli {
void declare_rig_run_options(ArgParser& parser) {
  declare_run_options(parser);
  parser.option("--rig", "RIG.xml", "sensor rig (schemas/sensor-rig.xsd): capture a dataset");
  parser.option("-o", "DIR", "dataset folder (required with --rig; absent or empty)");
  parser.option("--format", "corsa|kitti",
                "dataset layout: corsa (default) or kitti (adds kitti/ image_2, velodyne, "
                "label_2, calib)");
  parser.flag("--force", "replace a previous dataset in DIR");
  parser.option("--time-of-day", "HH:MM[:SS]", "override the scenario's time of day");
  parser.option("--weather", "KEY=VALUE,...",
                "override the weather: fog=M, rain=MM_PER_H, snow=MM_PER_H, clouds=0..1, "
                "wind=M_PER_S, wind_dir=DEG, wet=0|1, friction=SCALE");
  parser.repeated("--model", "FILE[@X,Y[,HEADING_DEG]]",
                  "add a building model (map metres, z up) at an offset; the scenario's "
                  "SceneGraphFile is loaded too");
  parser.flag("--preview", "also write DIR/preview/contact_sheet.png and camera_birds_eye.mp4");
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
  if (const auto format = parsed.value("--format")) {
    if (*format == "kitti") {
      dataset.format = sensors::DatasetFormat::kKitti;
    } else if (*format != "corsa") {
      throw UsageError("--format expects corsa or kitti, got '" + *format + "'");
    }
  }
  dataset.replace = parsed.flag("--force");
  dataset.preview = parsed.flag("--preview");
  options.quiet = parsed.flag("--quiet");
  try {
    if (const auto time = parsed.value("--time-of-day")) {
      dataset.environment.time_of_day = engine::parse_time_of_day(*time);
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
  return options;
}

}  // namespace corsa::cli
