// Shading of camera hits: the material's look at the hit (textures prefiltered to the pixel
// footprint), diffuse sky and sun light with shadows, vehicle headlights at night, a sky
// reflection with Schlick's Fresnel term on glossy surfaces (paint and its clear coat, glass,
// metal, wet road), and emission of lamps switched by the entity's light state, the signal's
// state or darkness.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "shading.h"
#include "surface.h"

namespace corsa::sensors::detail {
namespace {

bool is_road_like(SemanticClass c) {
  return c == SemanticClass::kRoad || c == SemanticClass::kLaneMarking ||
         c == SemanticClass::kParking || c == SemanticClass::kBikeLane ||
         c == SemanticClass::kSidewalk;
}

bool has_headlights(SemanticClass c) {
  return c == SemanticClass::kCar || c == SemanticClass::kTruck || c == SemanticClass::kBus ||
         c == SemanticClass::kMotorcycle || c == SemanticClass::kTrain;
}

constexpr uint32_t bit(LightRole r) { return 1u << static_cast<unsigned>(r); }

Vec3 reflect(Vec3 d, Vec3 n) { return d - n * (2.0 * dot(d, n)); }

double luma(Color c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

/// The lamps of an entity lit this frame: what the scenario set, and otherwise headlights and
/// tail lamps when it is dark, brake lamps and indicators as the engine reports them,
/// reversing lamps when it backs up.
uint32_t entity_lamp_bits(const EntityInstance& inst, const engine::EntitySnapshot& e,
                          const Lighting& l) {
  using engine::VehicleLight;
  auto on = [&](VehicleLight v) { return (inst.lights_on & engine::light_bit(v)) != 0; };
  auto set = [&](VehicleLight v) { return (inst.lights_set & engine::light_bit(v)) != 0; };
  uint32_t bits = bit(LightRole::kAlways);
  const bool beams_set = set(VehicleLight::kLowBeam) || set(VehicleLight::kHighBeam);
  const bool beams =
      beams_set ? on(VehicleLight::kLowBeam) || on(VehicleLight::kHighBeam) : l.headlights;
  if (beams) {
    bits |= bit(LightRole::kHeadlight) | bit(LightRole::kTail);
  }
  if (on(VehicleLight::kDaytimeRunning)) {
    bits |= bit(LightRole::kHeadlight);
  }
  if (on(VehicleLight::kBrake)) {
    bits |= bit(LightRole::kBrake);
  }
  if (on(VehicleLight::kIndicatorLeft) || on(VehicleLight::kWarning)) {
    bits |= bit(LightRole::kIndicatorLeft);
  }
  if (on(VehicleLight::kIndicatorRight) || on(VehicleLight::kWarning)) {
    bits |= bit(LightRole::kIndicatorRight);
  }
  if (on(VehicleLight::kReversing) || (!set(VehicleLight::kReversing) && e.speed < -0.1)) {
    bits |= bit(LightRole::kReversing);
  }
  return bits;
}

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

bool needs_uv(const Material& m) {
  return m.image != nullptr || m.pattern == Pattern::kSignFace || m.pattern == Pattern::kPlate;
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

}  // namespace

ShadingContext make_shading_context(const SceneData& scene, const Lighting& lighting,
                                    double pixel_angle) {
  ShadingContext c;
  c.scene = &scene;
  c.lighting = &lighting;
  c.pixel_angle = pixel_angle;
  c.darkness = 1.0 - smoothstep(0.01, 0.08, luma(lighting.ambient));
  c.static_lamps = bit(LightRole::kAlways) | (c.darkness > 0.3 ? bit(LightRole::kStreetLamp) : 0u);
  const double dip = -3.0 * std::numbers::pi / 180.0;  // low beams aim slightly down
  for (const auto& inst : scene.instances) {
    const engine::EntitySnapshot& e = scene.entities[inst.snapshot_index];
    const uint32_t lamps = entity_lamp_bits(inst, e, lighting);
    c.entity_lamps.push_back(lamps);
    if (!(lamps & bit(LightRole::kHeadlight)) || !has_headlights(inst.semantic)) {
      continue;
    }
    const Rigid& pose = inst.world_from_entity;
    const Vec3 dir = pose.apply_direction({std::cos(dip), 0.0, std::sin(dip)});
    const double front = e.box.center_x + 0.5 * e.box.length + 0.05;
    const double z = e.box.center_z - 0.5 * e.box.height + 0.65;
    const int count = inst.semantic == SemanticClass::kMotorcycle ? 1 : 2;
    for (int i = 0; i < count; ++i) {
      const double y = count == 1 ? 0.0 : (i == 0 ? 0.35 : -0.35) * e.box.width;
      c.headlights.push_back({scene.to_local(pose.apply({front, y, z})), dir, 30.0});
    }
  }
  return c;
}

Color shade_hit(const ShadingContext& c, const SurfaceHit& h, bool sunlit) {
  const SceneData& d = *c.scene;
  const Lighting& l = *c.lighting;
  const Material& m = d.materials[d.material_of(h.inst_id, h.geom_id, h.prim_id)];
  TexturePoint tp;
  if (h.entity < 0) {
    tp.position = h.position;
    tp.normal = h.normal;
    tp.base_z = d.static_geometries[h.geom_id].base_z;
  } else {
    const Rigid& w = d.instances[h.entity].world_from_entity;
    const Mat3 back = w.rotation.transposed();
    tp.position = back * (d.to_map(h.position) - w.translation);
    tp.normal = back * h.normal;
  }
  if (needs_uv(m)) {
    hit_uv(c, h, tp);
  }
  const double cos_view = std::clamp(-dot(h.view_dir, h.normal), 0.0, 1.0);
  tp.footprint = h.distance * c.pixel_angle / std::sqrt(std::max(cos_view, 0.05));
  tp.darkness = c.darkness;
  const SurfaceSample s = sample_surface(m, tp);

  const Vec3 n = h.normal;
  const bool wet = l.wet_road && is_road_like(h.semantic);
  Color albedo = s.albedo * (1.0 - s.metallic);
  if (wet) {
    albedo = albedo * 0.55;  // water darkens porous surfaces
  }
  Color light = l.ambient * (0.6 + 0.4 * std::max(0.0, n.z));
  if (sunlit) {
    light = light + l.sun * std::max(0.0, dot(n, l.sun_direction));
  }
  for (const Headlight& hl : c.headlights) {
    const Vec3 to_light = hl.position - h.position;
    const double d2 = dot(to_light, to_light);
    if (d2 > 6400.0 || d2 < 1e-4) {
      continue;  // beyond 80 m the beam is negligible
    }
    const Vec3 dir = to_light * (1.0 / std::sqrt(d2));
    const double cos_beam = -dot(dir, hl.direction);
    const double cos_surface = dot(dir, n);
    if (cos_beam < 0.85 || cos_surface <= 0.0) {
      continue;
    }
    const double cone = std::clamp((cos_beam - 0.85) / 0.12, 0.0, 1.0);
    light = light + Color{1.0, 0.95, 0.85} * (hl.intensity * cone * cos_surface / d2);
  }
  Color color = albedo * light;

  // Specular: the sky mirrored by glossy surfaces (no reflection rays: the sky only), weighted
  // by Schlick's Fresnel term, and the sun's glint.
  const Vec3 r = reflect(h.view_dir, n);
  // Glints only where the mirror direction is near the sun (pow() elsewhere adds nothing).
  const double to_sun = sunlit ? dot(r, l.sun_direction) : 0.0;
  auto lobe = [to_sun](double shininess) {
    return to_sun > 0.9 ? std::pow(to_sun, shininess) : 0.0;
  };
  const double grazing = 1.0 - cos_view;
  const double g2 = grazing * grazing;
  const double schlick = g2 * g2 * grazing;  // (1 - cos)^5
  const double smooth = 1.0 - std::clamp(s.roughness, 0.0, 1.0);
  const double gloss = smooth * smooth;
  if (gloss > 0.02) {
    const double q = (m.ior - 1.0) / (m.ior + 1.0);
    const double f0d = q * q;
    const Color f0 = mix(Color{f0d, f0d, f0d}, s.albedo, s.metallic);
    const Color fresnel = f0 + (Color{1.0, 1.0, 1.0} + f0 * -1.0) * schlick;
    const Color env = mix(l.ambient, l.sky(r), gloss);
    color = color + fresnel * env * gloss;
    if (sunlit) {
      const double r2 = s.roughness * s.roughness;
      const double shininess = 2.0 / std::max(1e-3, r2 * r2);
      const double glint = lobe(std::min(shininess, 2000.0));
      color = color + fresnel * l.sun * (glint * gloss * 3.0);
    }
  }
  if (s.clearcoat > 0.0) {
    const double fc = 0.04 + 0.96 * schlick;
    color = color + l.sky(r) * (s.clearcoat * fc);
    if (sunlit) {
      color = color + l.sun * (s.clearcoat * fc * 4.0 * lobe(600.0));
    }
  }
  if (wet) {
    // A wet film reflects the sky (Schlick's Fresnel for water) and glints in the sun.
    const double fresnel = 0.02 + 0.98 * schlick;
    color = color + l.sky(r) * (0.8 * fresnel);
    if (sunlit) {
      color = color + l.sun * (2.0 * lobe(300.0));
    }
  }
  color = color + s.emission;
  if (lamp_lit(c, h, m)) {
    color = color + m.emission;
  }
  return color;
}

Color apply_fog(const Lighting& l, Color radiance, double distance) {
  const double sigma = l.extinction();
  if (sigma <= 0.0) {
    return radiance;
  }
  const double t = std::isinf(distance) ? 0.0 : std::exp(-sigma * distance);
  return radiance * t + l.fog_color * (1.0 - t);
}

}  // namespace corsa::sensors::detail
