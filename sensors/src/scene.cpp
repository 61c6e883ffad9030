#include "corsa/sensors/scene.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "facade.h"
#include "material_defaults.h"
#include "noise_tile.h"
#include "scene_data.h"

namespace corsa::sensors {
namespace detail {

SceneData::~SceneData() {
  shapes.clear();  // releases the entity scenes before the device
  for (auto& [id, record] : objects) {
    if (record.alone != nullptr) {
      rtcReleaseScene(record.alone);  // shares the buffers of its static geometry: first
    }
  }
  for (RTCGeometry g : instance_pool) {
    rtcReleaseGeometry(g);
  }
  for (RTCGeometry g : moving_pool) {
    rtcReleaseGeometry(g);
  }
  if (moving_top != nullptr) {
    rtcReleaseScene(moving_top);
  }
  if (top != nullptr) {
    rtcReleaseScene(top);
  }
  if (static_scene != nullptr) {
    rtcReleaseScene(static_scene);
  }
  if (far_static != nullptr) {
    rtcReleaseScene(far_static);
  }
  if (device != nullptr) {
    rtcReleaseDevice(device);
  }
}

EntityShape::~EntityShape() {
  if (scene != nullptr) {
    rtcReleaseScene(scene);
  }
}

}  // namespace detail

namespace {

void check_device(RTCDevice device, const char* what) {
  const RTCError error = rtcGetDeviceError(device);
  if (error != RTC_ERROR_NONE) {
    // Embree errors come from our own misuse (or out of memory), never from user input.
    throw std::runtime_error(std::string("Embree error ") + std::to_string(error) + " in " + what);
  }
}

/// Creates a committed-ready triangle geometry from a mesh, translated by -origin.
RTCGeometry make_triangles(RTCDevice device, const StaticMesh& mesh, Vec3 origin) {
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.vertices.size()));
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3 p = mesh.vertices[i] - origin;
    v[3 * i] = static_cast<float>(p.x);
    v[3 * i + 1] = static_cast<float>(p.y);
    v[3 * i + 2] = static_cast<float>(p.z);
  }
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0,
                                                             RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                             mesh.triangles.size()));
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      idx[3 * i + k] = mesh.triangles[i][k];
    }
  }
  rtcCommitGeometry(geom);
  return geom;
}

/// A geometry over the vertex and index buffers of `source` (a far-scene twin: no copy); the
/// caller releases the returned reference once attached.
RTCGeometry share_triangles(RTCDevice device, RTCGeometry source, const StaticMesh& mesh) {
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                             rtcGetGeometryBufferData(source, RTC_BUFFER_TYPE_VERTEX, 0), 0,
                             3 * sizeof(float), mesh.vertices.size());
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                             rtcGetGeometryBufferData(source, RTC_BUFFER_TYPE_INDEX, 0), 0,
                             3 * sizeof(unsigned), mesh.triangles.size());
  rtcCommitGeometry(geom);
  return geom;
}

void validate_mesh(const StaticMesh& mesh) {
  const size_t n = mesh.triangles.size();
  if (mesh.classes.size() != 1 && mesh.classes.size() != n) {
    throw std::invalid_argument("static mesh '" + mesh.name +
                                "': classes must have one entry or one per triangle");
  }
  if (mesh.material_indices.size() > 1 && mesh.material_indices.size() != n) {
    throw std::invalid_argument("static mesh '" + mesh.name +
                                "': material indices must have one entry or one per triangle");
  }
  for (const uint16_t m : mesh.material_indices) {
    if (m >= mesh.materials.size()) {
      throw std::invalid_argument("static mesh '" + mesh.name + "': material index out of range");
    }
  }
  if (!mesh.uvs.empty() && mesh.uvs.size() != mesh.vertices.size()) {
    throw std::invalid_argument("static mesh '" + mesh.name + "': one uv per vertex expected");
  }
  if (!mesh.normals.empty() && mesh.normals.size() != mesh.vertices.size()) {
    throw std::invalid_argument("static mesh '" + mesh.name + "': one normal per vertex expected");
  }
  for (const auto& t : mesh.triangles) {
    for (uint32_t i : t) {
      if (i >= mesh.vertices.size()) {
        throw std::invalid_argument("static mesh '" + mesh.name + "': vertex index out of range");
      }
    }
  }
}

