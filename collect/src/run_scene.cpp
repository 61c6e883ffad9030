// The static scene and location of a data-collection run (run_scene.h).

#include "corsa/collect/run_scene.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

#include "corsa/core/strings.h"
#include "corsa/engine/simulation.h"
#include "corsa/sensors/georeference.h"
#include "corsa/sensors/scene.h"
#include "corsa/sensors/vehicle_size.h"
#include "corsa/sensors/world.h"
#include "corsa/xodr/map.h"
#include "corsa/xodr/road_mesh.h"
#include "corsa/xosc/scenario.h"

namespace corsa::collect {

ModelSpec parse_model_spec(std::string_view text) {
  ModelSpec spec;
  const size_t at = text.rfind('@');
  spec.file = std::string(text.substr(0, at));
  if (at == std::string_view::npos) {
    return spec;
  }
  const std::string expected = std::string(text) + ": expected FILE@X,Y[,HEADING_DEG]";
  std::vector<double> values;
  for (const std::string_view part : split(text.substr(at + 1), ',')) {
    const auto value = parse_double(trim(part));
    if (!value || !std::isfinite(*value)) {
      throw std::invalid_argument(expected);
    }
    values.push_back(*value);
  }
  if (values.size() < 2 || values.size() > 3) {
    throw std::invalid_argument(expected);
  }
  spec.placement.offset = {values[0], values[1], 0.0};
  spec.placement.heading = values.size() == 3 ? values[2] * std::numbers::pi / 180.0 : 0.0;
  return spec;
}

EntityModelSpec parse_entity_model_spec(std::string_view text) {
  const size_t eq = text.find('=');
  if (eq == std::string_view::npos || trim(text.substr(0, eq)).empty() ||
      text.substr(eq + 1).empty()) {
    throw std::invalid_argument("'" + std::string(text) +
                                "': expected WHO=FILE (a category such as car or pedestrian, "
                                "or an entity's name, then the model file)");
  }
  return {std::string(trim(text.substr(0, eq))), std::string(text.substr(eq + 1)),
          std::string(text)};
}

sensors::EntityModel resolve_entity_model(const EntityModelSpec& spec,
                                          const std::vector<std::string>& entity_names) {
  sensors::EntityModel m;
  m.file = spec.file;
  m.origin = "--entity-model " + spec.text;
  const auto& categories = sensors::entity_category_names();
  if (std::find(entity_names.begin(), entity_names.end(), spec.who) != entity_names.end()) {
    m.entity = spec.who;
  } else if (std::find(categories.begin(), categories.end(), spec.who) != categories.end()) {
    m.category = spec.who;
  } else {
    std::vector<std::string> known = entity_names;
    known.insert(known.end(), categories.begin(), categories.end());
    throw InputError(make_error(m.origin, 0,
                                "'" + spec.who +
                                    "' is neither an entity of the scenario nor a category "
                                    "(car, van, truck, bus, motorbike, bicycle, pedestrian, ...)" +
                                    did_you_mean(spec.who, known)));
  }
  return m;
}

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

namespace {

/// Refuses a road surface the sensor world cannot hold, at the road's line: Embree traces in
/// single precision around the scene's origin (a surface 2e303 m up, from an elevation of slope
/// 1e300, failed its ray assertion and aborted). The ground's height field grows its cells with
/// the roads' extent (world_ground.cpp: at most 2^25 cells), so any real map fits; an extent
/// beyond 1000 km (no road network is that large; single-precision tracing 500 km from the origin
/// is already centimetres coarse, and the ground's cells would be 170 m) or not finite is refused
/// as a limit of the sensor world (a lane 1e206 m wide asked for a vector beyond max_size()).
void refuse_surface_beyond_sensor_world(const xodr::Map& map, const xodr::RoadMesh& mesh,
                                        const sensors::Vec3& origin) {
  constexpr double kMaxHeight = 1e6;  // m from the origin, up or down
  constexpr double kMaxExtent = 1e6;  // m across the roads, east-west or north-south
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  std::vector<Diagnostic> refused;  // every road too high or too low, in one pass
  std::vector<char> road_refused(map.road_count(), 0);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (const uint32_t v : mesh.triangles[t]) {
      const xodr::Vec3& p = mesh.vertices[v];
      const uint32_t index = mesh.info[t].road_index;
      if (std::abs(p.z - origin.z) > kMaxHeight && road_refused[index] == 0) {
        road_refused[index] = 1;
        const xodr::Road& road = map.road(index);
        refused.push_back(make_error(
            map.data().source_file, road.line,
            "road '" + clip(road.id) + "': its surface reaches z = " + format_significant(p.z, 4) +
                " m; sensors trace at most 1e6 m above or below the "
                "map (elevation or lane heights too large)"));
      }
      x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x),
      y1 = std::max(y1, p.y);
    }
  }
  const bool extent_held = x1 - x0 <= kMaxExtent && y1 - y0 <= kMaxExtent;  // false if NaN
  if (mesh.triangles.empty() || extent_held) {
    if (!refused.empty()) {
      throw InputError(std::move(refused));
    }
    return;
  }
  // Named at the road farthest from the middle of the extent: the one that stretches it.
  const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
  double farthest = -1.0;
  uint32_t road_index = 0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (const uint32_t v : mesh.triangles[t]) {
      const double d =
          std::max(std::abs(mesh.vertices[v].x - cx), std::abs(mesh.vertices[v].y - cy));
      if (d > farthest) {
        farthest = d;
        road_index = mesh.info[t].road_index;
      }
    }
  }
  const xodr::Road& road = map.road(road_index);
  refused.push_back(make_error(
      map.data().source_file, road.line,
      "road '" + clip(road.id) + "': the road surfaces span " + format_significant(x1 - x0, 4) +
          " m x " + format_significant(y1 - y0, 4) +
          " m; Corsa's sensor world holds at most 1000 km x 1000 km (a limit of Corsa's sensors, "
          "not a fault in the map)"));
  throw InputError(std::move(refused));
}

