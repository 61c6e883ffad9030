// Per-frame part of the scene: entity instances and single-ray queries.

#include <limits>
#include <stdexcept>

#include "corsa/sensors/scene.h"
#include "scene_data.h"

namespace corsa::sensors {

void Scene::set_entities(std::span<const engine::EntitySnapshot> entities) {
  detail::SceneData& d = *data_;
  if (!d.committed) {
    throw std::logic_error("Scene::set_entities before Scene::commit");
  }
  d.entities.assign(entities.begin(), entities.end());
  d.instances.clear();
  size_t used = 0;
  for (size_t i = 0; i < d.entities.size(); ++i) {
    const engine::EntitySnapshot& e = d.entities[i];
    if (!e.visible || !(e.box.length > 0.0) || !(e.box.width > 0.0) || !(e.box.height > 0.0)) {
      continue;
    }
    if (used == d.instance_pool.size()) {
      RTCGeometry g = rtcNewGeometry(d.device, RTC_GEOMETRY_TYPE_INSTANCE);
      rtcAttachGeometryByID(d.top, g, static_cast<unsigned>(used + 1));
      d.instance_pool.push_back(g);
    }
    RTCGeometry g = d.instance_pool[used];
    rtcSetGeometryInstancedScene(g, d.prototypes[static_cast<size_t>(e.category)]);
    const Rigid pose = rigid_from_pose(e.pose.x, e.pose.y, e.pose.z, e.pose.h, e.pose.p, e.pose.r);
    const Vec3 centre = d.to_local(pose.apply({e.box.center_x, e.box.center_y, e.box.center_z}));
    const double scale[3] = {e.box.length, e.box.width, e.box.height};
    float xfm[12];  // column-major 3x4: columns are the scaled axes, then the translation
    for (int c = 0; c < 3; ++c) {
      for (int r = 0; r < 3; ++r) {
        xfm[3 * c + r] = static_cast<float>(pose.rotation.m[r][c] * scale[c]);
      }
    }
    xfm[9] = static_cast<float>(centre.x);
    xfm[10] = static_cast<float>(centre.y);
    xfm[11] = static_cast<float>(centre.z);
    rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
    rtcEnableGeometry(g);
    rtcCommitGeometry(g);
    detail::EntityInstance inst;
    inst.semantic = semantic_class_of_entity(e.category);
    inst.instance_id = e.instance_id;
    inst.snapshot_index = i;
    // (R S)^-T = R S^-1 for a rotation R and a diagonal scale S.
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) {
        inst.normal_matrix.m[r][c] = pose.rotation.m[r][c] / scale[c];
      }
    }
    d.instances.push_back(inst);
    ++used;
  }
  for (size_t i = used; i < d.instance_pool.size(); ++i) {
    rtcDisableGeometry(d.instance_pool[i]);
    rtcCommitGeometry(d.instance_pool[i]);
  }
  rtcCommitScene(d.top);
  if (rtcGetDeviceError(d.device) != RTC_ERROR_NONE) {
    throw std::runtime_error("Embree error while placing the entities");
  }
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