/// A stable text key of every field of a material (floats in hexadecimal, exact).
std::string material_key(const Material& m) {
  std::string key = m.name;
  char buf[64];
  auto add = [&](double v) {
    std::snprintf(buf, sizeof buf, "|%a", v);
    key += buf;
  };
  auto add_color = [&](Color c) {
    add(c.r);
    add(c.g);
    add(c.b);
  };
  add_color(m.base_color);
  add(static_cast<double>(m.pattern));
  add(static_cast<double>(m.seed));
  add(m.pattern_scale);
  for (double p : m.params) {
    add(p);
  }
  add_color(m.secondary);
  add(static_cast<double>(m.sign.shape));
  add_color(m.sign.fill);
  add_color(m.sign.border);
  add(m.sign.border_width);
  add(static_cast<double>(m.sign.symbol));
  add_color(m.sign.symbol_color);
  add(static_cast<double>(m.sign.number));
  std::snprintf(buf, sizeof buf, "|%p", static_cast<const void*>(m.image.get()));
  key += buf;
  add(m.metallic);
  add(m.roughness);
  add(m.clearcoat);
  add(m.transmission);
  add(m.ior);
  add_color(m.emission);
  add(static_cast<double>(m.light));
  return key;
}

/// The look of a building mesh that brings only a colour: a procedural facade tinted by it,
/// with floor height, bay width and windows drawn from its instance id (no two alike).
Material tinted_facade(Rgb8 color, uint32_t id) {
  Material m = detail::default_material(SemanticClass::kBuilding);
  m.base_color = linear_rgb(color.r, color.g, color.b);
  m.seed = id;
  auto r = [&](uint32_t salt) { return detail::cell_random(id, salt, 0xFACADEu); };
  m.pattern_scale = 3.0 + 0.6 * r(1);
  m.params = {2.6 + 1.6 * r(2), 0.35 + 0.3 * r(3), 0.38 + 0.25 * r(4), 3.8 + 1.2 * r(5)};
  const double trim = r(6);
  m.secondary = trim < 0.4   ? linear_rgb(60, 58, 56)
                : trim < 0.7 ? linear_rgb(215, 212, 205)
                             : linear_rgb(110, 80, 60);
  return m;
}

/// The street lamps and signal bulbs of a static mesh as light sources (tracer frame).
void add_static_lamps(detail::SceneData& d, const StaticMesh& mesh,
                      const detail::StaticGeometry& info) {
  bool any = false;
  for (const MaterialId m : info.materials) {
    any = any || d.materials[m].light != LightRole::kNone;
  }
  if (!any) {
    return;
  }
  const size_t n = mesh.triangles.size();
  std::vector<LightRole> roles(n);
  std::vector<Color> emissions(n);
  for (size_t i = 0; i < n; ++i) {
    const Material& m = d.materials[info.material_of(static_cast<unsigned>(i))];
    roles[i] = m.light;
    emissions[i] = m.emission;
  }
  std::vector<Vec3> local(mesh.vertices.size());
  for (size_t i = 0; i < local.size(); ++i) {
    local[i] = d.to_local(mesh.vertices[i]);
  }
  // A street light's pole stands on its lowest vertices; its lamps throw their light away from
  // it (along the arm, over the street).
  double z_low = std::numeric_limits<double>::infinity();
  for (const Vec3& v : local) {
    z_low = std::min(z_low, v.z);
  }
  Vec3 foot;
  int feet = 0;
  for (const Vec3& v : local) {
    if (v.z < z_low + 0.05) {
      foot = foot + v;
      ++feet;
    }
  }
  foot = foot * (1.0 / std::max(feet, 1));
  for (detail::LampPatch p : detail::find_lamps(local, mesh.triangles, roles, emissions, {})) {
    const Vec3 out{p.centre.x - foot.x, p.centre.y - foot.y, 0.0};
    p.reach = p.role == LightRole::kStreetLamp && norm(out) > 0.3 ? normalized(out) : Vec3{};
    p.signal = p.role == LightRole::kSignalRed || p.role == LightRole::kSignalYellow ||
                       p.role == LightRole::kSignalGreen
                   ? info.signal
                   : -1;
    if (p.signal >= 0 || p.role == LightRole::kStreetLamp) {
      d.static_lamps.push_back(p);
    }
  }
}

}  // namespace

