// Stage 1 of a camera pass: primary rays through the pixel centres (4x4 packets) give depth,
// class and instance; for RGB each hit is shaded into its terms, and its visibilities are
// estimated with secondary rays traced in batches per tile: shadow rays to the sun (over the
// solar disc for soft shadows), cosine-distributed sky rays whose occluders return one diffuse
// bounce, shadow rays to lamps picked in proportion to their light, mirror rays on smooth
// surfaces and rays through glass. Every random number is a hash of (frame seed, pixel, use),
// so the bytes do not depend on the thread count.

#include <algorithm>
#include <cmath>
#include <limits>

#include "brdf.h"
#include "camera_frame.h"

namespace corsa::sensors::detail {
namespace {

constexpr int kTile = 4;
constexpr float kInfinity = std::numeric_limits<float>::infinity();
constexpr double kSkyRayLength = 80.0;  ///< m: beyond, occluders are part of the sky light

enum RayKind : int { kSky, kMirror, kGlass };

/// A ray from o along unit d up to tfar, written in place: built on the stack and copied into
/// the batch, the rays stalled the store buffer (narrow writes read back wide).
void set_ray(RTCRay& r, Vec3 o, Vec3 d, float tfar) {
  r.org_x = static_cast<float>(o.x);
  r.org_y = static_cast<float>(o.y);
  r.org_z = static_cast<float>(o.z);
  r.dir_x = static_cast<float>(d.x);
  r.dir_y = static_cast<float>(d.y);
  r.dir_z = static_cast<float>(d.z);
  r.tnear = 0.0f;
  r.tfar = tfar;
  r.mask = 0xFFFFFFFFu;
  r.time = 0.0f;
  r.id = 0;
  r.flags = 0;
}

/// The same for a ray whose hit is wanted.
void set_hit_ray(RTCRayHit& h, Vec3 o, Vec3 d, float tfar) {
  set_ray(h.ray, o, d, tfar);
  h.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  h.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

/// Lane k of a packet: a ray from o along unit d up to tfar.
void set_lane(RTCRay16& r, int k, Vec3 o, Vec3 d, float tfar) {
  r.org_x[k] = static_cast<float>(o.x);
  r.org_y[k] = static_cast<float>(o.y);
  r.org_z[k] = static_cast<float>(o.z);
  r.dir_x[k] = static_cast<float>(d.x);
  r.dir_y[k] = static_cast<float>(d.y);
  r.dir_z[k] = static_cast<float>(d.z);
  r.tnear[k] = 0.0f;
  r.tfar[k] = tfar;
  r.mask[k] = 0xFFFFFFFFu;
  r.time[k] = 0.0f;
  r.id[k] = 0;
  r.flags[k] = 0;
}

/// Traces the first `count` lanes of the packets (the sun rays of a tile: nearly parallel and
/// from neighbouring points, they share most of their way through the scene).
void occluded(const SceneData& d, std::vector<RTCRay16>& packets, int count) {
  for (int first = 0; first < count; first += 16) {
    alignas(64) int valid[16];
    for (int k = 0; k < 16; ++k) {
      valid[k] = first + k < count ? -1 : 0;
    }
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcOccluded16(valid, d.top, &context, &packets[first / 16]);
  }
}

void occluded(const SceneData& d, std::vector<RTCRay>& rays) {
  if (rays.empty()) {
    return;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcOccluded1M(d.top, &context, rays.data(), static_cast<unsigned>(rays.size()), sizeof(RTCRay));
}

void intersect(const SceneData& d, std::vector<RTCRayHit>& rays) {
  if (rays.empty()) {
    return;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect1M(d.top, &context, rays.data(), static_cast<unsigned>(rays.size()),
                 sizeof(RTCRayHit));
}

/// Where a secondary ray starts: off the surface, against self-intersection.
Vec3 offset(const SurfacePoint& s, Vec3 along) {
  const double eps = 0.01 + 1e-4 * s.distance;
  return s.position + (dot(along, s.normal) >= 0.0 ? s.normal : -s.normal) * eps;
}

/// The surface a secondary ray found, or nullopt for the sky.
std::optional<SurfacePoint> secondary_surface(const Pass& p, const RTCRayHit& h,
                                              double path_before) {
  if (h.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
    return std::nullopt;
  }
  const SceneData& d = *p.scene;
  SurfaceHit s;
  s.inst_id = h.hit.instID[0];
  s.geom_id = h.hit.geomID;
  s.prim_id = h.hit.primID;
  s.u = h.hit.u;
  s.v = h.hit.v;
  const Vec3 dir{h.ray.dir_x, h.ray.dir_y, h.ray.dir_z};
  s.view_dir = dir;
  s.position = Vec3{h.ray.org_x, h.ray.org_y, h.ray.org_z} + dir * h.ray.tfar;
  Vec3 n = d.world_normal(s.inst_id, {h.hit.Ng_x, h.hit.Ng_y, h.hit.Ng_z});
  s.normal = dot(n, dir) > 0.0 ? -n : n;
  s.distance = path_before + h.ray.tfar;
  const auto label = d.label(s.inst_id, s.geom_id, s.prim_id);
  s.semantic = label.semantic;
  s.entity = label.entity;
  // Secondary views are blurred by the curvature they come from: a coarser texture level.
  return surface_at(*p.shading, s, 2.0);
}

/// Radiance an occluding surface sends back along a sky ray: one diffuse bounce of sky and sun
/// light off its base colour (half the sun unless a shadow ray said otherwise).
Color bounce(const Pass& p, const RTCRayHit& h, double sun_share) {
  const SceneData& d = *p.scene;
  const Lighting& l = *p.shading->lighting;
  const Material& m = d.materials[d.material_of(h.hit.instID[0], h.hit.geomID, h.hit.primID)];
  const Vec3 dir{h.ray.dir_x, h.ray.dir_y, h.ray.dir_z};
  Vec3 n = d.world_normal(h.hit.instID[0], {h.hit.Ng_x, h.hit.Ng_y, h.hit.Ng_z});
  n = dot(n, dir) > 0.0 ? -n : n;
  Color light = l.sky_light(n) * 0.6;
  const double n_dot_l = dot(n, l.sun_direction);
  if (n_dot_l > 0.0) {
    light = light + l.sun * (n_dot_l * sun_share);
  }
  return m.base_color * (1.0 - m.metallic) * light;
}

/// Light weights of a surface point (luminance each near light adds) for picking shadow rays.
double light_weights(const ShadingContext& c, const SurfacePoint& s, std::vector<float>& w) {
  w.clear();
  double total = 0.0;
  for (const uint32_t k : c.lights.near(s.position)) {
    const LightSample ls = illuminate(c.lights.lights()[k], s.position);
    const double cos_l = dot(s.normal, ls.direction);
    const double v = cos_l > 0.0 ? luminance(ls.irradiance) * cos_l : 0.0;
    w.push_back(static_cast<float>(v));
    total += v;
  }
  return total;
}

struct TileState {
  int count = 0;
  size_t pixel[16] = {};
  bool hit[16] = {};
  Vec3 dir[16];
  SurfacePoint surface[16];
  Visibility vis[16];
  Color mirrored[16], behind[16];
  bool has_mirrored[16] = {}, has_behind[16] = {};
  int sun_rays[16] = {}, sun_free[16] = {};
  int light_rays[16] = {}, light_free[16] = {};
  Color sky_sum[16];
  int sky_rays[16] = {};
};

/// Queues the secondary rays of one hit pixel.
void queue_rays(const Pass& p, TileState& t, int k, TileScratch& s) {
  const ShadingContext& c = *p.shading;
  const QualitySettings& q = c.quality;
  const Lighting& l = *c.lighting;
  const SurfacePoint& sp = t.surface[k];
  const uint64_t key = pixel_key(p.settings->frame_seed, t.pixel[k], 0x5eed);
  auto shadow = [&](Vec3 o, Vec3 d, float tfar) {
    set_ray(s.rays.emplace_back(), o, d, tfar);
    s.ray_owner.push_back(k);
  };
  auto probe = [&](Vec3 o, Vec3 d, float tfar, int kind) {
    set_hit_ray(s.hits.emplace_back(), o, d, tfar);
    s.hit_owner.push_back(k);
    s.hit_kind.push_back(kind);
  };
  if (l.sun_elevation > -0.01 && luminance(l.sun) > 0.0 && dot(sp.normal, l.sun_direction) > 0.0) {
    const double r1 = hash_uniform(key, 0), r2 = hash_uniform(key, 1);
    for (int j = 0; j < q.sun_rays; ++j) {
      double u1 = 0.0, u2 = 0.0;
      r2_point(j, r1, r2, u1, u2);
      const Vec3 d = q.soft_sun ? cone_direction(l.sun_direction, l.sun_angular_radius, u1, u2)
                                : l.sun_direction;
      const size_t n = s.sun_owner.size();
      if (n / 16 >= s.sun.size()) {
        s.sun.emplace_back();
      }
      set_lane(s.sun[n / 16], static_cast<int>(n % 16), offset(sp, d), d, kInfinity);
      s.sun_owner.push_back(k);
      ++t.sun_rays[k];
    }
  }
  if (!c.lights.empty() && q.light_rays > 0) {
    const double total = light_weights(c, sp, s.weights);
    const auto near = c.lights.near(sp.position);
    const double r1 = hash_uniform(key, 20), r2 = hash_uniform(key, 21);
    for (int j = 0; j < q.light_rays && total > 0.0; ++j) {
      // A light picked in proportion to its weight: the visibility of the pick estimates the
      // weighted visibility of them all.
      double u = hash_uniform(key, 10 + j) * total;
      size_t pick = 0;
      while (pick + 1 < s.weights.size() && u >= s.weights[pick]) {
        u -= s.weights[pick];
        ++pick;
      }
      const Light& light = c.lights.lights()[near[pick]];
      double u1 = 0.0, u2 = 0.0;
      r2_point(j, r1, r2, u1, u2);
      const Vec3 target =
          light.position + Vec3{(u1 - 0.5) * light.radius, (u2 - 0.5) * light.radius, 0.0};
      const Vec3 o = offset(sp, target - sp.position);
      const Vec3 to = target - o;
      const double dist = norm(to);
      // The ray stops short of the lamp: nothing stands in front of a lens within 0.3 m, but
      // the lamp's own housing, bumper or visor there would shadow the light it sends out.
      const double clear = std::min(0.3, 0.5 * dist);
      if (dist - clear <= 0.01) {
        continue;
      }
      shadow(o, to * (1.0 / dist), static_cast<float>(dist - clear));
      ++t.light_rays[k];
    }
  }
  const double r1 = hash_uniform(key, 30), r2 = hash_uniform(key, 31);
  for (int j = 0; j < q.sky_rays; ++j) {
    double u1 = 0.0, u2 = 0.0;
    r2_point(j, r1, r2, u1, u2);
    const Vec3 d = cosine_direction(sp.normal, u1, u2);
    probe(offset(sp, d), d, static_cast<float>(kSkyRayLength), kSky);
    ++t.sky_rays[k];
  }
  if (sp.mirror) {
    const Vec3 r = reflect(sp.view_dir, sp.normal);
    probe(offset(sp, r), r, kInfinity, kMirror);
  }
  if (sp.transmission > 0.0 && p.shading->quality.transmission) {
    // Through thin glass without refraction; past a second pane of the same glass (the far
    // side of a car) once more.
    probe(offset(sp, sp.view_dir), sp.view_dir, kInfinity, kGlass);
  }
}

/// Traces a tile's shadow rays and probe rays, and counts each pixel's unoccluded sun and lamp
/// rays.
void trace_queued(const Pass& p, TileState& t, TileScratch& s) {
  const SceneData& d = *p.scene;
  const int suns = static_cast<int>(s.sun_owner.size());
  occluded(d, s.sun, suns);
  occluded(d, s.rays);
  intersect(d, s.hits);
  // Embree sets tfar to -inf when a ray is occluded.
  for (int i = 0; i < suns; ++i) {
    t.sun_free[s.sun_owner[i]] += s.sun[i / 16].tfar[i % 16] >= 0.0f ? 1 : 0;
  }
  for (size_t i = 0; i < s.rays.size(); ++i) {
    t.light_free[s.ray_owner[i]] += s.rays[i].tfar >= 0.0f ? 1 : 0;
  }
}

/// The surfaces the mirror and glass rays found (glass seen through glass is passed once more),
/// and shadow rays towards the sun from them (when quality asks for it) and from the occluders
/// the sky rays hit (when quality asks for the bounce's shadow); then traces those.
void find_secondary(const Pass& p, const TileState& t, TileScratch& s) {
  const ShadingContext& c = *p.shading;
  const Lighting& l = *c.lighting;
  const SceneData& d = *p.scene;
  s.found.assign(s.hits.size(), std::nullopt);
  s.second.clear();
  s.second_owner.clear();
  const bool shadows = c.quality.reflections;
  for (size_t i = 0; i < s.hits.size(); ++i) {
    RTCRayHit& h = s.hits[i];
    const int k = s.hit_owner[i];
    if (s.hit_kind[i] == kSky) {
      if (h.hit.geomID != RTC_INVALID_GEOMETRY_ID && c.quality.bounce_shadow) {
        const Vec3 o = Vec3{h.ray.org_x, h.ray.org_y, h.ray.org_z} +
                       Vec3{h.ray.dir_x, h.ray.dir_y, h.ray.dir_z} * (h.ray.tfar * 0.999);
        set_ray(s.second.emplace_back(), o, l.sun_direction, kInfinity);
        s.second_owner.push_back(static_cast<int>(i));
      }
      continue;
    }
    std::optional<SurfacePoint>& found = s.found[i];
    found = secondary_surface(p, h, t.surface[k].distance);
    if (found && s.hit_kind[i] == kGlass && found->transmission > 0.0) {
      set_hit_ray(h, offset(*found, found->view_dir), found->view_dir, kInfinity);
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      rtcIntersect1(d.top, &context, &h);
      found = secondary_surface(p, h, found->distance);
    }
    if (found && shadows && dot(found->normal, l.sun_direction) > 0.0 && luminance(l.sun) > 0.0) {
      set_ray(s.second.emplace_back(), offset(*found, l.sun_direction), l.sun_direction, kInfinity);
      s.second_owner.push_back(static_cast<int>(i));
    }
  }
  occluded(d, s.second);
  s.sun_seen.assign(s.hits.size(), -1);
  for (size_t j = 0; j < s.second.size(); ++j) {
    s.sun_seen[s.second_owner[j]] = s.second[j].tfar >= 0.0f ? 1 : 0;
  }
}

/// What the probe rays bring back: sky rays the sky radiance or the bounce off the occluder they
/// hit (summed per pixel), mirror and glass rays the radiance of what they found.
void gather_probes(const Pass& p, TileState& t, const TileScratch& s) {
  const ShadingContext& c = *p.shading;
  const Lighting& l = *c.lighting;
  const bool shadows = c.quality.reflections;
  for (size_t i = 0; i < s.hits.size(); ++i) {
    const RTCRayHit& h = s.hits[i];
    const int k = s.hit_owner[i];
    const Vec3 o{h.ray.org_x, h.ray.org_y, h.ray.org_z};
    const Vec3 dir{h.ray.dir_x, h.ray.dir_y, h.ray.dir_z};
    const int sun_seen = s.sun_seen[i];  // -1: no shadow ray, 0 shadowed, 1 lit
    if (s.hit_kind[i] == kSky) {
      const bool escaped = h.hit.geomID == RTC_INVALID_GEOMETRY_ID;
      const double sun_share = sun_seen >= 0 ? sun_seen : 0.5;
      t.sky_sum[k] = t.sky_sum[k] + (escaped ? l.sky_model.radiance(dir) : bounce(p, h, sun_share));
      continue;
    }
    Color radiance;
    if (!s.found[i]) {
      radiance = sky_seen(c, o, dir);
    } else {
      const bool lit = sun_seen >= 0 ? sun_seen == 1 : !shadows;
      radiance = through_air(c, shade_secondary(c, *s.found[i], lit), o, dir, h.ray.tfar);
    }
    if (s.hit_kind[i] == kMirror) {
      t.mirrored[k] = radiance;
      t.has_mirrored[k] = true;
    } else {
      t.behind[k] = radiance;
      t.has_behind[k] = true;
    }
  }
}

/// The visibilities of each lit pixel: the share of its free sun and lamp rays, and the sky its
/// sky rays brought back against the open sky's light.
void finish_visibility(const Pass& p, TileState& t) {
  const Lighting& l = *p.shading->lighting;
  for (int k = 0; k < t.count; ++k) {
    if (!t.hit[k]) {
      continue;
    }
    Visibility& v = t.vis[k];
    v.sun = t.sun_rays[k] > 0 ? static_cast<double>(t.sun_free[k]) / t.sun_rays[k] : 1.0;
    v.lights = t.light_rays[k] > 0 ? static_cast<double>(t.light_free[k]) / t.light_rays[k] : 1.0;
    if (t.sky_rays[k] > 0) {
      const Color mean = t.sky_sum[k] * (1.0 / t.sky_rays[k]);
      const Color open = l.sky_light(t.surface[k].normal);
      auto ratio = [](double a, double b) { return b > 1e-12 ? std::min(a / b, 4.0) : 1.0; };
      v.sky = {ratio(mean.r, open.r), ratio(mean.g, open.g), ratio(mean.b, open.b)};
    }
  }
}

/// Turns the secondary rays of a tile into visibilities and radiances.
void resolve_rays(const Pass& p, TileState& t, TileScratch& s) {
  trace_queued(p, t, s);
  find_secondary(p, t, s);
  gather_probes(p, t, s);
  finish_visibility(p, t);
}

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

/// The sky seen by pixel `px` along `dir`: its whole record (every field: the buffers are kept
/// from frame to frame) and unit visibilities.
void store_sky(const Pass& p, size_t px, Vec3 dir) {
  PixelGeometry& g = (*p.geometry)[px];
  g = PixelGeometry{};
  g.distance = kInfinity;
  PixelRecord& rec = (*p.records)[px];
  rec = PixelRecord{};
  rec.terms.base = sky_seen(*p.shading, p.origin_local, dir);
  (*p.visibility)[px] = PixelVisibility{};
}

/// What lane k of the primary packet hit, as shading needs it.
SurfaceHit primary_hit(const Pass& p, const RTCRayHit16& rh, int k, Vec3 dir,
                       const SceneData::Label& label) {
  SurfaceHit sh;
  sh.inst_id = rh.hit.instID[0][k];
  sh.geom_id = rh.hit.geomID[k];
  sh.prim_id = rh.hit.primID[k];
  sh.u = rh.hit.u[k];
  sh.v = rh.hit.v[k];
  sh.view_dir = dir;
  sh.distance = rh.ray.tfar[k];
  sh.position = p.origin_local + dir * sh.distance;
  const Vec3 n =
      p.scene->world_normal(sh.inst_id, {rh.hit.Ng_x[k], rh.hit.Ng_y[k], rh.hit.Ng_z[k]});
  sh.normal = dot(n, dir) > 0.0 ? -n : n;
  sh.semantic = label.semantic;
  sh.entity = label.entity;
  return sh;
}

/// The record (surface, shading terms, mirrored and transmitted light) and the visibilities of
/// lit pixel k of a resolved tile.
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
  rec.terms = shade_terms(*p.shading, sp, t.has_mirrored[k] ? &t.mirrored[k] : nullptr,
                          t.has_behind[k] ? &t.behind[k] : nullptr);
  PixelVisibility& v = (*p.visibility)[t.pixel[k]];
  const Visibility& e = t.vis[k];
  v.sun = static_cast<float>(e.sun);
  v.sky[0] = static_cast<float>(e.sky.r);
  v.sky[1] = static_cast<float>(e.sky.g);
  v.sky[2] = static_cast<float>(e.sky.b);
  v.lights = static_cast<float>(e.lights);
}

}  // namespace

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
    const SurfaceHit sh = primary_hit(p, rh, k, t.dir[k], label);
    t.hit[k] = true;
    t.surface[k] = surface_at(*p.shading, sh);
    queue_rays(p, t, k, scratch);
    if (p.motion) {
      store_motion(p, t.pixel[k], p.scene->to_map(sh.position), label.entity);
    }
  }
  if (!rgb) {
    return;
  }
  resolve_rays(p, t, scratch);
  for (int k = 0; k < 16; ++k) {
    if (valid[k] && t.hit[k]) {
      store_lit(p, t, k);
    }
  }
}

}  // namespace corsa::sensors::detail
