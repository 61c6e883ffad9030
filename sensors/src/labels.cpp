#include "corsa/sensors/labels.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "corsa/sensors/camera_render.h"
#include "scene_data.h"
#include "vehicle_lamps.h"

namespace corsa::sensors {
namespace {

constexpr double kNear = 0.05;       // m, near clipping plane for projecting boxes
constexpr int kSilhouetteGrid = 64;  // at most 64 x 64 samples per object for occlusion

struct PixelStats {
  uint64_t count = 0;
  int x_min = 1 << 30, y_min = 1 << 30, x_max = -1, y_max = -1;
};

/// Pixel counts and boxes of the entities and of the static objects marked in `boxed` (by
/// instance id - kStaticInstanceBase).
std::map<uint32_t, PixelStats> pixel_stats(std::span<const uint32_t> instance, int width,
                                           const std::vector<bool>& boxed) {
  std::map<uint32_t, PixelStats> stats;
  for (size_t i = 0; i < instance.size(); ++i) {
    if (instance[i] == 0) {
      continue;
    }
    if (instance[i] >= kStaticInstanceBase) {
      const size_t k = instance[i] - kStaticInstanceBase;
      if (k >= boxed.size() || !boxed[k]) {
        continue;
      }
    }
    PixelStats& s = stats[instance[i]];
    const int x = static_cast<int>(i % width);
    const int y = static_cast<int>(i / width);
    ++s.count;
    s.x_min = std::min(s.x_min, x);
    s.x_max = std::max(s.x_max, x);
    s.y_min = std::min(s.y_min, y);
    s.y_max = std::max(s.y_max, y);
  }
  return stats;
}

Box3 transform_box(const Rigid& t, const Box3& b) {
  Box3 out = b;
  out.center = t.apply(b.center);
  out.rotation = t.rotation * b.rotation;
  return out;
}

/// Projection of a box (optical frame) clipped to the near plane; false if wholly behind.
bool project_box_into(const CameraModel& camera, const Box3& box, Box2& out) {
  const auto c = box.corners();
  std::vector<Vec3> points;
  for (const Vec3& p : c) {
    if (p.z >= kNear) {
      points.push_back(p);
    }
  }
  // Edges join corners whose indices differ in one bit.
  for (int i = 0; i < 8; ++i) {
    for (int bit = 1; bit < 8; bit <<= 1) {
      const int j = i | bit;
      if (j == i) {
        continue;
      }
      const Vec3 a = c[i];
      const Vec3 b = c[j];
      if ((a.z < kNear) != (b.z < kNear)) {
        const double t = (kNear - a.z) / (b.z - a.z);
        points.push_back(a + (b - a) * t);
      }
    }
  }
  if (points.empty()) {
    return false;
  }
  out = {1e300, 1e300, -1e300, -1e300};
  for (const Vec3& p : points) {
    const auto px = camera.project(p);
    if (!px) {
      continue;
    }
    out.x_min = std::min(out.x_min, px->u);
    out.x_max = std::max(out.x_max, px->u);
    out.y_min = std::min(out.y_min, px->v);
    out.y_max = std::max(out.y_max, px->v);
  }
  return out.x_min <= out.x_max;
}

/// Share of an object's silhouette (`shape`: its own triangles alone, in the frame
/// `shape_from_world` takes map points to) not covered by its pixels (`id`) in `instance`.
double occlusion_of(RTCScene shape, const Rigid& shape_from_world, uint32_t id,
                    const CameraRenderer& camera, const Rigid& world_from_cam, const Box2& box,
                    std::span<const uint32_t> instance, int width) {
  auto local = [&](Vec3 v) { return shape_from_world.rotation * v; };
  const Vec3 origin = shape_from_world.apply(world_from_cam.translation);
  const int x0 = static_cast<int>(std::ceil(box.x_min));
  const int x1 = static_cast<int>(std::floor(box.x_max));
  const int y0 = static_cast<int>(std::ceil(box.y_min));
  const int y1 = static_cast<int>(std::floor(box.y_max));
  const int stride = std::max(1, std::max(x1 - x0, y1 - y0) / kSilhouetteGrid + 1);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  uint64_t silhouette = 0, seen = 0;
  for (int y = y0; y <= y1; y += stride) {
    for (int x = x0; x <= x1; x += stride) {
      const Vec3 dir = local(world_from_cam.apply_direction(camera.pixel_ray(x, y)));
      RTCRay ray{};
      ray.org_x = static_cast<float>(origin.x);
      ray.org_y = static_cast<float>(origin.y);
      ray.org_z = static_cast<float>(origin.z);
      ray.dir_x = static_cast<float>(dir.x);
      ray.dir_y = static_cast<float>(dir.y);
      ray.dir_z = static_cast<float>(dir.z);
      ray.tfar = std::numeric_limits<float>::infinity();
      ray.mask = 0xFFFFFFFFu;
      rtcOccluded1(shape, &context, &ray);
      if (ray.tfar >= 0.0f) {
        continue;  // the shape alone does not cover this pixel
      }
      ++silhouette;
      seen += instance[static_cast<size_t>(y) * width + x] == id;
    }
  }
  return silhouette == 0 ? 0.0 : 1.0 - static_cast<double>(seen) / silhouette;
}

}  // namespace

double Box3::yaw() const { return std::atan2(rotation.m[1][0], rotation.m[0][0]); }

std::array<Vec3, 8> Box3::corners() const {
  std::array<Vec3, 8> c;
  for (int i = 0; i < 8; ++i) {
    const Vec3 local{(i & 1 ? 0.5 : -0.5) * length, (i & 2 ? 0.5 : -0.5) * width,
                     (i & 4 ? 0.5 : -0.5) * height};
    c[i] = center + rotation * local;
  }
  return c;
}

int kitti_occlusion_level(double occlusion) {
  if (occlusion < 0.1) {
    return 0;
  }
  if (occlusion < 0.5) {
    return 1;
  }
  return occlusion < 0.9 ? 2 : 3;
}

double kitti_rotation_y(const Box3& box) {
  const Vec3 forward = box.rotation.column(0);
  return std::atan2(-forward.z, forward.x);
}

std::optional<Box2> projected_box(const CameraModel& camera, const Box3& box) {
  Box2 out;
  if (!project_box_into(camera, box, out)) {
    return std::nullopt;
  }
  return out;
}

Box3 entity_box(const engine::EntitySnapshot& e) {
  const Rigid pose = rigid_from_pose(e.pose.x, e.pose.y, e.pose.z, e.pose.h, e.pose.p, e.pose.r);
  Box3 b;
  b.center = pose.apply({e.box.center_x, e.box.center_y, e.box.center_z});
  b.rotation = pose.rotation;
  b.length = e.box.length;
  b.width = e.box.width;
  b.height = e.box.height;
  return b;
}

namespace {

/// The labelled box of an entity: its box, grown to hold a person's posed body. A stride (0.7 m
/// at a brisk walk, feet and hands swinging) is longer than the 0.5 m box pedestrians are
/// usually given, and the hands hang a few centimetres beyond a 0.6 m wide one; a label must hold
/// the whole object, as KITTI's annotators draw the box around all of a person's points (a foot
/// out of the box put the tight 2D box of the person's pixels beyond the projected 3D box).
Box3 label_box(const engine::EntitySnapshot& e, const detail::EntityInstance& inst) {
  Box3 b = entity_box(e);
  const detail::EntityShape* shape = inst.shape;
  if (inst.semantic != SemanticClass::kPerson || shape == nullptr || shape->last_pose.empty()) {
    return b;
  }
  const auto& mesh = shape->mesh;
  const Vec3 c{e.box.center_x, e.box.center_y, e.box.center_z};
  Vec3 hi{0.5 * e.box.length, 0.5 * e.box.width, 0.5 * e.box.height};  // from the box centre
  Vec3 lo = hi;
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3 p = (mesh.bone[i] < shape->last_pose.size()
                        ? shape->last_pose[mesh.bone[i]].apply(mesh.vertices[i])
                        : mesh.vertices[i]) -
                   c;
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    lo = {std::max(lo.x, -p.x), std::max(lo.y, -p.y), std::max(lo.z, -p.z)};
  }
  b.length = hi.x + lo.x;
  b.width = hi.y + lo.y;
  b.height = hi.z + lo.z;
  b.center = b.center + b.rotation * ((hi - lo) * 0.5);
  return b;
}

// What a camera or LiDAR label of an entity's instance holds before the sensor's own measures:
// who it is, its class and its box in the world and in the sensor's frame.
ObjectLabel entity_label(const detail::SceneData& d, const detail::EntityInstance& inst,
                         const Rigid& sensor_from_world) {
  const engine::EntitySnapshot& e = d.entities[inst.snapshot_index];
  ObjectLabel l;
  l.instance_id = inst.instance_id;
  l.track_id = e.instance_id;
  l.name = e.name;
  l.semantic = inst.semantic;
  l.box_world = label_box(e, inst);
  l.box_sensor = transform_box(sensor_from_world, l.box_world);
  l.distance = norm(l.box_sensor.center);
  return l;
}

bool has_vehicle_lights(engine::EntityCategory c) {
  using C = engine::EntityCategory;
  return c != C::kPedestrian && c != C::kWheelchair && c != C::kAnimal && c != C::kObstacle;
}

/// A vehicle's lights as the frame draws them: every light lit, flashing or set, and the lamps of
/// its shape that are lit.
VehicleLightsLabel vehicle_lights_label(const engine::EntitySnapshot& e,
                                        const detail::EntityInstance& inst, bool dark) {
  const detail::VehicleLampState state = detail::vehicle_lamp_state(e, dark);
  VehicleLightsLabel out;
  size_t next_setting = 0;  // light_settings are in VehicleLight order
  for (size_t i = 0; i < engine::kVehicleLightTypes; ++i) {
    const auto light = static_cast<engine::VehicleLight>(i);
    const uint32_t bit = engine::light_bit(light);
    LightLabel l;
    l.light = light;
    l.lit = (state.lit & bit) != 0;
    l.mode = (state.flashing & bit) != 0 ? engine::LightMode::kFlashing
             : l.lit                     ? engine::LightMode::kOn
                                         : engine::LightMode::kOff;
    while (next_setting < e.light_settings.size() && e.light_settings[next_setting].light < light) {
      ++next_setting;
    }
    if (next_setting < e.light_settings.size() && e.light_settings[next_setting].light == light) {
      const engine::LightSettingView& s = e.light_settings[next_setting];
      l.set = true;
      l.mode = s.mode;  // a light fading out is lit with its mode already off
      l.intensity_cd = s.candela;
      l.rgb = s.rgb;
    }
    if (l.set || l.lit || l.mode != engine::LightMode::kOff) {
      out.lights.push_back(l);
    }
  }
  uint32_t shape_roles = 0;
  if (inst.shape != nullptr) {
    for (const detail::LampPatch& lamp : inst.shape->lamps) {
      shape_roles |= 1u << static_cast<unsigned>(lamp.role);
    }
  }
  out.lamps = state.roles & shape_roles;
  return out;
}

/// The static objects labelled like entities (those with their own box: parked vehicles),
/// marked by instance id - kStaticInstanceBase.
std::vector<bool> boxed_objects(const detail::SceneData& d) {
  std::vector<bool> boxed;
  for (const auto& [id, record] : d.objects) {
    if (record.alone != nullptr && id >= kStaticInstanceBase) {
      const size_t k = id - kStaticInstanceBase;
      boxed.resize(std::max(boxed.size(), k + 1), false);
      boxed[k] = true;
    }
  }
  return boxed;
}

/// The label of a static object with its own box (a parked vehicle) before the sensor's own
/// measures. Its track id is its instance id: the same over the run, never an entity's.
ObjectLabel boxed_object_label(uint32_t id, const detail::SceneData::ObjectRecord& record,
                               const Rigid& sensor_from_world) {
  ObjectLabel l;
  l.instance_id = id;
  l.track_id = id;
  l.semantic = record.info.semantic.value_or(SemanticClass::kStatic);
  l.parked = record.info.kind == "parked_vehicle";
  l.type = record.info.type;
  l.box_world = *record.info.box;
  l.box_sensor = transform_box(sensor_from_world, l.box_world);
  l.distance = norm(l.box_sensor.center);
  return l;
}

/// A camera's measures of a label whose sensor box is set, from its pixels `s`: the projected
/// box clipped to the image, its truncation, the visible box and pixels. False when the
/// projected box is behind the camera or outside the image.
bool measure_in_image(const CameraModel& camera, const PixelStats& s, ObjectLabel& l) {
  const int w = camera.width();
  const int h = camera.height();
  l.visible_pixels = s.count;
  l.box_2d_visible = {static_cast<double>(s.x_min), static_cast<double>(s.y_min),
                      static_cast<double>(s.x_max), static_cast<double>(s.y_max)};
  Box2 full;
  if (!project_box_into(camera, l.box_sensor, full)) {
    return false;
  }
  const Box2 clipped{std::max(full.x_min, -0.5), std::max(full.y_min, -0.5),
                     std::min(full.x_max, w - 0.5), std::min(full.y_max, h - 0.5)};
  if (clipped.x_min > clipped.x_max || clipped.y_min > clipped.y_max) {
    return false;
  }
  l.box_2d = clipped;
  l.truncation = full.area() > 0.0 ? std::clamp(1.0 - clipped.area() / full.area(), 0.0, 1.0) : 0.0;
  return true;
}

}  // namespace

