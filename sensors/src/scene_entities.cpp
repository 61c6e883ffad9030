// Per-frame part of the scene: entity shapes (built at first sight, articulated every frame),
// their instances, the traffic-signal states, and single-ray queries.

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "corsa/core/strings.h"
#include "corsa/sensors/scene.h"
#include "material_defaults.h"
#include "scene_data.h"

namespace corsa::sensors {
namespace {

bool same_box(const engine::Box& a, const engine::Box& b) {
  return a.center_x == b.center_x && a.center_y == b.center_y && a.center_z == b.center_z &&
         a.length == b.length && a.width == b.width && a.height == b.height;
}

/// A user's mesh (from an EntityShapeSource) as a rigid mesh of one bone.
detail::ArticulatedMesh from_static(const StaticMesh& mesh, SemanticClass fallback) {
  detail::ArticulatedMesh out;
  out.vertices = mesh.vertices;
  out.bone.assign(mesh.vertices.size(), 0);
  out.triangles = mesh.triangles;
  const size_t n = mesh.triangles.size();
  out.uvs = mesh.uvs.size() == mesh.vertices.size()
                ? mesh.uvs
                : std::vector<std::array<float, 2>>(mesh.vertices.size(), {0.0f, 0.0f});
  out.materials = mesh.materials;
  if (out.materials.empty()) {
    out.materials.push_back(
        mesh.color ? materials::plain("model colour",
                                      linear_rgb(mesh.color->r, mesh.color->g, mesh.color->b), 0.5)
                   : detail::default_material(fallback));
  }
  for (size_t i = 0; i < n; ++i) {
    const uint16_t m = mesh.material_indices.size() == n   ? mesh.material_indices[i]
                       : mesh.material_indices.size() == 1 ? mesh.material_indices[0]
                                                           : 0;
    out.material.push_back(std::min<uint16_t>(m, static_cast<uint16_t>(out.materials.size() - 1)));
    out.classes.push_back(mesh.classes.size() == n ? mesh.classes[i] : fallback);
  }
  return out;
}

/// Writes the posed vertices of a shape into its Embree vertex buffer.
void write_vertices(detail::EntityShape& shape, const std::vector<Rigid>* bones) {
  auto* v =
      static_cast<float*>(rtcGetGeometryBufferData(shape.geometry, RTC_BUFFER_TYPE_VERTEX, 0));
  const auto& mesh = shape.mesh;
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    Vec3 p = mesh.vertices[i];
    if (bones != nullptr && mesh.bone[i] < bones->size()) {
      p = (*bones)[mesh.bone[i]].apply(p);
    }
    v[3 * i] = static_cast<float>(p.x);
    v[3 * i + 1] = static_cast<float>(p.y);
    v[3 * i + 2] = static_cast<float>(p.z);
  }
}

bool same_pose(const std::vector<Rigid>& a, const std::vector<Rigid>& b) {
  if (a.size() != b.size()) {
    return false;
  }
  for (size_t i = 0; i < a.size(); ++i) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) {
        if (a[i].rotation.m[r][c] != b[i].rotation.m[r][c]) {
          return false;
        }
      }
    }
    if (a[i].translation.x != b[i].translation.x || a[i].translation.y != b[i].translation.y ||
        a[i].translation.z != b[i].translation.z) {
      return false;
    }
  }
  return true;
}

/// Builds (or rebuilds) the shape of an entity and its Embree scene.
void make_shape(Scene& scene, detail::SceneData& d, const engine::EntitySnapshot& e,
                detail::EntityShape& shape) {
  shape.category = e.category;
  shape.box = e.box;
  shape.model3d = e.model3d;
  StaticMesh user;
  if (d.shape_source != nullptr && d.shape_source->shape_of(e, user) && !user.triangles.empty()) {
    shape.mesh = from_static(user, semantic_class_of_entity(e.category));
    shape.pose = nullptr;
  } else {
    detail::build_entity_shape(e, d.options.seed, shape);
  }
  std::vector<MaterialId> palette;
  for (const Material& m : shape.mesh.materials) {
    palette.push_back(scene.add_material(m));
  }
  shape.materials.clear();
  std::vector<LightRole> roles;
  std::vector<Color> emissions;
  std::vector<uint32_t> bones;
  for (size_t i = 0; i < shape.mesh.material.size(); ++i) {
    const uint16_t m = shape.mesh.material[i];
    shape.materials.push_back(palette[m]);
    const Material& mat = shape.mesh.materials[m];
    roles.push_back(mat.light);
    emissions.push_back(mat.emission);
    bones.push_back(shape.mesh.bone.empty() ? 0u : shape.mesh.bone[shape.mesh.triangles[i][0]]);
  }
  shape.lamps =
      detail::find_lamps(shape.mesh.vertices, shape.mesh.triangles, roles, emissions, bones);
  shape.scene = rtcNewScene(d.device);
  shape.geometry = rtcNewGeometry(d.device, RTC_GEOMETRY_TYPE_TRIANGLE);
  const auto& mesh = shape.mesh;
  rtcSetNewGeometryBuffer(shape.geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                          3 * sizeof(float), mesh.vertices.size());
  auto* idx = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(shape.geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                              3 * sizeof(unsigned), mesh.triangles.size()));
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      idx[3 * i + k] = mesh.triangles[i][k];
    }
  }
  if (shape.pose) {
    // Articulated: the vertices move every frame, the topology never.
    rtcSetSceneFlags(shape.scene, RTC_SCENE_FLAG_DYNAMIC);
    rtcSetGeometryBuildQuality(shape.geometry, RTC_BUILD_QUALITY_REFIT);
  }
  write_vertices(shape, nullptr);
  rtcCommitGeometry(shape.geometry);
  rtcAttachGeometry(shape.scene, shape.geometry);
  rtcReleaseGeometry(shape.geometry);  // the scene holds it
  rtcCommitScene(shape.scene);
  shape.last_pose.clear();
}

}  // namespace