bool is_countable_class(SemanticClass c) {
  switch (c) {
    case SemanticClass::kUnlabeled:
    case SemanticClass::kRoad:
    case SemanticClass::kSidewalk:
    case SemanticClass::kTerrain:
    case SemanticClass::kSky:
    case SemanticClass::kLaneMarking:
    case SemanticClass::kGround:
    case SemanticClass::kRailTrack:
    case SemanticClass::kParking:
    case SemanticClass::kBikeLane:
    case SemanticClass::kWater:
      return false;
    default:
      return true;
  }
}

Scene::Scene(const SceneOptions& options) : data_(std::make_unique<detail::SceneData>()) {
  data_->options = options;
  data_->device = rtcNewDevice(nullptr);
  if (data_->device == nullptr) {
    throw std::runtime_error("cannot create the Embree device");
  }
  data_->static_scene = rtcNewScene(data_->device);
  rtcSetSceneBuildQuality(data_->static_scene, RTC_BUILD_QUALITY_HIGH);
  data_->far_static = rtcNewScene(data_->device);
  rtcSetSceneBuildQuality(data_->far_static, RTC_BUILD_QUALITY_HIGH);
  data_->top = rtcNewScene(data_->device);
  // The top level holds only instances and is rebuilt every frame: favour build speed.
  rtcSetSceneBuildQuality(data_->top, RTC_BUILD_QUALITY_LOW);
  for (int c = 0; c < kSemanticClassCount; ++c) {
    data_->class_materials[c] =
        add_material(detail::default_material(static_cast<SemanticClass>(c)));
  }
  // The static scene is instanced once at the identity as top-level geometry 0.
  RTCGeometry inst = rtcNewGeometry(data_->device, RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(inst, data_->static_scene);
  const float identity[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, identity);
  rtcSetGeometryMask(inst, detail::kStaticMask);
  rtcCommitGeometry(inst);
  rtcAttachGeometryByID(data_->top, inst, 0);
  rtcReleaseGeometry(inst);
  check_device(data_->device, "scene creation");
}

Scene::~Scene() = default;
Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;

MaterialId Scene::add_material(const Material& material) {
  detail::SceneData& d = *data_;
  std::string key = material_key(material);
  const auto it = d.material_keys.find(key);
  if (it != d.material_keys.end()) {
    return it->second;
  }
  if (d.materials.size() >= 65535) {
    throw std::runtime_error("more than 65535 distinct materials in one scene");
  }
  const auto id = static_cast<MaterialId>(d.materials.size());
  d.materials.push_back(material);
  d.material_keys.emplace(std::move(key), id);
  return id;
}

const Material& Scene::material(MaterialId id) const { return data_->materials.at(id); }
size_t Scene::material_count() const { return data_->materials.size(); }

void Scene::set_entity_shape_source(std::shared_ptr<EntityShapeSource> source) {
  data_->shape_source = std::move(source);
}

void Scene::add_road_mesh(const xodr::RoadMesh& road) {
  StaticMesh mesh;
  mesh.name = "road mesh";
  mesh.vertices.reserve(road.vertices.size());
  for (const auto& v : road.vertices) {
    mesh.vertices.push_back({v.x, v.y, v.z});
  }
  mesh.triangles = road.triangles;
  // The lane coordinates as uvs: asphalt darkens its wheel paths and lays repairs along them.
  if (road.lane_coords.size() == road.vertices.size()) {
    mesh.uvs = road.lane_coords;
  }
  mesh.classes.reserve(road.info.size());
  // Palette: the class looks, plus yellow paint for yellow marks.
  for (int c = 0; c < kSemanticClassCount; ++c) {
    mesh.materials.push_back(detail::default_material(static_cast<SemanticClass>(c)));
  }
  Material yellow = detail::default_material(SemanticClass::kLaneMarking);
  yellow.name = "yellow road paint";
  yellow.base_color = linear_rgb(226, 178, 40);
  mesh.materials.push_back(yellow);
  const auto yellow_index = static_cast<uint16_t>(mesh.materials.size() - 1);
  for (const auto& info : road.info) {
    const SemanticClass c = info.kind == xodr::SurfaceKind::kRoadMark
                                ? SemanticClass::kLaneMarking
                                : semantic_class_of_lane(info.lane_type);
    mesh.classes.push_back(c);
    mesh.material_indices.push_back(
        info.color == xodr::MarkColor::kYellow ? yellow_index : static_cast<uint16_t>(c));
  }
  if (mesh.triangles.empty()) {
    return;
  }
  add_static_mesh(std::move(mesh));
}

uint32_t Scene::add_static_mesh(StaticMesh mesh) {
  validate_mesh(mesh);
  detail::SceneData& d = *data_;
  bool countable = false;
  for (const SemanticClass c : mesh.classes) {
    countable = countable || is_countable_class(c);
  }
  if (mesh.instance_id == 0 && countable) {
    mesh.instance_id = kStaticInstanceBase + static_cast<uint32_t>(d.static_geometries.size());
  }
  if (mesh.triangles.empty()) {
    return mesh.instance_id;
  }
  std::optional<MaterialId> far_material;
  if (mesh.materials.empty() && mesh.color && mesh.classes.size() == 1 &&
      mesh.classes[0] == SemanticClass::kBuilding) {
    // Its rectangular walls become facades in real geometry (recessed windows, ledges, shop
    // fronts); the roof and other walls keep the facade pattern tinted by its colour.
    const Material rest = tinted_facade(*mesh.color, mesh.instance_id);
    const uint64_t seed =
        derive_seed(d.options.seed, "building facade " + std::to_string(mesh.instance_id));
    // Far sky rays see its plain mesh (walls without openings) in the rest's material.
    RTCGeometry plain = make_triangles(d.device, mesh, d.options.origin);
    rtcAttachGeometryByID(d.far_static, plain, static_cast<unsigned>(d.static_geometries.size()));
    rtcReleaseGeometry(plain);
    far_material = add_material(rest);
    mesh = detail::dress_building(std::move(mesh), rest, seed);
  }
  RTCGeometry geom = make_triangles(d.device, mesh, d.options.origin);
  const unsigned id = rtcAttachGeometry(d.static_scene, geom);
  if (!far_material) {
    RTCGeometry twin = share_triangles(d.device, geom, mesh);
    rtcAttachGeometryByID(d.far_static, twin, id);
    rtcReleaseGeometry(twin);
  }
  RTCScene alone = nullptr;
  if (mesh.object.box && !mesh.object.kind.empty() && mesh.instance_id != 0) {
    alone = rtcNewScene(d.device);
    RTCGeometry twin = share_triangles(d.device, geom, mesh);
    rtcAttachGeometry(alone, twin);
    rtcReleaseGeometry(twin);
    rtcCommitScene(alone);
  }
  rtcReleaseGeometry(geom);
  if (id != d.static_geometries.size()) {
    throw std::logic_error("static geometry ids out of step");
  }
  detail::StaticGeometry info;
  info.far_material = far_material;
  info.instance_id = mesh.instance_id;
  info.triangles = mesh.triangles.size();
  if (!mesh.materials.empty()) {
    std::vector<MaterialId> palette;
    for (const Material& m : mesh.materials) {
      palette.push_back(add_material(m));
    }
    if (mesh.material_indices.empty()) {
      info.materials = {palette[0]};
    } else {
      for (const uint16_t i : mesh.material_indices) {
        info.materials.push_back(palette[i]);
      }
    }
  } else if (mesh.color) {
    const bool building = mesh.classes.size() == 1 && mesh.classes[0] == SemanticClass::kBuilding;
    info.materials = {add_material(
        building ? tinted_facade(*mesh.color, mesh.instance_id)
                 : materials::plain("colour " + std::to_string(mesh.color->r) + "," +
                                        std::to_string(mesh.color->g) + "," +
                                        std::to_string(mesh.color->b),
                                    linear_rgb(mesh.color->r, mesh.color->g, mesh.color->b)))};
  } else {
    for (const SemanticClass c : mesh.classes) {
      info.materials.push_back(d.class_materials[static_cast<size_t>(c)]);
    }
  }
  info.classes = std::move(mesh.classes);
  if (!mesh.signal_id.empty()) {
    size_t index = 0;
    while (index < d.signal_ids.size() && d.signal_ids[index] != mesh.signal_id) {
      ++index;
    }
    if (index == d.signal_ids.size()) {
      d.signal_ids.push_back(mesh.signal_id);
      d.signal_states.emplace_back();
      d.signal_bulbs.push_back(0);
    }
    info.signal = static_cast<int>(index);
  }
  Bounds bounds;
  double base_z = 1e300;
  for (const Vec3& v : mesh.vertices) {
    bounds.min = {std::min(bounds.min.x, v.x), std::min(bounds.min.y, v.y),
                  std::min(bounds.min.z, v.z)};
    bounds.max = {std::max(bounds.max.x, v.x), std::max(bounds.max.y, v.y),
                  std::max(bounds.max.z, v.z)};
    base_z = std::min(base_z, v.z);
    d.bounds.min = {std::min(d.bounds.min.x, v.x), std::min(d.bounds.min.y, v.y),
                    std::min(d.bounds.min.z, v.z)};
    d.bounds.max = {std::max(d.bounds.max.x, v.x), std::max(d.bounds.max.y, v.y),
                    std::max(d.bounds.max.z, v.z)};
  }
  info.base_z = base_z - d.options.origin.z;
  if (!mesh.object.kind.empty() && mesh.instance_id != 0) {
    d.objects[mesh.instance_id] = {mesh.object, bounds, info.signal, alone};
  }
  if (!mesh.uvs.empty()) {
    info.uvs = std::move(mesh.uvs);
    info.uv_triangles = mesh.triangles;
    for (const auto& t : mesh.triangles) {
      const Vec3 e1 = mesh.vertices[t[1]] - mesh.vertices[t[0]];
      const Vec3 e2 = mesh.vertices[t[2]] - mesh.vertices[t[0]];
      const double area = norm(cross(e1, e2));
      const auto& a = info.uvs[t[0]];
      const auto& b = info.uvs[t[1]];
      const auto& c = info.uvs[t[2]];
      const double uv_area =
          std::fabs((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
      info.uv_per_m.push_back(area > 0.0 ? static_cast<float>(std::sqrt(uv_area / area)) : 1.0f);
    }
  }
  if (!mesh.normals.empty()) {
    info.normal_triangles = mesh.triangles;
    for (const Vec3& n : mesh.normals) {
      info.normals.push_back(
          {static_cast<float>(n.x), static_cast<float>(n.y), static_cast<float>(n.z)});
    }
  }
  add_static_lamps(d, mesh, info);
  d.static_geometries.push_back(std::move(info));
  d.triangle_count += d.static_geometries.back().triangles;
  d.committed = false;
  return d.static_geometries.back().instance_id;
}

void Scene::commit() {
  rtcCommitScene(data_->static_scene);
  rtcCommitScene(data_->far_static);
  data_->committed = true;
  // The top level changes with the static scene's bounds: rebuild it with the current entities.
  std::vector<engine::EntitySnapshot> current = data_->entities;
  set_entities(current, data_->motion_span);
  check_device(data_->device, "static scene commit");
}

std::span<const engine::EntitySnapshot> Scene::entities() const { return data_->entities; }

Bounds Scene::static_bounds() const { return data_->bounds; }
const SceneOptions& Scene::options() const { return data_->options; }
size_t Scene::static_mesh_count() const { return data_->static_geometries.size(); }
size_t Scene::static_triangle_count() const { return data_->triangle_count; }

}  // namespace corsa::sensors
