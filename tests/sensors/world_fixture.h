#pragma once

// A map's road mesh and generated world in one scene, built as `corsa run --rig` builds them,
// for the tests of the world beyond the road.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/sensors/camera_render.h"
#include "corsa/sensors/world.h"
#include "corsa/xodr/map.h"
#include "corsa/xodr/road_mesh.h"

namespace corsa::test {

/// The real OpenDRIVE maps of the shared data.
inline const std::filesystem::path kXodrData =
    std::filesystem::path(CORSA_SHARED_DIR) / "data" / "xodr";

inline xodr::Map load_map(const std::filesystem::path& path) {
  Diagnostics quiet;
  return xodr::Map::load(path, quiet);
}

struct BuiltWorld {
  sensors::Scene scene;
  sensors::WorldReport report;
  std::vector<Diagnostic> warnings;  ///< what building the world warned about
};

/// The scene centred on the map's extent: road mesh, then the world as `options` say.
inline std::unique_ptr<BuiltWorld> build_world_scene(const xodr::Map& map,
                                                     const sensors::WorldOptions& options) {
  const auto& h = map.data().header;
  auto out = std::make_unique<BuiltWorld>(
      BuiltWorld{sensors::Scene(sensors::SceneOptions{
                     {0.5 * (h.east + h.west), 0.5 * (h.north + h.south), 0.0}, options.seed}),
                 {},
                 {}});
  out->scene.add_road_mesh(xodr::build_road_mesh(map));
  out->scene.commit();
  Diagnostics diagnostics([&](const Diagnostic& d) { out->warnings.push_back(d); });
  out->report = sensors::build_world(map, out->scene, options, diagnostics);
  out->scene.commit();
  return out;
}

/// The scene centred on the map's extent: road mesh, then the world from `seed` (generated
/// buildings along streets when `buildings`).
inline std::unique_ptr<BuiltWorld> build_world_scene(const xodr::Map& map, uint64_t seed,
                                                     bool buildings = false) {
  sensors::WorldOptions options;
  options.seed = seed;
  options.buildings = buildings;
  return build_world_scene(map, options);
}

/// A small 90-degree camera (480 x 270) that sees much of the world in few pixels.
inline sensors::CameraIntrinsics wide_camera() {
  sensors::CameraIntrinsics k;
  k.width = 480;
  k.height = 270;
  k.fov_deg = 90.0;
  return k;
}

}  // namespace corsa::test
