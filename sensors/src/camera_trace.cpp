// Stage 1 of a camera pass: primary rays through the pixel centres (4x4 packets) give depth,
// class and instance; for RGB each hit is shaded into its terms, and its secondary rays
// (camera_rays.cpp) give its visibilities and the light its mirror and glass rays find.

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>

#include "camera_tile.h"

namespace corsa::sensors::detail {
namespace {

constexpr int kTile = 4;
constexpr float kInfinity = std::numeric_limits<float>::infinity();

/// Image motion of a surface point over 2 kMotionHalf seconds. The pinhole projection is used
/// without the lens distortion: over a blur of a few pixels the difference is far below one.
void store_motion(const Pass& p, size_t px, Vec3 p_world, int pool) {
  Vec3 v;
  if (pool >= 0) {
    const SceneData& d = *p.scene;
    const engine::EntitySnapshot& e = d.entities[d.instances[pool].snapshot_index];
    const Vec3 r = p_world - Vec3{e.pose.x, e.pose.y, e.pose.z};
    v = Vec3{e.vx, e.vy, e.vz} + Vec3{-e.yaw_rate * r.y, e.yaw_rate * r.x, 0.0};
  }
  const Vec3 a = p.cam_early.apply(p_world - v * kMotionHalf);
  const Vec3 b = p.cam_late.apply(p_world + v * kMotionHalf);
  if (a.z <= 1e-3 || b.z <= 1e-3) {
    return;
  }
  float* m = &(*p.motion_vectors)[2 * px];
  m[0] = static_cast<float>(p.model->fx() * (b.x / b.z - a.x / a.z));
  m[1] = static_cast<float>(p.model->fy() * (b.y / b.z - a.y / a.z));
}

/// The primary rays of the 4x4 tile at (col0, row0) as one packet (pixels outside the image
/// masked off): from the camera, past the carrying vehicle.
void primary_packet(const Pass& p, int col0, int row0, TileState& t, RTCRayHit16& rh, int* valid) {
  for (int k = 0; k < 16; ++k) {
    const int col = col0 + k % kTile;
    const int row = row0 + k / kTile;
    valid[k] = col < p.width && row < p.height ? -1 : 0;
    t.pixel[k] = valid[k] ? static_cast<size_t>(row) * p.width + col : 0;
    const float* r = p.rays + 3 * t.pixel[k];
    const auto& m = p.rotation;
    const Vec3 dir{m[0][0] * r[0] + m[0][1] * r[1] + m[0][2] * r[2],
                   m[1][0] * r[0] + m[1][1] * r[1] + m[1][2] * r[2],
                   m[2][0] * r[0] + m[2][1] * r[1] + m[2][2] * r[2]};
    t.dir[k] = dir;
    rh.ray.org_x[k] = static_cast<float>(p.origin_local.x);
    rh.ray.org_y[k] = static_cast<float>(p.origin_local.y);
    rh.ray.org_z[k] = static_cast<float>(p.origin_local.z);
    rh.ray.dir_x[k] = static_cast<float>(dir.x);
    rh.ray.dir_y[k] = static_cast<float>(dir.y);
    rh.ray.dir_z[k] = static_cast<float>(dir.z);
    rh.ray.tnear[k] = p.carrier.exit(dir);
    rh.ray.tfar[k] = kInfinity;
    rh.ray.mask[k] = 0xFFFFFFFFu;
    rh.ray.flags[k] = 0;
    rh.ray.time[k] = 0.0f;
    rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
  }
}

/// Instance id, class and depth (along the optical axis) of pixel `px` from its primary ray
/// (lane k of the packet); returns the label.
SceneData::Label store_labels(const Pass& p, const RTCRayHit16& rh, int k, size_t px) {
  const bool hit = rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
  const auto label = hit ? p.scene->label(rh.hit.instID[0][k], rh.hit.geomID[k], rh.hit.primID[k])
                         : SceneData::Label{SemanticClass::kSky, 0, -1};
  p.out->instance[px] = label.instance_id;
  if (!p.out->semantic.empty()) {
    p.out->semantic[px] = static_cast<uint8_t>(label.semantic);
  }
  if (!p.out->depth.empty()) {
    const double z = hit ? static_cast<double>(rh.ray.tfar[k]) * p.rays[3 * px + 2] : 0.0;
    p.out->depth[px] = hit && z <= p.settings->max_depth_m ? static_cast<float>(z) : 0.0f;
  }
  return label;
}

/// Radiance into 3 floats of pixel `px`, as composite() stores it.
void store_radiance(float* linear, size_t px, Color c) {
  float* out = linear + 3 * px;
  out[0] = static_cast<float>(c.r);
  out[1] = static_cast<float>(c.g);
  out[2] = static_cast<float>(c.b);
}

/// The sky seen by pixel `px` along `dir`: its whole record (every field: the buffers are kept
/// from frame to frame) and unit visibilities, or its radiance when the pass composites at once.
void store_sky(const Pass& p, size_t px, Vec3 dir) {
  const Color sky = sky_seen(*p.shading, p.origin_local, dir);
  if (p.direct != nullptr) {
    p.distances[px] = kInfinity;
    store_radiance(p.direct, px, sky);
    return;
  }
  PixelGeometry& g = (*p.geometry)[px];
  g = PixelGeometry{};
  g.distance = kInfinity;
  PixelRecord& rec = (*p.records)[px];
  rec = PixelRecord{};
  rec.terms.base = sky;
  (*p.visibility)[px] = PixelVisibility{};
}

/// A pixel's visibilities in the single precision the per-pixel buffers keep.
PixelVisibility visibility_as_stored(const Visibility& e) {
  PixelVisibility v;
  v.sun = static_cast<float>(e.sun);
  v.sky[0] = static_cast<float>(e.sky.r);
  v.sky[1] = static_cast<float>(e.sky.g);
  v.sky[2] = static_cast<float>(e.sky.b);
  v.lights = static_cast<float>(e.lights);
  return v;
}

ShadeTerms tile_pixel_terms(const Pass& p, const TileState& t, int k) {
  return shade_terms(*p.shading, t.surface[k], t.has_mirrored[k] ? &t.mirrored[k] : nullptr,
                     t.has_behind[k] ? &t.behind[k] : nullptr);
}

/// The record (surface, shading terms, mirrored and transmitted light) and the visibilities of
/// lit pixel k of a resolved tile, for the later stages.
void store_lit(const Pass& p, const TileState& t, int k) {
  const SurfacePoint& sp = t.surface[k];
  PixelGeometry& g = (*p.geometry)[t.pixel[k]];
  g.position[0] = static_cast<float>(sp.position.x);
  g.position[1] = static_cast<float>(sp.position.y);
  g.position[2] = static_cast<float>(sp.position.z);
  g.normal[0] = static_cast<float>(sp.normal.x);
  g.normal[1] = static_cast<float>(sp.normal.y);
  g.normal[2] = static_cast<float>(sp.normal.z);
  g.distance = static_cast<float>(sp.distance);
  g.surface_id = sp.surface_id;
  PixelRecord& rec = (*p.records)[t.pixel[k]];
  rec.has_mirrored = t.has_mirrored[k];
  rec.has_behind = t.has_behind[k];
  rec.mirrored = Color3f(t.mirrored[k]);
  rec.behind = Color3f(t.behind[k]);
  rec.terms = tile_pixel_terms(p, t, k);
  (*p.visibility)[t.pixel[k]] = visibility_as_stored(t.vis[k]);
}

/// The lit pixels of a resolved tile composited at once (Pass::direct): composite_pixel()'s
/// terms times visibilities, then the air in front of them for the whole tile in one call (its
/// exponentials two pixels at a time: Lighting::transmittances).
void composite_lit(const Pass& p, const TileState& t, const int* valid) {
  const ShadingContext& c = *p.shading;
  ShadeTerms terms[16];
  int lit[16];
  double dir_z[16], distance[16], kept[16];
  int n = 0;
  for (int k = 0; k < 16; ++k) {
    if (!valid[k] || !t.hit[k]) {
      continue;
    }
    // Rounded to single precision as the buffers of the other presets keep them.
    const float d = static_cast<float>(t.surface[k].distance);
    p.distances[t.pixel[k]] = d;
    // All the tile's terms before any is read (as the hits in trace_tile).
    new (&terms[n]) ShadeTerms(tile_pixel_terms(p, t, k));
    dir_z[n] = centre_ray(p, t.pixel[k]).z;
    distance[n] = d;
    lit[n] = k;
    ++n;
  }
  c.lighting->transmittances(c.eye_air, dir_z, distance, n, kept);
  const Color fog = c.lighting->fog_color;
  for (int i = 0; i < n; ++i) {
    const Color seen = combine(terms[i], visibility_as_stored(t.vis[lit[i]]).get());
    store_radiance(p.direct, t.pixel[lit[i]], seen * kept[i] + fog * (1.0 - kept[i]));
  }
}

}  // namespace

SurfaceHit primary_hit(const Pass& p, const RTCRayHit16& rh, int k, Vec3 dir,
                       const SceneData::Label& label) {
  const unsigned inst_id = rh.hit.instID[0][k];
  const double distance = rh.ray.tfar[k];
  const Vec3 n = p.scene->world_normal(inst_id, {rh.hit.Ng_x[k], rh.hit.Ng_y[k], rh.hit.Ng_z[k]});
  // Every field given at once: assigned one by one, the hit was first cleared with a string
  // store in the caller's return slot (a third of this function's time).
  return SurfaceHit{.inst_id = inst_id,
                    .geom_id = rh.hit.geomID[k],
                    .prim_id = rh.hit.primID[k],
                    .u = rh.hit.u[k],
                    .v = rh.hit.v[k],
                    .position = p.origin_local + dir * distance,
                    .normal = dot(n, dir) > 0.0 ? -n : n,
                    .view_dir = dir,
                    .distance = distance,
                    .semantic = label.semantic,
                    .entity = label.entity};
}

Vec3 ray_at(const Pass& p, double x, double y) {
  const int w = p.width;
  const int h = p.height;
  const double cx = std::clamp(x, 0.0, w - 1.0);
  const double cy = std::clamp(y, 0.0, h - 1.0);
  const int x0 = std::min(static_cast<int>(cx), w - 2 < 0 ? 0 : w - 2);
  const int y0 = std::min(static_cast<int>(cy), h - 2 < 0 ? 0 : h - 2);
  const int x1 = std::min(x0 + 1, w - 1);
  const int y1 = std::min(y0 + 1, h - 1);
  // Outside the image (half a pixel at the border) the ray is extrapolated linearly.
  const double fx = x - x0;
  const double fy = y - y0;
  auto at = [&](int c, int r) {
    const float* v = p.rays + 3 * (static_cast<size_t>(r) * w + c);
    return Vec3{v[0], v[1], v[2]};
  };
  const Vec3 top = at(x0, y0) * (1.0 - fx) + at(x1, y0) * fx;
  const Vec3 bottom = at(x0, y1) * (1.0 - fx) + at(x1, y1) * fx;
  const Vec3 local = normalized(top * (1.0 - fy) + bottom * fy);
  const auto& m = p.rotation;
  return {m[0][0] * local.x + m[0][1] * local.y + m[0][2] * local.z,
          m[1][0] * local.x + m[1][1] * local.y + m[1][2] * local.z,
          m[2][0] * local.x + m[2][1] * local.y + m[2][2] * local.z};
}

void trace_tile(const Pass& p, int col0, int row0, TileScratch& scratch) {
  alignas(64) RTCRayHit16 rh;
  alignas(64) int valid[16];
  TileState t;
  t.count = 16;
  primary_packet(p, col0, row0, t, rh, valid);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  rtcIntersect16(valid, p.scene->top, &context, &rh);

  const bool rgb = p.settings->outputs.rgb;
  scratch.clear();
  // The tile's hits first, then their surfaces, then their rays: each result read right after
  // it was written stalled the load on the store buffer (wide loads of narrow stores). Results
  // are built in place (placement new of the returned value): assigned, they were returned
  // into a temporary and copied at once, a copy that stalled the same way.
  SurfaceHit hits[16];
  for (int k = 0; k < 16; ++k) {
    if (!valid[k]) {
      continue;
    }
    const SceneData::Label label = store_labels(p, rh, k, t.pixel[k]);
    if (!rgb) {
      continue;
    }
    if (rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) {
      store_sky(p, t.pixel[k], t.dir[k]);
      continue;
    }
    new (&hits[k]) SurfaceHit(primary_hit(p, rh, k, t.dir[k], label));
    t.hit[k] = true;
  }
  if (!rgb) {
    return;
  }
  for (int k = 0; k < 16; ++k) {
    if (!t.hit[k]) {
      continue;
    }
    new (&t.surface[k]) SurfacePoint(surface_at(*p.shading, hits[k]));
  }
  for (int k = 0; k < 16; ++k) {
    if (!t.hit[k]) {
      continue;
    }
    queue_rays(p, t, k, scratch);
    if (p.motion) {
      store_motion(p, t.pixel[k], p.scene->to_map(hits[k].position), hits[k].entity);
    }
  }
  resolve_rays(p, t, scratch);
  if (p.direct != nullptr) {
    composite_lit(p, t, valid);
    return;
  }
  for (int k = 0; k < 16; ++k) {
    if (valid[k] && t.hit[k]) {
      store_lit(p, t, k);
    }
  }
}

}  // namespace corsa::sensors::detail
