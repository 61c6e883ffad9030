// Shading of camera hits: the material's look at the hit (textures prefiltered to the pixel
// footprint, wet road with puddles, snow cover), lit by the sun, the sky and the lamps through a
// diffuse (Lambert) and a microfacet (GGX) lobe, a clear coat over car paint, glass that
// reflects by Fresnel's law and lets the view through, and the emission of lamps switched by
// the entity's light state, the signal's state or darkness.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "brdf.h"
#include "noise_tile.h"
#include "scalar_math.h"
#include "shading.h"
#include "surface.h"
#include "vehicle_lamps.h"

namespace corsa::sensors::detail {
namespace {

bool is_road_like(SemanticClass c) {
  return c == SemanticClass::kRoad || c == SemanticClass::kLaneMarking ||
         c == SemanticClass::kParking || c == SemanticClass::kBikeLane ||
         c == SemanticClass::kSidewalk;
}

constexpr uint32_t bit(LightRole r) { return 1u << static_cast<unsigned>(r); }

/// Texture coordinates at a hit and the texture units per metre there.
void hit_uv(const ShadingContext& c, const SurfaceHit& h, TexturePoint& tp) {
  const SceneData& d = *c.scene;
  const std::array<float, 2>* uv[3] = {nullptr, nullptr, nullptr};
  if (h.entity < 0) {
    const StaticGeometry& g = d.static_geometries[h.geom_id];
    if (g.uvs.empty()) {
      return;
    }
    const auto& t = g.uv_triangles[h.prim_id];
    for (int k = 0; k < 3; ++k) {
      uv[k] = &g.uvs[t[k]];
    }
    tp.uv_per_m = g.uv_per_m[h.prim_id];
  } else {
    const ArticulatedMesh& mesh = d.instances[h.entity].shape->mesh;
    if (mesh.uvs.empty()) {
      return;
    }
    const auto& t = mesh.triangles[h.prim_id];
    for (int k = 0; k < 3; ++k) {
      uv[k] = &mesh.uvs[t[k]];
    }
    const Vec3 e1 = mesh.vertices[t[1]] - mesh.vertices[t[0]];
    const Vec3 e2 = mesh.vertices[t[2]] - mesh.vertices[t[0]];
    const double area = norm(cross(e1, e2));
    const double uv_area = std::fabs(((*uv[1])[0] - (*uv[0])[0]) * ((*uv[2])[1] - (*uv[0])[1]) -
                                     ((*uv[2])[0] - (*uv[0])[0]) * ((*uv[1])[1] - (*uv[0])[1]));
    tp.uv_per_m = area > 0.0 ? std::sqrt(uv_area / area) : 1.0;
  }
  const double w0 = 1.0 - h.u - h.v;
  tp.u = w0 * (*uv[0])[0] + h.u * (*uv[1])[0] + h.v * (*uv[2])[0];
  tp.v = w0 * (*uv[0])[1] + h.u * (*uv[1])[1] + h.v * (*uv[2])[1];
}

/// The shading normal of a static hit: the mesh's vertex normals interpolated at the hit (at
/// Embree's barycentrics u, v) and turned to the viewer's side of the surface, or the flat
/// normal when the mesh has none or the triangle's are zero (a flat part of a smooth mesh).
Vec3 smooth_normal(const StaticGeometry& g, const SurfaceHit& h) {
  if (g.normals.empty()) {
    return h.normal;
  }
  const auto& t = g.normal_triangles[h.prim_id];
  const double w0 = 1.0 - h.u - h.v;
  const auto& a = g.normals[t[0]];
  const auto& b = g.normals[t[1]];
  const auto& c = g.normals[t[2]];
  const Vec3 sum{w0 * a[0] + h.u * b[0] + h.v * c[0], w0 * a[1] + h.u * b[1] + h.v * c[1],
                 w0 * a[2] + h.u * b[2] + h.v * c[2]};
  if (dot(sum, sum) < 1e-12) {
    return h.normal;
  }
  const Vec3 n = normalized(sum);
  return dot(n, h.normal) < 0.0 ? n * -1.0 : n;
}

bool needs_uv(const Material& m) {
  return m.image != nullptr || m.pattern == Pattern::kSignFace || m.pattern == Pattern::kPlate ||
         m.pattern == Pattern::kGlazing ||  // panes: their column, floor and share across
         m.pattern == Pattern::kAsphalt ||  // wheel paths and repairs follow the lanes
         m.pattern == Pattern::kTerrain;    // verges follow the kerbs
}

/// Whether a material's emission is switched on at this hit.
bool lamp_lit(const ShadingContext& c, const SurfaceHit& h, const Material& m) {
  if (m.light == LightRole::kNone) {
    return false;
  }
  const uint32_t b = bit(m.light);
  if (h.entity >= 0) {
    return (c.entity_lamps[h.entity] & b) != 0;
  }
  if (m.light == LightRole::kSignalRed || m.light == LightRole::kSignalYellow ||
      m.light == LightRole::kSignalGreen) {
    const int s = c.scene->static_geometries[h.geom_id].signal;
    if (s < 0) {
      return false;
    }
    const int k = m.light == LightRole::kSignalRed      ? 0
                  : m.light == LightRole::kSignalYellow ? 1
                                                        : 2;
    return (c.scene->signal_bulbs[s] >> k) & 1u;
  }
  return (c.static_lamps & b) != 0;
}

/// A lit lamp's emission at a hit: the material's own, unless a LightStateAction gave the
/// entity's lamp of that role a look.
Color lamp_emission(const ShadingContext& c, const SurfaceHit& h, const Material& m) {
  if (h.entity >= 0 && static_cast<size_t>(h.entity) < c.entity_looks.size()) {
    const LampLooks& looks = c.entity_looks[h.entity];
    const auto role = static_cast<size_t>(m.light);
    if (role < looks.size() && looks[role] != nullptr) {
      return looked_emission(*looks[role], m.light, m.emission);
    }
  }
  return m.emission;
}

/// Wet road: water darkens the porous surface and smooths it; in puddles (the low spots of a
/// 12 m noise field, more of them the harder it rains) it is a mirror over a dark bottom.
void wet(const Lighting& l, const TexturePoint& tp, SurfacePoint& s, double& roughness) {
  const double rain = std::max(l.rain_intensity, 1.0);
  const double level = 0.32 + 0.05 * std::min(std::log2(rain), 4.0);
  const double field = noise(2, tp.position.x * 0.7 + 31.0, tp.position.y * 0.7 - 17.0, 12.0,
                             tp.footprint, tp.one_level);
  const double puddle = 1.0 - smoothstep(level - 0.02, level + 0.02, field);
  s.diffuse = s.diffuse * (0.55 - 0.35 * puddle);
  roughness = std::min(roughness, 0.3) * (1.0 - puddle) + 0.02 * puddle;
  s.f0 = mix(s.f0, Color{0.02, 0.02, 0.02}, 0.5 + 0.5 * puddle);
  s.mirror = s.mirror || puddle > 0.5;
}

/// Snow lying on upward surfaces: thick on ground, roofs and cars, patchy slush on roads.
void snow(const Lighting& l, const TexturePoint& tp, SemanticClass cls, SurfacePoint& s,
          double& roughness) {
  const double up = smoothstep(0.45, 0.8, s.normal.z);
  if (up <= 0.0) {
    return;
  }
  const double amount = std::min(1.0, l.snow_intensity / 1.5 + 0.3);
  const double patch =
      noise(1, tp.position.x * 1.3, tp.position.y * 1.3, 6.0, tp.footprint, tp.one_level);
  double cover = cls == SemanticClass::kRoad || cls == SemanticClass::kLaneMarking
                     ? smoothstep(0.55, 0.75, patch + 0.2 * amount) * 0.8
                     : smoothstep(0.2, 0.45, patch + 0.3 * amount);
  cover *= up * amount;
  s.diffuse = mix(s.diffuse, Color{0.82, 0.84, 0.88}, cover);
  s.f0 = mix(s.f0, Color{0.02, 0.02, 0.02}, cover);
  s.clearcoat *= 1.0 - cover;
  roughness = roughness + (0.65 - roughness) * cover;
}

}  // namespace

QualitySettings quality_settings(RenderQuality q) {
  QualitySettings s;
  switch (q) {
    case RenderQuality::kFast:
      return s;
    case RenderQuality::kDefault:
      s.soft_sun = true;
      s.sky_rays = 1;
      s.light_rays = 1;
      s.reflections = true;
      s.transmission = true;
      s.edge_samples = 4;
      s.denoise = true;
      s.bloom = true;
      s.motion_blur = true;
      s.glossy_sky = true;
      s.trilinear = true;
      s.sensor_noise = true;
      return s;
    case RenderQuality::kHigh:
      s.sun_rays = 4;
      s.soft_sun = true;
      s.sky_rays = 8;
      s.bounce_shadow = true;
      s.light_rays = 4;
      s.reflections = true;
      s.transmission = true;
      s.edge_samples = 12;
      s.denoise = true;
      s.bloom = true;
      s.motion_blur = true;
      s.glossy_sky = true;
      s.trilinear = true;
      s.sensor_noise = true;
      return s;
  }
  return s;
}

ShadingContext make_shading_context(const SceneData& scene, const Lighting& lighting,
                                    double pixel_angle, RenderQuality quality) {
  ShadingContext c;
  c.scene = &scene;
  c.lighting = &lighting;
  c.pixel_angle = pixel_angle;
  c.quality = quality_settings(quality);
  c.darkness = lighting.darkness;
  c.static_lamps =
      bit(LightRole::kAlways) | (lighting.darkness > 0.3 ? bit(LightRole::kStreetLamp) : 0u);
  bool looks = false;
  for (const auto& inst : scene.instances) {
    c.entity_lamps.push_back(
        vehicle_lamp_state(scene.entities[inst.snapshot_index], lighting.headlights).roles);
    looks = looks || !scene.entities[inst.snapshot_index].light_looks.empty();
  }
  if (looks) {
    for (const auto& inst : scene.instances) {
      c.entity_looks.push_back(lamp_looks(scene.entities[inst.snapshot_index]));
    }
  }
  c.ground_z = scene.bounds.empty() ? 0.0 : scene.bounds.min.z - scene.options.origin.z;
  // Lamps fainter than a thousandth of the daylight at 2 m are not worth their cost.
  const double daylight = luminance(lighting.ambient) + luminance(lighting.sun);
  c.lights = LightList(scene, c.entity_lamps, c.entity_looks, c.static_lamps, 1e-3 * daylight);
  return c;
}

void place_eye(ShadingContext& c, Vec3 eye) {
  c.eye_z = eye.z;
  c.eye_air = c.lighting->air_start(eye.z - c.ground_z);
}

SurfacePoint surface_at(const ShadingContext& c, const SurfaceHit& h, double footprint_scale) {
  const SceneData& d = *c.scene;
  const Lighting& l = *c.lighting;
  const MaterialId id = d.material_of(h.inst_id, h.geom_id, h.prim_id);
  const Material& m = d.materials[id];
  Vec3 position = h.position;  // in the surface's own frame
  Vec3 normal = h.normal;
  double base_z = 0.0;
  if (h.entity < 0) {
    base_z = d.static_geometries[h.geom_id].base_z;
    normal = smooth_normal(d.static_geometries[h.geom_id], h);
  } else {
    const Rigid& w = d.instances[h.entity].world_from_entity;
    const Mat3 back = w.rotation.transposed();
    position = back * (d.to_map(h.position) - w.translation);
    normal = back * h.normal;
  }
  const double cos_view = std::clamp(-dot(h.view_dir, h.normal), 0.0, 1.0);
  // Every field given at once (as for the surface point below).
  TexturePoint tp{.position = position,
                  .normal = normal,
                  .u = 0.0,
                  .v = 0.0,
                  .footprint = footprint_scale * h.distance * c.pixel_angle /
                               std::sqrt(std::max(cos_view, 0.05)),
                  .stretch = 1.0 / std::sqrt(std::max(cos_view, 0.05)),
                  .uv_per_m = 1.0,
                  .base_z = base_z,
                  .darkness = c.darkness,
                  .one_level = !c.quality.trilinear};
  if (needs_uv(m)) {
    hit_uv(c, h, tp);
  }
  const SurfaceSample t = sample_surface(m, tp);

  const double metallic = std::clamp(t.metallic, 0.0, 1.0);
  const double q = (m.ior - 1.0) / (m.ior + 1.0);
  // Every field given at once: declared first and assigned after, the point was cleared with a
  // string store in the caller's return slot.
  SurfacePoint s{.position = h.position,
                 .normal = h.entity < 0 ? normal : h.normal,
                 .view_dir = h.view_dir,
                 .distance = h.distance,
                 .diffuse = t.albedo * (1.0 - metallic) * (1.0 - t.transmission),
                 .f0 = mix(Color{q * q, q * q, q * q}, t.albedo, metallic),
                 .roughness = 0.0,
                 .clearcoat = t.clearcoat,
                 .transmission = t.transmission,
                 .emission = t.emission,
                 .mirror = false,
                 .surface_id = 0};
  double roughness = std::clamp(t.roughness, 0.0, 1.0);
  if (l.wet_road && is_road_like(h.semantic)) {
    // Tracer-local positions: the puddles stay put on the road.
    TexturePoint at = tp;
    at.position = h.position;
    wet(l, at, s, roughness);
  }
  if (l.snow_intensity > 0.0) {
    snow(l, tp, h.semantic, s, roughness);
  }
  s.roughness = roughness;
  if (lamp_lit(c, h, m)) {
    s.emission = s.emission + lamp_emission(c, h, m);
  }
  s.mirror = s.mirror || roughness < 0.2 || s.clearcoat > 0.0 || s.transmission > 0.0;
  s.mirror = s.mirror && c.quality.reflections;
  s.surface_id = surface_id_of(d, h.inst_id, h.geom_id, id);
  return s;
}

uint32_t surface_id_of(const SceneData& d, unsigned inst_id, unsigned geom_id, MaterialId id) {
  const auto sid = static_cast<uint32_t>(inst_id * 0x9E3779B1u ^ (geom_id + 1) * 0x85EBCA77u ^
                                         (id + 1u) * 0xC2B2AE3Du) &
                   ~kFoldlessSurface;
  uint32_t out = sid == 0 ? 1u : sid;  // 0 is the sky
  const Pattern pattern = d.materials[id].pattern;
  if (pattern == Pattern::kFoliage || pattern == Pattern::kPlaster) {
    out |= kFoldlessSurface;
  }
  return out;
}

ShadeTerms shade_terms(const ShadingContext& c, const SurfacePoint& s, const Color* mirrored,
                       const Color* behind) {
  const Lighting& l = *c.lighting;
  // Built in locals and returned at the end: assembled in the caller's return slot, the terms
  // were cleared there with a string store first (a tenth of this function's time).
  Color base, sun_term, sky_term, lights_term;
  const Vec3 n = s.normal;
  const Vec3 v = -s.view_dir;
  const double n_dot_v = std::max(dot(n, v), 1e-4);
  const Vec3 r = reflect(s.view_dir, n);
  // The clear coat (a smooth lacquer, IOR 1.5) reflects first; the base layer gets the rest.
  const double coat = s.clearcoat * (0.04 + 0.96 * schlick_weight(n_dot_v));
  const double under = 1.0 - coat;
  const Color spec_albedo = environment_brdf(s.f0, s.roughness, n_dot_v);
  // Glass: what is not reflected passes, to show what lies behind (darkened by the cabin).
  const Color glass_f = fresnel_schlick(s.f0, n_dot_v);

  // Sun: Lambert + GGX, the coat's own sharp lobe.
  const double n_dot_l = dot(n, l.sun_direction);
  if (n_dot_l > 0.0 && l.sun_elevation > -0.02) {
    Color sun = s.diffuse * (n_dot_l * under) +
                ggx_specular(n, v, l.sun_direction, s.roughness, s.f0) * under;
    if (s.clearcoat > 0.0) {
      sun = sun + ggx_specular(n, v, l.sun_direction, 0.08, Color{0.04, 0.04, 0.04}) * s.clearcoat;
    }
    sun_term = l.sun * sun;
  }

  // Sky light, and the sky mirrored by rough surfaces (occluded like the sky light).
  const Color sky_n = l.sky_light(n);
  sky_term = s.diffuse * sky_n * under;
  const bool traced_mirror = s.mirror && mirrored != nullptr;
  // Rougher lobes see a blurred sky: between the mirrored sky and the sky light (at the ends
  // of the range only one of them, which is all that is looked up: mix() gives it exactly).
  const double blur = traced_mirror ? 0.0 : smoothstep(0.0, 0.7, s.roughness);
  const bool sky_mirrored =
      (!traced_mirror && blur < 1.0) || (s.clearcoat > 0.0 && mirrored == nullptr);
  const Color sky_r = sky_mirrored ? l.sky(r) : Color{};
  const Color env = mirrored != nullptr ? *mirrored : sky_r;
  if (traced_mirror) {
    base = base + env * spec_albedo * under;
  } else {
    // Without the glossy sky (`fast`) the blurred sky is the sky light on the normal, already
    // at hand: one spherical-harmonic evaluation a pixel instead of two.
    const bool glossy = blur > 0.0 && c.quality.glossy_sky;
    const Color blurred = glossy ? l.sky_light(r) : sky_n;
    const Color sky_env = blur <= 0.0 ? sky_r : blur >= 1.0 ? blurred : mix(sky_r, blurred, blur);
    sky_term = sky_term + sky_env * spec_albedo * under;
  }
  if (s.clearcoat > 0.0) {
    base = base + env * coat;
  }
  if (s.transmission > 0.0) {
    const Color pass = Color{1.0, 1.0, 1.0} + glass_f * -1.0;
    if (behind != nullptr) {
      base = base + *behind * pass * (s.transmission * 0.35);
    }
  }

  // Local lights, unshadowed (their visibility multiplies the sum).
  for (const uint32_t k : c.lights.near(s.position)) {
    const LightSample ls = illuminate(c.lights.lights()[k], s.position);
    const double cos_l = dot(n, ls.direction);
    if (cos_l <= 0.0 || luminance(ls.irradiance) <= 0.0) {
      continue;
    }
    const Color lobe = s.diffuse * (cos_l * under) +
                       ggx_specular(n, v, ls.direction, std::max(s.roughness, 0.05), s.f0) * under;
    lights_term = lights_term + ls.irradiance * lobe;
  }
  base = base + s.emission;
  return {base, sun_term, sky_term, lights_term};
}

Color shade_secondary(const ShadingContext& c, const SurfacePoint& s, bool sun_visible) {
  const Lighting& l = *c.lighting;
  const Vec3 n = s.normal;
  // What a secondary ray sees: occluders are assumed to see most of the sky.
  Color light = l.sky_light(n) * 0.8;
  const double n_dot_l = dot(n, l.sun_direction);
  if (sun_visible && n_dot_l > 0.0) {
    light = light + l.sun * n_dot_l;
  }
  for (const uint32_t k : c.lights.near(s.position)) {
    const LightSample ls = illuminate(c.lights.lights()[k], s.position);
    const double cos_l = dot(n, ls.direction);
    if (cos_l > 0.0) {
      light = light + ls.irradiance * cos_l;
    }
  }
  const double n_dot_v = std::max(-dot(n, s.view_dir), 1e-4);
  const Color spec = environment_brdf(s.f0, s.roughness, n_dot_v);
  const Color mirrored = l.sky(reflect(s.view_dir, n));
  return s.diffuse * light + spec * mirrored * 0.8 + s.emission;
}

namespace {

/// The air at a ray's origin: the eye's, computed once, or its own.
Lighting::AirStart air_at(const ShadingContext& c, Vec3 origin) {
  return origin.z == c.eye_z ? c.eye_air : c.lighting->air_start(origin.z - c.ground_z);
}

}  // namespace

Color sky_seen(const ShadingContext& c, Vec3 origin, Vec3 direction) {
  const Lighting& l = *c.lighting;
  // The sky model already holds the haze of the whole atmosphere: only fog and precipitation
  // stand in front of it.
  const double t = l.transmittance(air_at(c, origin), direction.z,
                                   std::numeric_limits<double>::infinity(), false);
  return l.sky(direction) * t + l.fog_color * (1.0 - t);
}

Color through_air(const ShadingContext& c, Color radiance, Vec3 origin, Vec3 direction,
                  double distance) {
  const Lighting& l = *c.lighting;
  const double t = l.transmittance(air_at(c, origin), direction.z, distance, true);
  return radiance * t + l.fog_color * (1.0 - t);
}

}  // namespace corsa::sensors::detail
