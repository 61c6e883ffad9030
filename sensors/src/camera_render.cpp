#include "corsa/sensors/camera_render.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

#include "carrier.h"
#include "scene_data.h"
#include "shading.h"

namespace corsa::sensors {
namespace {

constexpr int kTile = 4;  // 4x4 pixels = one 16-ray packet

/// Camera pose at a time offset dt (s) from the capture, for motion blur.
Rigid camera_at(const CameraMotion& m, const Rigid& world_from_cam, double dt) {
  const Rigid spin = rigid_from_pose(0, 0, 0, m.yaw_rate * dt, 0, 0);
  Rigid moved;
  moved.rotation = spin.rotation * world_from_cam.rotation;
  moved.translation =
      m.pivot + m.velocity * dt + spin.rotation * (world_from_cam.translation - m.pivot);
  return moved;
}

struct Pass {
  const detail::SceneData* scene;
  const CameraModel* model;
  const float* rays;
  const RenderSettings* settings;
  const detail::ShadingContext* shading;
  Rigid world_from_cam;       // optical frame to map
  float rotation[3][3];       // its rotation in single precision, for the rays
  Rigid cam_early, cam_late;  // inverse poses at -shutter/2 and +shutter/2 (blur)
  bool blur;
  Vec3 origin_local;
  detail::CarrierExit carrier;
  CameraImages* out;
  std::vector<float>* linear;
  std::vector<float>* motion;
};

Vec3 point_velocity(const detail::SceneData& d, int pool, Vec3 p_world) {
  if (pool < 0) {
    return {};
  }
  const engine::EntitySnapshot& e = d.entities[d.instances[pool].snapshot_index];
  const Vec3 r = p_world - Vec3{e.pose.x, e.pose.y, e.pose.z};
  return Vec3{e.vx, e.vy, e.vz} + Vec3{-e.yaw_rate * r.y, e.yaw_rate * r.x, 0.0};
}

/// Image motion of a surface point over the exposure. The pinhole projection is used without
/// the lens distortion: over a blur of a few pixels the difference is far below a pixel.
void store_motion(const Pass& p, size_t px, Vec3 p_world, int pool) {
  const double half = 0.5 * p.settings->rgb.shutter_speed_s;
  const Vec3 v = point_velocity(*p.scene, pool, p_world);
  const Vec3 a = p.cam_early.apply(p_world - v * half);
  const Vec3 b = p.cam_late.apply(p_world + v * half);
  if (a.z <= 1e-3 || b.z <= 1e-3) {
    return;
  }
  float* m = &(*p.motion)[2 * px];
  m[0] = static_cast<float>(p.model->fx() * (b.x / b.z - a.x / a.z));
  m[1] = static_cast<float>(p.model->fy() * (b.y / b.z - a.y / a.z));
}

void trace_tile(const Pass& p, int col0, int row0) {
  const int w = p.out->width;
  const int h = p.out->height;
  const detail::SceneData& d = *p.scene;
  const Lighting* l = p.settings->lighting;
  const bool rgb = p.settings->outputs.rgb;
  alignas(64) RTCRayHit16 rh;
  alignas(64) int valid[16];
  size_t pixel[16];
  for (int k = 0; k < 16; ++k) {
    const int col = col0 + k % kTile;
    const int row = row0 + k / kTile;
    valid[k] = col < w && row < h ? -1 : 0;
    pixel[k] = valid[k] ? static_cast<size_t>(row) * w + col : 0;
    const float* r = p.rays + 3 * pixel[k];
    const auto& m = p.rotation;
    const Vec3 dir{m[0][0] * r[0] + m[0][1] * r[1] + m[0][2] * r[2],
                   m[1][0] * r[0] + m[1][1] * r[1] + m[1][2] * r[2],
                   m[2][0] * r[0] + m[2][1] * r[1] + m[2][2] * r[2]};
    rh.ray.org_x[k] = static_cast<float>(p.origin_local.x);
    rh.ray.org_y[k] = static_cast<float>(p.origin_local.y);
    rh.ray.org_z[k] = static_cast<float>(p.origin_local.z);
    rh.ray.dir_x[k] = static_cast<float>(dir.x);
    rh.ray.dir_y[k] = static_cast<float>(dir.y);
    rh.ray.dir_z[k] = static_cast<float>(dir.z);
    rh.ray.tnear[k] = p.carrier.exit(dir);
    rh.ray.tfar[k] = std::numeric_limits<float>::infinity();
    rh.ray.mask[k] = 0xFFFFFFFFu;
    rh.ray.flags[k] = 0;
    rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  rtcIntersect16(valid, d.top, &context, &rh);

  alignas(64) RTCRay16 shadow;
  alignas(64) int shadow_valid[16];
  for (int k = 0; k < 16; ++k) {
    shadow.tnear[k] = 0.0f;
    shadow.tfar[k] = 0.0f;
    shadow.mask[k] = 0xFFFFFFFFu;
    shadow.flags[k] = 0;
    shadow.org_x[k] = shadow.org_y[k] = shadow.org_z[k] = 0.0f;
    shadow.dir_x[k] = shadow.dir_y[k] = 0.0f;
    shadow.dir_z[k] = 1.0f;
  }
  Vec3 normal[16];
  Vec3 position[16];
  detail::SceneData::Label label[16];
  for (int k = 0; k < 16; ++k) {
    shadow_valid[k] = 0;
    if (!valid[k]) {
      continue;
    }
    const size_t px = pixel[k];
    const bool hit = rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
    const float* r = p.rays + 3 * px;
    const double t = rh.ray.tfar[k];
    const double z = hit ? t * r[2] : 0.0;
    const bool in_range = hit && z <= p.settings->max_depth_m;
    label[k] = hit ? d.label(rh.hit.instID[0][k], rh.hit.geomID[k], rh.hit.primID[k])
                   : detail::SceneData::Label{SemanticClass::kSky, 0, -1};
    p.out->instance[px] = label[k].instance_id;
    if (!p.out->semantic.empty()) {
      p.out->semantic[px] = static_cast<uint8_t>(label[k].semantic);
    }
    if (!p.out->depth.empty()) {
      p.out->depth[px] = in_range ? static_cast<float>(z) : 0.0f;
    }
    if (!rgb || !hit) {
      continue;
    }
    const Vec3 dir{rh.ray.dir_x[k], rh.ray.dir_y[k], rh.ray.dir_z[k]};
    Vec3 n = d.world_normal(rh.hit.instID[0][k], {rh.hit.Ng_x[k], rh.hit.Ng_y[k], rh.hit.Ng_z[k]});
    if (dot(n, dir) > 0.0) {
      n = -n;
    }
    normal[k] = n;
    position[k] = p.origin_local + dir * t;
    if (l->sun_elevation > 0.0 && dot(n, l->sun_direction) > 0.0) {
      const Vec3 o = position[k] + n * (0.01 + 1e-4 * t);
      shadow_valid[k] = -1;
      shadow.org_x[k] = static_cast<float>(o.x);
      shadow.org_y[k] = static_cast<float>(o.y);
      shadow.org_z[k] = static_cast<float>(o.z);
      shadow.dir_x[k] = static_cast<float>(l->sun_direction.x);
      shadow.dir_y[k] = static_cast<float>(l->sun_direction.y);
      shadow.dir_z[k] = static_cast<float>(l->sun_direction.z);
      shadow.tnear[k] = 0.0f;
      shadow.tfar[k] = std::numeric_limits<float>::infinity();
      shadow.mask[k] = 0xFFFFFFFFu;
      shadow.flags[k] = 0;
    }
    if (p.blur) {
      store_motion(p, px, d.to_map(position[k]), label[k].entity);
    }
  }
  if (!rgb) {
    return;
  }
  RTCIntersectContext shadow_context;
  rtcInitIntersectContext(&shadow_context);
  rtcOccluded16(shadow_valid, d.top, &shadow_context, &shadow);
  for (int k = 0; k < 16; ++k) {
    if (!valid[k]) {
      continue;
    }
    const Vec3 dir{rh.ray.dir_x[k], rh.ray.dir_y[k], rh.ray.dir_z[k]};
    Color c;
    if (rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) {
      c = detail::apply_fog(*l, l->sky(dir), std::numeric_limits<double>::infinity());
    } else {
      const bool sunlit = shadow_valid[k] != 0 && shadow.tfar[k] >= 0.0f;
      detail::SurfaceHit hit;
      hit.inst_id = rh.hit.instID[0][k];
      hit.geom_id = rh.hit.geomID[k];
      hit.prim_id = rh.hit.primID[k];
      hit.u = rh.hit.u[k];
      hit.v = rh.hit.v[k];
      hit.position = position[k];
      hit.normal = normal[k];
      hit.view_dir = dir;
      hit.distance = rh.ray.tfar[k];
      hit.semantic = label[k].semantic;
      hit.entity = label[k].entity;
      c = detail::shade_hit(*p.shading, hit, sunlit);
      c = detail::apply_fog(*l, c, rh.ray.tfar[k]);
    }
    float* out = &(*p.linear)[3 * pixel[k]];
    out[0] = static_cast<float>(c.r);
    out[1] = static_cast<float>(c.g);
    out[2] = static_cast<float>(c.b);
  }
}

}  // namespace

Rigid world_from_optical(const Rigid& world_from_body) {
  return world_from_body * optical_in_body();
}

CameraRenderer::CameraRenderer(const CameraIntrinsics& intrinsics) : model_(intrinsics) {
  const int w = intrinsics.width;
  const int h = intrinsics.height;
  rays_.resize(static_cast<size_t>(w) * h * 3);
  // Undistorting every pixel is iterative (~0.3 s for 1280x720): rows in parallel.
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    for (int row = rows.begin(); row != rows.end(); ++row) {
      for (int col = 0; col < w; ++col) {
        const Vec3 r = model_.ray({static_cast<double>(col), static_cast<double>(row)});
        float* out = &rays_[3 * (static_cast<size_t>(row) * w + col)];
        out[0] = static_cast<float>(r.x);
        out[1] = static_cast<float>(r.y);
        out[2] = static_cast<float>(r.z);
      }
    }
  });
}

