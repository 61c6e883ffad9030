#pragma once

// The static world of a data-collection run: the map's road mesh, the scenario's SceneGraphFile
// and extra building models, in one sensors::Scene, and where the map lies on Earth (for the sun).

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/sensors/environment.h"
#include "corsa/sensors/geometry.h"
#include "corsa/sensors/model_io.h"
#include "corsa/sensors/rig.h"

namespace corsa::engine {
class Simulation;
}
namespace corsa::xodr {
class Map;
}
namespace corsa::sensors {
class Scene;
}

namespace corsa::collect {

/// A building model added to the scene (map metres, z up), e.g. from `--model FILE@X,Y,HEADING`.
struct ModelSpec {
  std::filesystem::path file;
  sensors::ModelPlacement placement;  ///< offset (m, map frame) and heading (rad, from +x)
};

/// Reads "FILE[@X,Y[,HEADING_DEG]]": X, Y in map metres, the heading in degrees counter-clockwise
/// from +x. Throws std::invalid_argument ("expected FILE@X,Y[,HEADING_DEG]") for anything else.
ModelSpec parse_model_spec(std::string_view text);

/// A model for entities given on the command line (`--entity-model WHO=FILE`): WHO names a
/// scenario entity or an OpenSCENARIO category; FILE is taken as written (relative to the
/// working directory). `text` is the option's value, for messages.
struct EntityModelSpec {
  std::string who;
  std::filesystem::path file;
  std::string text;
};

/// Reads "WHO=FILE". Throws std::invalid_argument ("... expected WHO=FILE ...") when either side
/// is empty.
EntityModelSpec parse_entity_model_spec(std::string_view text);

/// The rig-style model of `spec`: for the entity of that name when the scenario has one, else for
/// the category of that name. Throws InputError located at "--entity-model TEXT" when WHO is
/// neither (with the nearest name).
sensors::EntityModel resolve_entity_model(const EntityModelSpec& spec,
                                          const std::vector<std::string>& entity_names);

/// The middle of the map's header bounds (m, map frame), or the origin when the header gives no
/// bounds (or `map` is null). The scene is centred there so that float coordinates stay small.
sensors::Vec3 map_centre(const xodr::Map* map);

/// The committed scene of a run: the road mesh of the simulation's map (when it has one), the
/// scenario's SceneGraphFile (map coordinates; InputError located at the RoadNetwork when the
/// file is missing) and `models`, then the world around the roads (sensors::build_world, with
/// generated buildings along the streets when the rig says buildings="generate"). Entities get
/// their model3d files, or the rig's <EntityModel>s, or generated shapes.
std::unique_ptr<sensors::Scene> build_run_scene(const engine::Simulation& simulation,
                                                const std::vector<ModelSpec>& models,
                                                const sensors::SensorRig& rig,
                                                Diagnostics& diagnostics);

/// Where the sensor scene's origin (`scene_origin`, map coordinates: the scene's
/// options().origin, the header's centre or the roads' when the bounds lie far from them) lies on
/// Earth, from the map's geoReference; Seoul with a warning when the map has none or it cannot be
/// used.
sensors::GeoLocation run_location(const engine::Simulation& simulation,
                                  const sensors::Vec3& scene_origin, Diagnostics& diagnostics);

}  // namespace corsa::collect
