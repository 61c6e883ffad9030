#include "corsa/sensors/scene.h"

#include <stdexcept>
#include <string>

#include "scene_data.h"

namespace corsa::sensors {
namespace detail {

SceneData::~SceneData() {
  for (RTCGeometry g : instance_pool) {
    rtcReleaseGeometry(g);
  }
  for (RTCScene s : prototypes) {
    if (s != nullptr) {
      rtcReleaseScene(s);
    }
  }
  if (top != nullptr) {
    rtcReleaseScene(top);
  }
  if (static_scene != nullptr) {
    rtcReleaseScene(static_scene);
  }
  if (device != nullptr) {
    rtcReleaseDevice(device);
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

void validate_mesh(const StaticMesh& mesh) {
  if (mesh.classes.size() != 1 && mesh.classes.size() != mesh.triangles.size()) {
    throw std::invalid_argument("static mesh '" + mesh.name +
                                "': classes must have one entry or one per triangle");
  }
  for (const auto& t : mesh.triangles) {
    for (uint32_t i : t) {
      if (i >= mesh.vertices.size()) {
        throw std::invalid_argument("static mesh '" + mesh.name + "': vertex index out of range");
      }
    }
  }
}

}  // namespace

Scene::Scene(const SceneOptions& options) : data_(std::make_unique<detail::SceneData>()) {
  data_->options = options;
  data_->device = rtcNewDevice(nullptr);
  if (data_->device == nullptr) {
    throw std::runtime_error("cannot create the Embree device");
  }
  data_->static_scene = rtcNewScene(data_->device);
  rtcSetSceneBuildQuality(data_->static_scene, RTC_BUILD_QUALITY_HIGH);
  data_->top = rtcNewScene(data_->device);
  // The top level holds only instances and is rebuilt every frame: favour build speed.
  rtcSetSceneBuildQuality(data_->top, RTC_BUILD_QUALITY_LOW);
  for (size_t c = 0; c < detail::kCategoryCount; ++c) {
    set_prototype(static_cast<engine::EntityCategory>(c),
                  detail::default_prototype(static_cast<engine::EntityCategory>(c)));
  }
  // The static scene is instanced once at the identity as top-level geometry 0.
  RTCGeometry inst = rtcNewGeometry(data_->device, RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(inst, data_->static_scene);
  const float identity[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, identity);
  rtcCommitGeometry(inst);
  rtcAttachGeometryByID(data_->top, inst, 0);
  rtcReleaseGeometry(inst);
  check_device(data_->device, "scene creation");
}

Scene::~Scene() = default;
Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;

void Scene::add_road_mesh(const xodr::RoadMesh& road) {
  StaticMesh mesh;
  mesh.name = "road mesh";
  mesh.vertices.reserve(road.vertices.size());
  for (const auto& v : road.vertices) {
    mesh.vertices.push_back({v.x, v.y, v.z});
  }
  mesh.triangles = road.triangles;
  mesh.classes.reserve(road.info.size());
  for (const auto& info : road.info) {
    mesh.classes.push_back(info.kind == xodr::SurfaceKind::kRoadMark
                               ? SemanticClass::kLaneMarking
                               : semantic_class_of_lane(info.lane_type));
  }
  if (mesh.triangles.empty()) {
    return;
  }
  add_static_mesh(std::move(mesh));
}

uint32_t Scene::add_static_mesh(StaticMesh mesh) {
  validate_mesh(mesh);
  detail::SceneData& d = *data_;
  if (mesh.instance_id == 0 && mesh.classes.size() == 1 &&
      (mesh.classes[0] == SemanticClass::kBuilding ||
       mesh.classes[0] == SemanticClass::kStaticObject)) {
    mesh.instance_id = kStaticInstanceBase + static_cast<uint32_t>(d.static_geometries.size());
  }
  if (mesh.triangles.empty()) {
    return mesh.instance_id;
  }
  RTCGeometry geom = make_triangles(d.device, mesh, d.options.origin);
  const unsigned id = rtcAttachGeometry(d.static_scene, geom);
  rtcReleaseGeometry(geom);
  if (id != d.static_geometries.size()) {
    throw std::logic_error("static geometry ids out of step");
  }
  detail::StaticGeometry info;
  info.classes = std::move(mesh.classes);
  info.instance_id = mesh.instance_id;
  info.color = mesh.color;
  info.triangles = mesh.triangles.size();
  d.static_geometries.push_back(std::move(info));
  for (const Vec3& v : mesh.vertices) {
    d.bounds.min = {std::min(d.bounds.min.x, v.x), std::min(d.bounds.min.y, v.y),
                    std::min(d.bounds.min.z, v.z)};
    d.bounds.max = {std::max(d.bounds.max.x, v.x), std::max(d.bounds.max.y, v.y),
                    std::max(d.bounds.max.z, v.z)};
  }
  d.triangle_count += mesh.triangles.size();
  d.committed = false;
  return d.static_geometries.back().instance_id;
}

void Scene::set_prototype(engine::EntityCategory category, const StaticMesh& unit_mesh) {
  detail::SceneData& d = *data_;
  StaticMesh mesh = unit_mesh;
  mesh.classes = {SemanticClass::kObstacle};
  validate_mesh(mesh);
  RTCScene scene = rtcNewScene(d.device);
  RTCGeometry geom = make_triangles(d.device, mesh, Vec3{});
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(scene);
  auto& slot = d.prototypes[static_cast<size_t>(category)];
  if (slot != nullptr) {
    rtcReleaseScene(slot);
  }
  slot = scene;
  check_device(d.device, "prototype");
}

void Scene::commit() {
  rtcCommitScene(data_->static_scene);
  data_->committed = true;
  // The top level changes with the static scene's bounds: rebuild it with the current entities.
  std::vector<engine::EntitySnapshot> current = data_->entities;
  set_entities(current);
  check_device(data_->device, "static scene commit");
}

std::span<const engine::EntitySnapshot> Scene::entities() const { return data_->entities; }

Bounds Scene::static_bounds() const { return data_->bounds; }
const SceneOptions& Scene::options() const { return data_->options; }
size_t Scene::static_mesh_count() const { return data_->static_geometries.size(); }
size_t Scene::static_triangle_count() const { return data_->triangle_count; }

}  // namespace corsa::sensors
