// The secondary rays of a camera tile (stage 1, after the primary rays of camera_trace.cpp):
// each hit's visibilities are estimated with rays traced in batches per tile: shadow rays to
// the sun (over the solar disc for soft shadows; 16-ray packets, nearly parallel rays from
// neighbouring points), cosine-distributed sky rays whose occluders return one diffuse bounce,
// shadow rays to lamps picked in proportion to their light, mirror rays on smooth surfaces and
// rays through glass. Every random number is a hash of (frame seed, pixel, use) or, for the sky
// rays, of (frame seed, the pixel's 4x4 block) through an interleaved pattern (brdf.h), so the
// bytes do not depend on the thread count.

#include <algorithm>
#include <cmath>
#include <limits>

#include "brdf.h"
#include "camera_tile.h"

namespace corsa::sensors::detail {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
constexpr double kSkyRayLength = 80.0;  ///< m: beyond, occluders are part of the sky light
/// m: sky rays see the full scene this far, then the far scene (buildings as plain meshes, as
/// SceneData::far_static): beyond, a facade's recesses and ledges change which pixels of a wall
/// a ray meets, not how much sky it hides, and tracing them cost a fifth of a frame.
constexpr double kSkyNear = 4.0;
/// RTCRay::id of a sky ray whose hit is in the far static scene.
constexpr unsigned kFarHit = 1;

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

void intersect(RTCScene scene, std::vector<RTCRayHit>& rays) {
  // 16 at a time as packets: the rays of a tile start from neighbouring points.
  for (size_t first = 0; first < rays.size(); first += 16) {
    const size_t n = std::min<size_t>(16, rays.size() - first);
    alignas(64) RTCRayHit16 p;
    alignas(64) int valid[16];
    for (size_t k = 0; k < 16; ++k) {
      const RTCRayHit& r = rays[first + std::min(k, n - 1)];
      valid[k] = k < n ? -1 : 0;
      p.ray.org_x[k] = r.ray.org_x;
      p.ray.org_y[k] = r.ray.org_y;
      p.ray.org_z[k] = r.ray.org_z;
      p.ray.dir_x[k] = r.ray.dir_x;
      p.ray.dir_y[k] = r.ray.dir_y;
      p.ray.dir_z[k] = r.ray.dir_z;
      p.ray.tnear[k] = r.ray.tnear;
      p.ray.tfar[k] = r.ray.tfar;
      p.ray.mask[k] = r.ray.mask;
      p.ray.time[k] = r.ray.time;
      p.ray.id[k] = r.ray.id;
      p.ray.flags[k] = r.ray.flags;
      p.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
      p.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
    }
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcIntersect16(valid, scene, &context, &p);
    for (size_t k = 0; k < n; ++k) {
      RTCRayHit& r = rays[first + k];
      r.ray.tfar = p.ray.tfar[k];
      r.hit.Ng_x = p.hit.Ng_x[k];
      r.hit.Ng_y = p.hit.Ng_y[k];
      r.hit.Ng_z = p.hit.Ng_z[k];
      r.hit.u = p.hit.u[k];
      r.hit.v = p.hit.v[k];
      r.hit.primID = p.hit.primID[k];
      r.hit.geomID = p.hit.geomID[k];
      r.hit.instID[0] = p.hit.instID[0][k];
    }
  }
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
  const MaterialId id = h.ray.id == kFarHit
                            ? d.static_geometries[h.hit.geomID].far_material_of(h.hit.primID)
                            : d.material_of(h.hit.instID[0], h.hit.geomID, h.hit.primID);
  const Material& m = d.materials[id];
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

}  // namespace

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
    // Hard shadows aim every ray at the sun's centre: no random numbers to draw.
    const double r1 = q.soft_sun ? hash_uniform(key, 0) : 0.0;
    const double r2 = q.soft_sun ? hash_uniform(key, 1) : 0.0;
    for (int j = 0; j < q.sun_rays; ++j) {
      Vec3 d = l.sun_direction;
      if (q.soft_sun) {
        double u1 = 0.0, u2 = 0.0;
        r2_point(j, r1, r2, u1, u2);
        d = cone_direction(l.sun_direction, l.sun_angular_radius, u1, u2);
      }
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
  // Sky rays from the interleaved pattern: the filter averages them into smooth sky light on
  // walls and the ground. The sun and lamp rays keep independent draws per pixel: their
  // visibilities change within a few pixels (penumbrae), where the filter's narrow steps would
  // leave the pattern's blocks, not averaged, as a regular texture in the shadow's edge.
  const InterleavedSample r = q.sky_rays > 0
                                  ? p.patterns.sky.at(t.pixel[k] % static_cast<size_t>(p.width),
                                                      t.pixel[k] / static_cast<size_t>(p.width))
                                  : InterleavedSample{};
  for (int j = 0; j < q.sky_rays; ++j) {
    double u1 = 0.0, u2 = 0.0;
    r2_point(j, r.u1, r.u2, u1, u2);
    const Vec3 d = cosine_direction(sp.normal, u1, u2);
    probe(offset(sp, d), d, static_cast<float>(kSkyNear), kSky);
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

namespace {

/// Continues the sky rays that met nothing within kSkyNear out to kSkyRayLength: through the
/// entities of the top scene (the static instance masked off) and through the far static scene,
/// the nearer hit kept (a far static hit as the static instance's, flagged kFarHit).
void trace_far_sky(const SceneData& d, TileScratch& s) {
  s.far.clear();
  s.far_index.clear();
  for (size_t i = 0; i < s.hits.size(); ++i) {
    const RTCRayHit& h = s.hits[i];
    if (s.hit_kind[i] == kSky && h.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
      RTCRayHit& f = s.far.emplace_back(h);
      f.ray.tnear = static_cast<float>(kSkyNear);
      f.ray.tfar = static_cast<float>(kSkyRayLength);
      f.ray.mask = ~kStaticMask;
      s.far_index.push_back(i);
    }
  }
  if (s.far.empty()) {
    return;
  }
  s.far_static = s.far;
  for (RTCRayHit& f : s.far_static) {
    f.ray.mask = 0xFFFFFFFFu;
  }
  intersect(d.top, s.far);
  intersect(d.far_static, s.far_static);
  for (size_t j = 0; j < s.far.size(); ++j) {
    RTCRayHit& h = s.hits[s.far_index[j]];
    const RTCRayHit& e = s.far[j];
    const RTCRayHit& w = s.far_static[j];
    if (w.hit.geomID != RTC_INVALID_GEOMETRY_ID && w.ray.tfar <= e.ray.tfar) {
      h.ray.tfar = w.ray.tfar;
      h.hit = w.hit;
      h.hit.instID[0] = 0;
      h.ray.id = kFarHit;
    } else if (e.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
      h.ray.tfar = e.ray.tfar;
      h.hit = e.hit;
    }
  }
}

/// Traces a tile's shadow rays and probe rays, and counts each pixel's unoccluded sun and lamp
/// rays.
void trace_queued(const Pass& p, TileState& t, TileScratch& s) {
  const SceneData& d = *p.scene;
  const int suns = static_cast<int>(s.sun_owner.size());
  occluded(d, s.sun, suns);
  occluded(d, s.rays);
  intersect(d.top, s.hits);
  trace_far_sky(d, s);
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

}  // namespace

/// Turns the secondary rays of a tile into visibilities and radiances.
void resolve_rays(const Pass& p, TileState& t, TileScratch& s) {
  trace_queued(p, t, s);
  find_secondary(p, t, s);
  gather_probes(p, t, s);
  finish_visibility(p, t);
}

}  // namespace corsa::sensors::detail