std::vector<ObjectLabel> camera_labels(const Scene& scene, const CameraRenderer& renderer,
                                       const Rigid& world_from_body,
                                       std::span<const uint32_t> instance, uint32_t carrier,
                                       const Lighting* lighting) {
  const detail::SceneData& d = scene.data();
  const CameraModel& camera = renderer.model();
  const bool dark = lighting != nullptr && lighting->headlights;
  const int w = camera.width();
  const Rigid world_from_cam = world_from_optical(world_from_body);
  const Rigid cam_from_world = world_from_cam.inverse();
  const auto stats = pixel_stats(instance, w, boxed_objects(d));
  std::vector<ObjectLabel> labels;
  for (const auto& inst : d.instances) {
    const auto it = stats.find(inst.instance_id);
    if (it == stats.end() || inst.instance_id == carrier) {
      continue;
    }
    ObjectLabel l = entity_label(d, inst, cam_from_world);
    if (!measure_in_image(camera, it->second, l)) {
      continue;
    }
    l.occlusion = occlusion_of(inst.shape->scene, inst.world_from_entity.inverse(),
                               inst.instance_id, renderer, world_from_cam, l.box_2d, instance, w);
    if (const engine::EntitySnapshot& e = d.entities[inst.snapshot_index];
        has_vehicle_lights(e.category)) {
      l.lights = vehicle_lights_label(e, inst, dark);
    }
    labels.push_back(std::move(l));
  }
  // Parked vehicles after the entities, by instance id; their triangles are in the tracer frame.
  const Rigid tracer_from_world =
      rigid_from_pose(-d.options.origin.x, -d.options.origin.y, -d.options.origin.z, 0, 0, 0);
  for (const auto& [id, s] : stats) {
    if (id < kStaticInstanceBase) {
      continue;
    }
    const auto& record = d.objects.at(id);
    ObjectLabel l = boxed_object_label(id, record, cam_from_world);
    if (!measure_in_image(camera, s, l)) {
      continue;
    }
    l.occlusion = occlusion_of(record.alone, tracer_from_world, id, renderer, world_from_cam,
                               l.box_2d, instance, w);
    labels.push_back(std::move(l));
  }
  return labels;
}