/// `centre` (file coordinates) in the map's geoReference CRS: OpenDRIVE's header <offset> moves
/// the file's coordinates there (x_geo = offset + R(hdg) x_file, §2.6); a converted NGII map
/// keeps its coordinates small and the UTM origin in the offset, so without it the map lands far
/// away.
sensors::Vec3 in_map_crs(const xodr::Map& map, const sensors::Vec3& c) {
  const xodr::Header& h = map.data().header;
  const double cos_h = std::cos(h.offset_hdg), sin_h = std::sin(h.offset_hdg);
  return {h.offset_x + cos_h * c.x - sin_h * c.y, h.offset_y + sin_h * c.x + cos_h * c.y,
          h.offset_z + c.z};
}

/// The sensor scene's origin: the middle of the header's bounds (map_centre) when it lies within
/// 1 km of the roads' extent, else, with a warning, the middle of the roads' extent. Header
/// bounds are the author's word and may be anything (north 1e30 moved the origin there: single-
/// precision tracing then saw nothing); the roads are what the sensors look at.
sensors::Vec3 scene_origin(const xodr::Map& map, const xodr::RoadMesh& mesh,
                           Diagnostics& diagnostics) {
  const sensors::Vec3 header_centre = map_centre(&map);
  const xodr::Header& h = map.data().header;
  if (mesh.vertices.empty() || !(h.east > h.west && h.north > h.south)) {
    return header_centre;
  }
  double x0 = mesh.vertices.front().x, x1 = x0, y0 = mesh.vertices.front().y, y1 = y0;
  for (const xodr::Vec3& p : mesh.vertices) {
    x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  }
  constexpr double kMargin = 1000.0;  // m
  if (header_centre.x >= x0 - kMargin && header_centre.x <= x1 + kMargin &&
      header_centre.y >= y0 - kMargin && header_centre.y <= y1 + kMargin) {
    return header_centre;
  }
  diagnostics.add(make_warning(
      map.data().source_file, h.line,
      "<header> bounds (west " + format_significant(h.west, 4) + ", east " +
          format_significant(h.east, 4) + ", south " + format_significant(h.south, 4) + ", north " +
          format_significant(h.north, 4) + ") are centred more than 1 km from the roads (x " +
          format_significant(x0, 4) + " to " + format_significant(x1, 4) + ", y " +
          format_significant(y0, 4) + " to " + format_significant(y1, 4) +
          "): the sensor scene is centred on the roads instead"));
  return {0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.0};
}

}  // namespace