namespace {

/// Column-major 3x4 instance transform of entity `e` at `t` seconds from the snapshot (its pose
/// moved on with its velocity and yaw rate): the rotation's columns, then the translation.
void instance_transform(const engine::EntitySnapshot& e, double t, const detail::SceneData& d,
                        float xfm[12]) {
  const Rigid pose = rigid_from_pose(e.pose.x + e.vx * t, e.pose.y + e.vy * t, e.pose.z + e.vz * t,
                                     e.pose.h + e.yaw_rate * t, e.pose.p, e.pose.r);
  const Vec3 origin = d.to_local(pose.translation);
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) {
      xfm[3 * c + r] = static_cast<float>(pose.rotation.m[r][c]);
    }
  }
  xfm[9] = static_cast<float>(origin.x);
  xfm[10] = static_cast<float>(origin.y);
  xfm[11] = static_cast<float>(origin.z);
}

/// The top-level scene of moving entities, with the static scene at geomID 0 as in `top`.
RTCScene make_moving_top(detail::SceneData& d) {
  RTCScene top = rtcNewScene(d.device);
  rtcSetSceneBuildQuality(top, RTC_BUILD_QUALITY_LOW);
  RTCGeometry inst = rtcNewGeometry(d.device, RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(inst, d.static_scene);
  const float identity[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, identity);
  rtcSetGeometryMask(inst, detail::kStaticMask);
  rtcCommitGeometry(inst);
  rtcAttachGeometryByID(top, inst, 0);
  rtcReleaseGeometry(inst);
  return top;
}

/// The instance of entity slot `used` in the moving top level: the same shape, its pose at
/// both ends of the motion interval.
void place_moving(detail::SceneData& d, size_t used, RTCScene shape,
                  const engine::EntitySnapshot& e) {
  if (used == d.moving_pool.size()) {
    RTCGeometry m = rtcNewGeometry(d.device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryTimeStepCount(m, 2);
    rtcAttachGeometryByID(d.moving_top, m, static_cast<unsigned>(used + 1));
    d.moving_pool.push_back(m);
  }
  RTCGeometry m = d.moving_pool[used];
  rtcSetGeometryInstancedScene(m, shape);
  float xfm[12];
  for (unsigned step = 0; step < 2; ++step) {
    instance_transform(e, (step == 0 ? -0.5 : 0.5) * d.motion_span, d, xfm);
    rtcSetGeometryTransform(m, step, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
  }
  rtcEnableGeometry(m);
  rtcCommitGeometry(m);
}

}  // namespace

void Scene::set_entities(std::span<const engine::EntitySnapshot> entities, double motion_span) {
  detail::SceneData& d = *data_;
  if (!d.committed) {
    throw std::logic_error("Scene::set_entities before Scene::commit");
  }
  d.entities.assign(entities.begin(), entities.end());
  d.instances.clear();
  d.motion_span = motion_span > 0.0 ? motion_span : 0.0;
  if (d.motion_span > 0.0 && d.moving_top == nullptr) {
    d.moving_top = make_moving_top(d);
  }
  size_t used = 0;
  std::vector<Rigid> bones;
  for (size_t i = 0; i < d.entities.size(); ++i) {
    const engine::EntitySnapshot& e = d.entities[i];
    if (!e.visible || !(e.box.length > 0.0) || !(e.box.width > 0.0) || !(e.box.height > 0.0)) {
      continue;
    }
    std::unique_ptr<detail::EntityShape>& slot = d.shapes[e.instance_id];
    if (!slot || slot->category != e.category || !same_box(slot->box, e.box) ||
        slot->model3d != e.model3d) {
      slot = std::make_unique<detail::EntityShape>();
      make_shape(*this, d, e, *slot);
    }
    detail::EntityShape& shape = *slot;
    if (shape.pose) {
      bones.clear();
      shape.pose(e, bones);
      if (!same_pose(bones, shape.last_pose)) {
        write_vertices(shape, &bones);
        rtcUpdateGeometryBuffer(shape.geometry, RTC_BUFFER_TYPE_VERTEX, 0);
        rtcCommitGeometry(shape.geometry);
        rtcCommitScene(shape.scene);
        shape.last_pose = bones;
      }
    }
    if (used == d.instance_pool.size()) {
      RTCGeometry g = rtcNewGeometry(d.device, RTC_GEOMETRY_TYPE_INSTANCE);
      rtcAttachGeometryByID(d.top, g, static_cast<unsigned>(used + 1));
      d.instance_pool.push_back(g);
    }
    RTCGeometry g = d.instance_pool[used];
    rtcSetGeometryInstancedScene(g, shape.scene);
    const Rigid pose = rigid_from_pose(e.pose.x, e.pose.y, e.pose.z, e.pose.h, e.pose.p, e.pose.r);
    float xfm[12];
    instance_transform(e, 0.0, d, xfm);
    rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
    rtcEnableGeometry(g);
    rtcCommitGeometry(g);
    if (d.motion_span > 0.0) {
      place_moving(d, used, shape.scene, e);
    }
    detail::EntityInstance inst;
    inst.semantic = semantic_class_of_entity(e.category);
    inst.instance_id = e.instance_id;
    inst.snapshot_index = i;
    inst.shape = &shape;
    inst.normal_matrix = pose.rotation;
    inst.world_from_entity = pose;
    inst.lights_on = e.lights_on;
    inst.lights_set = e.lights_set;
    d.instances.push_back(inst);
    ++used;
  }
  for (size_t i = used; i < d.instance_pool.size(); ++i) {
    rtcDisableGeometry(d.instance_pool[i]);
    rtcCommitGeometry(d.instance_pool[i]);
  }
  rtcCommitScene(d.top);
  if (d.motion_span > 0.0) {
    for (size_t i = used; i < d.moving_pool.size(); ++i) {
      rtcDisableGeometry(d.moving_pool[i]);
      rtcCommitGeometry(d.moving_pool[i]);
    }
    rtcCommitScene(d.moving_top);
  }
  if (rtcGetDeviceError(d.device) != RTC_ERROR_NONE) {
    throw std::runtime_error("Embree error while placing the entities");
  }
}

void Scene::set_signals(std::span<const engine::SignalSnapshot> signals) {
  detail::SceneData& d = *data_;
  for (size_t i = 0; i < d.signal_ids.size(); ++i) {
    d.signal_states[i].clear();
    d.signal_bulbs[i] = 0;
    for (const auto& s : signals) {
      if (s.id == d.signal_ids[i]) {
        d.signal_states[i] = s.state;
      }
    }
    // OpenSCENARIO gives the state as text; the common forms are one word per lamp from the
    // top ("on;off;off" = red, as in the ASAM examples) or a colour name ("red", "green").
    const std::string state = to_lower(d.signal_states[i]);
    const std::vector<std::string_view> parts = split(state, ';');
    uint8_t bulbs = 0;
    if (parts.size() >= 3) {
      for (size_t k = 0; k < 3; ++k) {
        const std::string_view p = trim(parts[k]);
        if (p == "on" || p == "1" || p == "true" || p == "flashing") {
          bulbs |= static_cast<uint8_t>(1u << k);
        }
      }
    } else {
      bulbs |= state.find("red") != std::string::npos ? 1 : 0;
      bulbs |= state.find("yellow") != std::string::npos || state.find("amber") != std::string::npos
                   ? 2
                   : 0;
      bulbs |= state.find("green") != std::string::npos ? 4 : 0;
    }
    d.signal_bulbs[i] = bulbs;
  }
}

std::string Scene::signal_state(const std::string& signal_id) const {
  const detail::SceneData& d = *data_;
  for (size_t i = 0; i < d.signal_ids.size(); ++i) {
    if (d.signal_ids[i] == signal_id) {
      return d.signal_states[i];
    }
  }
  return {};
}

std::optional<RayHit> Scene::intersect(Vec3 origin, Vec3 direction, double max_distance) const {
  const detail::SceneData& d = *data_;
  const Vec3 dir = normalized(direction);
  const Vec3 o = d.to_local(origin);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh{};
  rh.ray.org_x = static_cast<float>(o.x);
  rh.ray.org_y = static_cast<float>(o.y);
  rh.ray.org_z = static_cast<float>(o.z);
  rh.ray.dir_x = static_cast<float>(dir.x);
  rh.ray.dir_y = static_cast<float>(dir.y);
  rh.ray.dir_z = static_cast<float>(dir.z);
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = static_cast<float>(std::min(max_distance, 3.0e38));
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(d.top, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
    return std::nullopt;
  }
  RayHit hit;
  hit.distance = rh.ray.tfar;
  hit.point = origin + dir * hit.distance;
  const auto label = d.label(rh.hit.instID[0], rh.hit.geomID, rh.hit.primID);
  hit.semantic = label.semantic;
  hit.instance_id = label.instance_id;
  hit.entity_index =
      label.entity < 0 ? -1 : static_cast<int>(d.instances[label.entity].snapshot_index);
  Vec3 n = d.world_normal(rh.hit.instID[0], {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z});
  if (dot(n, dir) > 0.0) {
    n = -n;
  }
  hit.normal = n;
  return hit;
}

}  // namespace corsa::sensors
