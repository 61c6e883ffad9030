// The static scene and location of a `corsa run --rig` (see run_rig.h).

#include <cmath>
#include <numbers>

#include "corsa/core/strings.h"
#include "corsa/engine/simulation.h"
#include "corsa/sensors/georeference.h"
#include "corsa/sensors/model_io.h"
#include "corsa/sensors/scene.h"
#include "corsa/xodr/map.h"
#include "corsa/xodr/road_mesh.h"
#include "corsa/xosc/scenario.h"
#include "run_rig.h"

namespace corsa::cli {
namespace {

sensors::Vec3 map_centre(const xodr::Map* map) {
  if (map == nullptr) {
    return {};
  }
  const xodr::Header& h = map->data().header;
  if (h.east > h.west && h.north > h.south) {
    return {0.5 * (h.east + h.west), 0.5 * (h.north + h.south), 0.0};
  }
  return {};
}

// FILE[@X,Y[,HEADING_DEG]]
std::vector<sensors::StaticMesh> load_model_option(const std::string& text) {
  const size_t at = text.rfind('@');
  sensors::ModelPlacement placement;
  std::string file = text;
  if (at != std::string::npos) {
    file = text.substr(0, at);
    const std::vector<std::string_view> parts = split(text.substr(at + 1), ',');
    std::vector<double> values;
    for (const std::string_view part : parts) {
      const auto value = parse_double(trim(part));
      if (!value || !std::isfinite(*value)) {
        throw UsageError("--model " + text + ": expected FILE@X,Y[,HEADING_DEG]");
      }
      values.push_back(*value);
    }
    if (values.size() < 2 || values.size() > 3) {
      throw UsageError("--model " + text + ": expected FILE@X,Y[,HEADING_DEG]");
    }
    placement.offset = {values[0], values[1], 0.0};
    placement.heading = values.size() == 3 ? values[2] * std::numbers::pi / 180.0 : 0.0;
  }
  return sensors::load_model(file, placement);
}

}  // namespace

std::unique_ptr<sensors::Scene> build_run_scene(const engine::Simulation& simulation,
                                                const std::vector<std::string>& models,
                                                Diagnostics& diagnostics) {
  const xodr::Map* map = simulation.map();
  auto scene = std::make_unique<sensors::Scene>(sensors::SceneOptions{map_centre(map)});
  if (map != nullptr) {
    scene->add_road_mesh(xodr::build_road_mesh(*map, xodr::MeshOptions{}, diagnostics));
  }
  const xosc::RoadNetwork& network = simulation.scenario().road_network;
  if (network.scene_graph_file && !network.scene_graph_file_path.empty()) {
    // The SceneGraphFile is taken in map coordinates (metres, z up; glTF turned z-up).
    if (!std::filesystem::exists(network.scene_graph_file_path)) {
      throw InputError(network.scene_graph_file->source.error(
          "scene graph file '" + network.scene_graph_file->filepath + "' not found (looked for " +
          network.scene_graph_file_path.string() + ")"));
    }
    for (sensors::StaticMesh& mesh : sensors::load_model(network.scene_graph_file_path, {})) {
      scene->add_static_mesh(std::move(mesh));
    }
  }
  for (const std::string& model : models) {
    for (sensors::StaticMesh& mesh : load_model_option(model)) {
      scene->add_static_mesh(std::move(mesh));
    }
  }
  scene->commit();
  return scene;
}

sensors::GeoLocation run_location(const engine::Simulation& simulation, Diagnostics& diagnostics) {
  const xodr::Map* map = simulation.map();
  if (map != nullptr && !map->data().header.geo_reference.empty()) {
    try {
      return sensors::geolocation_of(map->data().header.geo_reference, map_centre(map));
    } catch (const InputError& error) {
      diagnostics.add_once("run-location", make_warning(map->data().source_file, 0,
                                                        "cannot place the map on Earth (" +
                                                            error.diagnostic().message +
                                                            "); the sun is computed for Seoul"));
      return {};
    }
  }
  diagnostics.add_once("run-location",
                       make_warning("", 0,
                                    "the map has no geoReference; the sun is computed "
                                    "for Seoul (37.57 N, 126.98 E)"));
  return {};
}

}  // namespace corsa::cli