namespace {

/// Where the scenario's entities (and its traffic) stand at the start, with 2 m to spare, and
/// the lanes they stand in: parked vehicles keep clear of them.
std::vector<sensors::KeepClear> entities_kept_clear(const engine::Simulation& simulation,
                                                    const xodr::Map& map) {
  engine::WorldSnapshot start;
  simulation.fill_snapshot(start);
  std::vector<sensors::KeepClear> out;
  for (const engine::EntitySnapshot& e : start.entities) {
    sensors::KeepClear k;
    k.x = e.pose.x;
    k.y = e.pose.y;
    k.radius = 0.5 * std::hypot(e.box.length, e.box.width) + std::fabs(e.box.center_x) + 2.0;
    xodr::LocateOptions near;
    near.max_distance = 0.5;
    if (const auto at = map.locate(e.pose.x, e.pose.y, near)) {
      k.road = map.road(at->road).id;
      k.lane = at->lane;
    }
    out.push_back(std::move(k));
  }
  return out;
}

/// Warns, at its BoundingBox, about each scenario vehicle too large for the generated models'
/// details (sensors/vehicle_size.h): sensors see it as a plain box. Vehicles that name a model
/// (model3d, or the rig's) are seen as that model: nothing to say.
void warn_vehicles_too_large_for_details(const engine::Simulation& simulation,
                                         const sensors::ModelShapeSource& shapes,
                                         Diagnostics& diagnostics) {
  engine::WorldSnapshot start;
  simulation.fill_snapshot(start);
  for (const engine::EntitySnapshot& e : start.entities) {
    if (!sensors::vehicle_too_large_for_details(e.category, e.box) || shapes.names_model(e)) {
      continue;
    }
    for (const xosc::ScenarioObject& object : simulation.scenario().entities.objects) {
      if (object.name != e.name) {
        continue;
      }
      const auto* vehicle = std::get_if<xosc::Vehicle>(&object.object);
      const xosc::Source& where = vehicle != nullptr ? vehicle->bounding_box.source : object.source;
      diagnostics.add(where.warning(
          "vehicle '" + clip(e.name) + "': its bounding box (" +
          format_significant(e.box.length, 4) + " x " + format_significant(e.box.width, 4) + " x " +
          format_significant(e.box.height, 4) +
          " m) is larger than any vehicle the generated models detail (60 m long, or 1 km for "
          "trains and trams, 6 m wide, 8 m high): sensors see a plain box of its size"));
    }
  }
}

}  // namespace