std::vector<StaticObjectLabel> static_object_labels(const Scene& scene,
                                                    std::span<const uint32_t> instance, int width,
                                                    std::span<const uint8_t> semantic) {
  const detail::SceneData& d = scene.data();
  std::map<uint32_t, PixelStats> stats;
  std::map<uint32_t, std::map<uint8_t, uint64_t>> classes;
  for (size_t i = 0; i < instance.size(); ++i) {
    if (instance[i] < kStaticInstanceBase || d.objects.find(instance[i]) == d.objects.end()) {
      continue;
    }
    PixelStats& s = stats[instance[i]];
    const int x = static_cast<int>(i % width);
    const int y = static_cast<int>(i / width);
    ++s.count;
    s.x_min = std::min(s.x_min, x);
    s.x_max = std::max(s.x_max, x);
    s.y_min = std::min(s.y_min, y);
    s.y_max = std::max(s.y_max, y);
    if (!semantic.empty()) {
      ++classes[instance[i]][semantic[i]];
    }
  }
  std::vector<StaticObjectLabel> out;
  for (const auto& [id, s] : stats) {
    const auto& record = d.objects.at(id);
    StaticObjectLabel l;
    l.instance_id = id;
    l.info = record.info;
    if (record.signal >= 0) {
      l.state = d.signal_states[record.signal];
    }
    if (record.info.box) {
      l.box_world = *record.info.box;
    } else {
      l.box_world.center = (record.bounds.min + record.bounds.max) * 0.5;
      l.box_world.length = record.bounds.max.x - record.bounds.min.x;
      l.box_world.width = record.bounds.max.y - record.bounds.min.y;
      l.box_world.height = record.bounds.max.z - record.bounds.min.z;
    }
    l.box_2d_visible = {static_cast<double>(s.x_min), static_cast<double>(s.y_min),
                        static_cast<double>(s.x_max), static_cast<double>(s.y_max)};
    l.visible_pixels = s.count;
    if (record.info.semantic) {
      l.semantic = *record.info.semantic;  // known from what it is, not from its pixels
      out.push_back(std::move(l));
      continue;
    }
    uint64_t most = 0;
    for (const auto& [c, n] : classes[id]) {
      if (n > most) {
        most = n;
        l.semantic = static_cast<SemanticClass>(c);
      }
    }
    out.push_back(std::move(l));
  }
  return out;
}