Vec3 CameraRenderer::pixel_ray(int col, int row) const {
  const float* r = &rays_[3 * (static_cast<size_t>(row) * model_.width() + col)];
  return {r[0], r[1], r[2]};
}

CameraImages CameraRenderer::render(const Scene& scene, const CameraMotion& motion,
                                    const RenderSettings& settings) const {
  const int w = model_.width();
  const int h = model_.height();
  const size_t n = static_cast<size_t>(w) * h;
  CameraImages out;
  out.width = w;
  out.height = h;
  out.instance.assign(n, 0);
  if (settings.outputs.depth) {
    out.depth.assign(n, 0.0f);
  }
  if (settings.outputs.semantic) {
    out.semantic.assign(n, 0);
  }
  const bool rgb = settings.outputs.rgb && settings.lighting != nullptr;
  std::vector<float> linear;
  std::vector<float> blur_vectors;
  detail::ShadingContext shading;
  Pass p{};
  p.scene = &scene.data();
  p.model = &model_;
  p.rays = rays_.data();
  p.settings = &settings;
  p.world_from_cam = world_from_optical(motion.world_from_body);
  p.origin_local = scene.data().to_local(p.world_from_cam.translation);
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) {
      p.rotation[r][k] = static_cast<float>(p.world_from_cam.rotation.m[r][k]);
    }
  }
  p.carrier = detail::CarrierExit(settings.carrier, p.world_from_cam.translation);
  p.out = &out;
  if (rgb) {
    linear.assign(3 * n, 0.0f);
    shading = detail::make_shading_context(scene.data(), *settings.lighting, 1.0 / model_.fx());
    p.shading = &shading;
    p.linear = &linear;
    bool moving = norm(motion.velocity) > 0.0 || motion.yaw_rate != 0.0;
    for (const auto& e : scene.entities()) {
      moving = moving || e.vx != 0.0 || e.vy != 0.0 || e.vz != 0.0 || e.yaw_rate != 0.0;
    }
    p.blur = moving && settings.rgb.shutter_speed_s > 0.0;
    if (p.blur) {
      const double half = 0.5 * settings.rgb.shutter_speed_s;
      p.cam_early = camera_at(motion, p.world_from_cam, -half).inverse();
      p.cam_late = camera_at(motion, p.world_from_cam, half).inverse();
      blur_vectors.assign(2 * n, 0.0f);
      p.motion = &blur_vectors;
    }
  }
  RenderSettings effective = settings;
  effective.outputs.rgb = rgb;
  p.settings = &effective;
  const int tiles_x = (w + kTile - 1) / kTile;
  const int tiles_y = (h + kTile - 1) / kTile;
  tbb::parallel_for(tbb::blocked_range<int>(0, tiles_y), [&](const tbb::blocked_range<int>& r) {
    for (int ty = r.begin(); ty != r.end(); ++ty) {
      for (int tx = 0; tx < tiles_x; ++tx) {
        trace_tile(p, tx * kTile, ty * kTile);
      }
    }
  });
  if (rgb) {
    if (p.blur) {
      detail::motion_blur(linear, blur_vectors, w, h);
    }
    out.rgb = detail::develop(linear, w, h, settings.rgb, settings.frame_seed);
    detail::draw_rain(out.rgb, w, h, *settings.lighting, settings.frame_seed);
  }
  return out;
}

}  // namespace corsa::sensors