std::unique_ptr<sensors::Scene> build_run_scene(const engine::Simulation& simulation,
                                                const std::vector<ModelSpec>& models,
                                                const sensors::SensorRig& rig,
                                                Diagnostics& diagnostics) {
  const xodr::Map* map = simulation.map();
  // Entities with a model3d file get that model (relative paths from the scenario's folder), the
  // others the rig's model for their name or category.
  auto shapes = std::make_shared<sensors::ModelShapeSource>(
      simulation.scenario().path.parent_path(), diagnostics, rig.entity_models, rig.file);
  warn_vehicles_too_large_for_details(simulation, *shapes, diagnostics);
  xodr::RoadMesh road_mesh;
  sensors::Vec3 origin;
  if (map != nullptr) {
    road_mesh = xodr::build_road_mesh(*map, xodr::MeshOptions{}, diagnostics);
    origin = scene_origin(*map, road_mesh, diagnostics);
  }
  auto scene =
      std::make_unique<sensors::Scene>(sensors::SceneOptions{origin, simulation.options().seed});
  scene->set_entity_shape_source(std::move(shapes));
  if (map != nullptr) {
    refuse_surface_beyond_sensor_world(*map, road_mesh, origin);
    scene->add_road_mesh(road_mesh);
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
  for (const ModelSpec& model : models) {
    for (sensors::StaticMesh& mesh : sensors::load_model(model.file, model.placement)) {
      scene->add_static_mesh(std::move(mesh));
    }
  }
  scene->commit();
  if (map != nullptr) {
    // Ground, vegetation, street lights, street furniture, signals, objects, rails and generated
    // buildings; plants and generated buildings keep clear of the models.
    sensors::WorldOptions world;
    world.seed = simulation.options().seed;
    world.buildings = rig.generate_buildings;
    world.parked = rig.parked_vehicles;
    world.parked_density = rig.parked_density;
    world.keep_clear = entities_kept_clear(simulation, *map);
    sensors::build_world(*map, *scene, world, diagnostics);
    scene->commit();
  }
  return scene;
}

namespace {

// "+lat_0=49 +lon_0=8" (CARLA's maps) names an origin but no projection: read as a transverse
// Mercator around that origin, the projection CARLA assumes. Nothing for any other text.
std::optional<std::string> origin_only_projection(const std::string& geo_reference) {
  if (geo_reference.find("+proj") != std::string::npos ||
      geo_reference.find("+lat_0") == std::string::npos ||
      geo_reference.find("+lon_0") == std::string::npos ||
      geo_reference.find("EPSG") != std::string::npos ||
      geo_reference.find('[') != std::string::npos) {
    return std::nullopt;
  }
  return "+proj=tmerc " + std::string(trim(geo_reference)) + " +ellps=WGS84 +units=m";
}

std::string place_text(const sensors::GeoLocation& where) {
  return format_fixed(std::fabs(where.latitude_deg), 2) +
         (where.latitude_deg <= -0.005 ? " S, " : " N, ") +
         format_fixed(std::fabs(where.longitude_deg), 2) +
         (where.longitude_deg <= -0.005 ? " W" : " E");
}

}  // namespace

sensors::GeoLocation run_location(const engine::Simulation& simulation,
                                  const sensors::Vec3& scene_origin, Diagnostics& diagnostics) {
  const xodr::Map* map = simulation.map();
  const sensors::GeoLocation seoul;
  const std::string fallback = "; the sun is computed at " + place_text(seoul) +
                               " (Seoul), where a time without a zone is local solar time";
  if (map == nullptr || map->data().header.geo_reference.empty()) {
    diagnostics.add_once("run-location",
                         make_warning(map == nullptr ? "" : map->data().source_file, 0,
                                      std::string(map == nullptr ? "the scenario has no map"
                                                                 : "the map has no geoReference") +
                                          fallback));
    return seoul;
  }
  const std::string& geo_reference = map->data().header.geo_reference;
  const std::optional<std::string> origin_only = origin_only_projection(geo_reference);
  try {
    const sensors::GeoLocation where = sensors::geolocation_of(origin_only.value_or(geo_reference),
                                                               in_map_crs(*map, scene_origin));
    if (origin_only) {
      diagnostics.add_once("run-location",
                           make_warning(map->data().source_file, 0,
                                        "geoReference '" + clip(geo_reference) +
                                            "' names no projection; read as a transverse "
                                            "Mercator around its origin (as CARLA does): the "
                                            "sun is computed at " +
                                            place_text(where)));
    } else if (std::fabs(where.latitude_deg) < 0.01 && std::fabs(where.longitude_deg) < 0.01) {
      // RoadRunner's default geoReference (a transverse Mercator at 0 N, 0 E, as in CARLA's
      // Town04 to Town07) is honoured, but said: on the equator the sun sets near 18:00 local
      // solar time all year, so an evening there is darker than at most real places.
      diagnostics.add_once("run-location",
                           make_warning(map->data().source_file, 0,
                                        "the geoReference places the map at " + place_text(where) +
                                            " (a default origin?); the sun is computed there, "
                                            "where it sets near 18:00 local solar time"));
    }
    return where;
  } catch (const InputError& error) {
    diagnostics.add_once("run-location",
                         make_warning(map->data().source_file, 0,
                                      "cannot place the map on Earth (" +
                                          error.diagnostic().message + ")" + fallback));
    return seoul;
  }
}

}  // namespace corsa::collect