std::vector<ObjectLabel> lidar_labels(const Scene& scene, const Rigid& world_from_sensor,
                                      const PointCloud& cloud, double range_m, uint32_t carrier) {
  const detail::SceneData& d = scene.data();
  const Rigid sensor_from_world = world_from_sensor.inverse();
  std::map<uint32_t, uint64_t> counts;
  for (const auto& p : cloud.points) {
    if (p.instance_id != 0) {
      ++counts[p.instance_id];
    }
  }
  std::vector<ObjectLabel> labels;
  for (const auto& inst : d.instances) {
    if (inst.instance_id == carrier) {
      continue;
    }
    ObjectLabel l = entity_label(d, inst, sensor_from_world);
    if (l.distance > range_m) {
      continue;
    }
    const auto it = counts.find(inst.instance_id);
    l.lidar_points = it == counts.end() ? 0 : it->second;
    labels.push_back(std::move(l));
  }
  // Parked vehicles after the entities, by instance id.
  for (const auto& [id, record] : d.objects) {
    if (record.alone == nullptr) {
      continue;
    }
    ObjectLabel l = boxed_object_label(id, record, sensor_from_world);
    if (l.distance > range_m) {
      continue;
    }
    const auto it = counts.find(id);
    l.lidar_points = it == counts.end() ? 0 : it->second;
    labels.push_back(std::move(l));
  }
  return labels;
}

}  // namespace corsa::sensors
