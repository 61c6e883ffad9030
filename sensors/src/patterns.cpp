// Procedural surface patterns (see corsa/sensors/material.h): deterministic functions of the
// surface position and the material's seed. Noise comes from the mip-mapped tile (read at the
// pixel footprint) and line patterns are box filtered over the footprint, so a pattern fades to
// its average where the pixel is larger than its features instead of aliasing.

#include <algorithm>
#include <cmath>

#include "corsa/sensors/texture_image.h"
#include "noise_tile.h"
#include "scalar_math.h"
#include "surface.h"

namespace corsa::sensors::detail {
namespace {

/// 1 while features of `size` metres are resolved (footprint below a quarter of them), falling
/// to 0 at three quarters: the weight of per-cell variation, whose average is 0.
double detail_weight(double footprint, double size) {
  return 1.0 - smoothstep(0.25 * size, 0.75 * size, footprint);
}

/// The noise channel at (u, v) read with the point's filtering (surface.h TexturePoint).
double pattern_noise(const TexturePoint& p, int channel, double u, double v, double tile_m,
                     double footprint_m) {
  return noise(channel, u, v, tile_m, footprint_m, p.one_level);
}

double lerp(double a, double b, double t) { return a + (b - a) * t; }

/// Union of two coverages.
double either(double a, double b) { return 1.0 - (1.0 - a) * (1.0 - b); }

/// Surface coordinates in metres: (x, y) on floors and roofs, (along the wall, up) on walls.
struct Plane {
  double a = 0.0;
  double b = 0.0;
  bool wall = false;
};

Plane plane_of(const TexturePoint& p, uint32_t seed) {
  // Each seed reads another part of the (huge) noise plane.
  const double offset = 37.0 * static_cast<double>(seed % 9973u);
  if (std::fabs(p.normal.z) >= 0.6) {
    return {p.position.x + offset, p.position.y - offset, false};
  }
  const double h = std::hypot(p.normal.x, p.normal.y);
  const double tx = -p.normal.y / h;
  const double ty = p.normal.x / h;
  return {p.position.x * tx + p.position.y * ty + offset, p.position.z, true};
}

SurfaceSample base(const Material& m) {
  SurfaceSample s;
  s.albedo = m.base_color;
  s.roughness = m.roughness;
  s.metallic = m.metallic;
  s.clearcoat = m.clearcoat;
  s.transmission = m.transmission;
  return s;
}

SurfaceSample asphalt(const Material& m, const TexturePoint& p) {
  SurfaceSample s = base(m);
  const Plane q = plane_of(p, m.seed);
  const double fp = p.footprint;
  const double grain = pattern_noise(p, 0, q.a, q.b, 1.5, fp);  // aggregate, ~6 mm texels
  const double mid = pattern_noise(p, 1, q.a, q.b, 14.0, fp);   // patches of a few metres
  const double wear = pattern_noise(p, 2, q.a, q.b, 90.0, fp);  // older, lighter stretches
  double tone = 1.0 + 0.7 * (grain - 0.5) + 0.45 * (mid - 0.5);
  tone *= 1.0 + 0.35 * m.params[0] * smoothstep(0.45, 0.75, wear);
  // Light stones of the aggregate: one in ten 1 cm cells.
  const double stone_weight = detail_weight(fp, 0.01);
  if (stone_weight > 0.0) {
    const double r = cell_random(static_cast<int64_t>(std::floor(q.a * 100.0)),
                                 static_cast<int64_t>(std::floor(q.b * 100.0)), m.seed);
    tone += stone_weight * (r < 0.1 ? 0.5 : 0.0) - stone_weight * 0.05;
  }
  // Cracks: the 0.5 level line of a field, thin; below a resolvable size they only darken.
  // Their field is read only where they can show (a footprint under 2 cm on worn asphalt):
  // elsewhere a factor is exactly 0, and skipping the read keeps every value.
  const double resolved = 1.0 - smoothstep(0.004, 0.02, fp);
  const double worn = smoothstep(0.6, 0.75, wear);
  if (resolved > 0.0 && worn > 0.0) {
    const double field = pattern_noise(p, 3, q.a, q.b, 9.0, fp);
    const double crack = (1.0 - smoothstep(0.0, 0.005, std::fabs(field - 0.5))) * resolved * worn;
    tone *= 1.0 - 0.35 * crack;
  }
  s.albedo = m.base_color * std::max(0.2, tone);
  s.roughness = std::clamp(m.roughness - 0.15 * (1.0 - wear), 0.3, 1.0);
  return s;
}

SurfaceSample paint(const Material& m, const TexturePoint& p) {
  SurfaceSample s = base(m);
  const Plane q = plane_of(p, m.seed);
  const double fp = p.footprint;
  const double worn = pattern_noise(p, 1, q.a, q.b, 4.0, fp);
  const double grain = pattern_noise(p, 0, q.a, q.b, 1.0, fp);
  const double asphalt = smoothstep(0.32, 0.18, worn * 0.8 + grain * 0.2) * m.params[0];
  s.albedo = mix(m.base_color * (0.9 + 0.2 * grain), m.secondary, asphalt);
  return s;
}

SurfaceSample concrete(const Material& m, const TexturePoint& p) {
  SurfaceSample s = base(m);
  const Plane q = plane_of(p, m.seed);
  const double fp = p.footprint;
  const double size = std::max(0.1, m.pattern_scale);
  const double fine = pattern_noise(p, 0, q.a, q.b, 2.0, fp);
  const double stain = pattern_noise(p, 2, q.a, q.b, 20.0, fp);
  double tone = (1.0 + 0.25 * (fine - 0.5)) * (1.0 + 0.3 * (stain - 0.5));
  const double slab = cell_random(static_cast<int64_t>(std::floor(q.a / size)),
                                  static_cast<int64_t>(std::floor(q.b / size)), m.seed);
  tone *= 1.0 + 0.12 * (slab - 0.5) * detail_weight(fp, size);
  const double joint_width = 0.012;
  const double joints = either(filtered_pulse(q.a, size, joint_width / size, fp),
                               filtered_pulse(q.b, size, joint_width / size, fp));
  s.albedo = mix(m.base_color * tone, m.secondary, joints);
  return s;
}

SurfaceSample paving(const Material& m, const TexturePoint& p) {
  SurfaceSample s = base(m);
  const Plane q = plane_of(p, m.seed);
  const double fp = p.footprint;
  const double length = std::max(0.05, m.pattern_scale);
  const double width = 0.5 * length;
  const double row = std::floor(q.b / width);
  const double shifted = q.a + (static_cast<int64_t>(row) % 2 != 0 ? 0.5 * length : 0.0);
  const double col = std::floor(shifted / length);
  const double r = cell_random(static_cast<int64_t>(col), static_cast<int64_t>(row), m.seed);
  const double w = detail_weight(fp, width);
  // A fifth of the bricks in the secondary tone; the average mixes both.
  const Color brick = r < 0.2 ? mix(m.base_color, m.secondary, w * 0.6 + 0.2 * (1.0 - w))
                              : mix(m.base_color, m.secondary, 0.2 * (1.0 - w));
  const double tone =
      1.0 + 0.2 * (r - 0.5) * w + 0.2 * (pattern_noise(p, 0, q.a, q.b, 2.0, fp) - 0.5);
  const double joint = 0.006;
  const double lines = either(filtered_pulse(shifted, length, joint / length, fp),
                              filtered_pulse(q.b, width, joint / width, fp));
  s.albedo = mix(brick * tone, m.base_color * 0.45, lines);
  return s;
}

SurfaceSample roof(const Material& m, const TexturePoint& p) {
  SurfaceSample s = base(m);
  const Plane q = plane_of(p, m.seed);
  const double gravel = pattern_noise(p, 0, q.a, q.b, 3.0, p.footprint);
  const double tar = pattern_noise(p, 1, q.a, q.b, 25.0, p.footprint);
  s.albedo = Color{0.13, 0.13, 0.13} * (0.8 + 0.5 * gravel) * (0.7 + 0.6 * tar);
  s.roughness = 0.95;
  return s;
}

SurfaceSample facade(const Material& m, const TexturePoint& p) {
  const Plane q = plane_of(p, m.seed);
  if (!q.wall) {
    return roof(m, p);
  }
  SurfaceSample s = base(m);
  const double fp = p.footprint;
  const double floor_h = std::max(2.4, m.pattern_scale);
  const double bay = std::max(1.5, m.params[0]);
  const double share_x = std::clamp(m.params[1], 0.2, 0.9);
  const double share_y = std::clamp(m.params[2], 0.2, 0.8);
  const double ground = std::max(0.0, m.params[3]);
  const double z = p.position.z - p.base_z;
  const double wall_tone = 1.0 + 0.16 * (pattern_noise(p, 0, q.a, z, 6.0, fp) - 0.5) +
                           0.12 * (pattern_noise(p, 2, q.a, z, 40.0, fp) - 0.5);
  Color wall = m.base_color * wall_tone;
  // Rain streaks under windows and at the top: darker vertical stains.
  wall = wall *
         (1.0 - 0.12 * smoothstep(0.55, 0.8, pattern_noise(p, 3, q.a * 6.0, z * 0.25, 30.0, fp)));
  double glass = 0.0;
  double frame = 0.0;
  double lit = 0.0;
  const double frame_w = 0.07;
  if (z < ground) {
    // Shop fronts: tall panes in most of each bay under a dark fascia band.
    const double pane_x = filtered_pulse(q.a - 0.08 * bay, bay, 0.84, fp);
    const double pane_y = filtered_pulse(z - 0.45, 1e6, std::max(0.0, ground - 1.05) / 1e6, fp);
    glass = pane_x * pane_y;
    frame = filtered_pulse(z - (ground - 0.55), 1e6, 0.5 / 1e6, fp);
    const double cell = std::floor(q.a / bay);
    lit = cell_random(static_cast<int64_t>(cell), -1, m.seed) < 0.45 ? 1.0 : 0.0;
  } else {
    const double zz = z - ground;
    const double x0 = 0.5 * (1.0 - share_x) * bay;
    const double y0 = 0.3 * floor_h;
    const double pane_x = filtered_pulse(q.a - x0, bay, share_x, fp);
    const double pane_y = filtered_pulse(zz - y0, floor_h, share_y, fp);
    const double outer_x = filtered_pulse(q.a - x0 + frame_w, bay, share_x + 2 * frame_w / bay, fp);
    const double outer_y =
        filtered_pulse(zz - y0 + frame_w, floor_h, share_y + 2 * frame_w / floor_h, fp);
    glass = pane_x * pane_y;
    frame = std::max(0.0, outer_x * outer_y - glass);
    const auto cx = static_cast<int64_t>(std::floor(q.a / bay));
    const auto cy = static_cast<int64_t>(std::floor(zz / floor_h));
    lit = cell_random(cx, cy, m.seed ^ 0x11u) < 0.25 ? 1.0 : 0.0;
    // Far away the lit windows are an average glow.
    lit = lerp(0.25, lit, detail_weight(fp, bay));
  }
  // Glass: dark interior behind a reflective pane, some with blinds (lighter).
  const auto cell_x = static_cast<int64_t>(std::floor(q.a / bay));
  const auto cell_y = static_cast<int64_t>(std::floor(z / floor_h));
  const double blind = cell_random(cell_x, cell_y, m.seed ^ 0x77u);
  const Color pane = mix(Color{0.02, 0.025, 0.03}, Color{0.25, 0.22, 0.18},
                         blind < 0.25 ? 0.6 * detail_weight(fp, bay) : 0.0);
  s.albedo = mix(mix(wall, m.secondary, frame), pane, glass);
  s.roughness = lerp(m.roughness, 0.05, glass);
  // Lit rooms: warm or cool light of a varying strength per window, 60-250 cd/m^2 as lit
  // interiors seen through glass are (renderer radiance unit: kNitsPerUnit, about 32 kcd/m^2).
  const double tint = cell_random(cell_x, cell_y, m.seed ^ 0x99u);
  const Color room = tint < 0.6 ? Color{1.0, 0.72, 0.42} : Color{0.75, 0.85, 1.0};
  s.emission = room * ((0.002 + 0.006 * tint) * glass * lit * p.darkness);
  return s;
}

SurfaceSample foliage(const Material& m, const TexturePoint& p) {
  SurfaceSample s = base(m);
  const double fp = p.footprint;
  const Vec3 x = p.position;
  const double leaves = pattern_noise(p, 0, x.x + x.z * 0.7, x.y - x.z * 0.4, 0.8, fp);
  const double clumps = pattern_noise(p, 1, x.x - x.z * 0.5, x.y + x.z * 0.8, 5.0, fp);
  const double t = smoothstep(0.3, 0.7, 0.55 * leaves + 0.45 * clumps);
  s.albedo = mix(m.secondary, m.base_color, t) *
             (0.75 + 0.5 * pattern_noise(p, 2, x.x, x.y + x.z, 2.0, fp));
  return s;
}

SurfaceSample grass(const Material& m, const TexturePoint& p) {
  SurfaceSample s = base(m);
  const Plane q = plane_of(p, m.seed);
  const double fp = p.footprint;
  const double blades = pattern_noise(p, 0, q.a, q.b, 0.6, fp);
  const double patches = pattern_noise(p, 1, q.a, q.b, 10.0, fp);
  const double dry =
      smoothstep(0.5, 0.75, pattern_noise(p, 2, q.a, q.b, 70.0, fp) * 0.6 + patches * 0.4);
  s.albedo = mix(m.base_color, m.secondary, 0.7 * dry) * (0.7 + 0.6 * blades);
  return s;
}

SurfaceSample dirt(const Material& m, const TexturePoint& p) {
  SurfaceSample s = base(m);
  const Plane q = plane_of(p, m.seed);
  const double fp = p.footprint;
  const double fine = pattern_noise(p, 0, q.a, q.b, 1.2, fp);
  const double mid = pattern_noise(p, 1, q.a, q.b, 8.0, fp);
  double tone = (0.75 + 0.5 * fine) * (0.85 + 0.3 * mid);
  const double w = detail_weight(fp, 0.03);
  if (w > 0.0) {
    const double r = cell_random(static_cast<int64_t>(std::floor(q.a * 33.0)),
                                 static_cast<int64_t>(std::floor(q.b * 33.0)), m.seed);
    tone += w * (r < 0.12 ? 0.35 : 0.0) - 0.04 * w;
  }
  s.albedo = mix(m.base_color, m.secondary, smoothstep(0.4, 0.7, mid)) * tone;
  return s;
}

SurfaceSample terrain(const Material& m, const TexturePoint& p) {
  const Plane q = plane_of(p, m.seed);
  const double fp = p.footprint;
  const double bare = smoothstep(0.6, 0.72,
                                 pattern_noise(p, 3, q.a, q.b, 160.0, fp) * 0.7 +
                                     pattern_noise(p, 1, q.a, q.b, 12.0, fp) * 0.3);
  Material g = m;
  g.secondary = Color{0.16, 0.14, 0.05};  // dry grass
  SurfaceSample s = grass(g, p);
  if (bare > 0.0) {
    Material d = m;
    d.base_color = m.secondary;
    d.secondary = m.secondary * 0.7;
    s.albedo = mix(s.albedo, dirt(d, p).albedo, bare);
  }
  return s;
}

SurfaceSample bark(const Material& m, const TexturePoint& p) {
  SurfaceSample s = base(m);
  const Plane q = plane_of(p, m.seed);
  const double furrows = pattern_noise(p, 0, q.a * 6.0, q.b * 0.6, 1.0, p.footprint * 6.0);
  s.albedo = m.base_color * (0.55 + 0.9 * furrows);
  return s;
}

SurfaceSample rubber(const Material& m, const TexturePoint& p) {
  SurfaceSample s = base(m);
  const double n = pattern_noise(p, 0, p.position.x + p.position.z, p.position.y, 0.5, p.footprint);
  s.albedo = m.base_color * (0.85 + 0.3 * n);
  return s;
}

SurfaceSample metal_grid(const Material& m, const TexturePoint& p) {
  SurfaceSample s = base(m);
  const double slots = filtered_pulse(p.position.z, 0.035, 0.5, p.footprint);
  s.albedo = mix(m.base_color, m.secondary, slots);
  return s;
}

SurfaceSample image_texture(const Material& m, const TexturePoint& p) {
  SurfaceSample s = base(m);
  const double texels = p.footprint * p.uv_per_m * std::max(m.image->width(), m.image->height());
  s.albedo = m.base_color * m.image->sample(p.u, p.v, texels);
  return s;
}

}  // namespace

SurfaceSample sample_surface(const Material& m, const TexturePoint& p) {
  if (m.image) {
    return image_texture(m, p);
  }
  switch (m.pattern) {
    case Pattern::kNone:
      return base(m);
    case Pattern::kAsphalt:
      return asphalt(m, p);
    case Pattern::kPaint:
      return paint(m, p);
    case Pattern::kConcrete:
      return concrete(m, p);
    case Pattern::kPaving:
      return paving(m, p);
    case Pattern::kFacade:
      return facade(m, p);
    case Pattern::kRoof:
      return roof(m, p);
    case Pattern::kFoliage:
      return foliage(m, p);
    case Pattern::kGrass:
      return grass(m, p);
    case Pattern::kDirt:
      return dirt(m, p);
    case Pattern::kTerrain:
      return terrain(m, p);
    case Pattern::kBark:
      return bark(m, p);
    case Pattern::kRubber:
      return rubber(m, p);
    case Pattern::kMetalGrid:
      return metal_grid(m, p);
    case Pattern::kSignFace:
    case Pattern::kPlate: {
      SurfaceSample s = base(m);
      const double fw = std::max(1e-4, p.footprint * p.uv_per_m);
      s.albedo = sign_face_color(m.sign, p.u, p.v, fw);
      return s;
    }
  }
  return base(m);
}

}  // namespace corsa::sensors::detail
