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

/// The share of a footprint `w` wide centred on x that lies in [a, b] (a box filter, exact).
double box_coverage(double x, double a, double b, double w) {
  const double half = 0.5 * std::max(w, 1e-4);
  return std::clamp((std::min(x + half, b) - std::max(x - half, a)) / (2.0 * half), 0.0, 1.0);
}

/// A band of Gaussian profile (height 1, spread sigma) at distance `d` from its centre line,
/// convolved with the footprint (taken as a Gaussian of spread w / 2): wider and fainter with
/// the same integral, so it never aliases.
double filtered_band(double d, double sigma, double w) {
  const double spread2 = sigma * sigma + 0.25 * w * w;
  return sigma / std::sqrt(spread2) * std::exp(-0.5 * d * d / spread2);
}

/// Where an asphalt point lies in its lane (from the road mesh's lane coordinates as uv).
struct AsphaltLanePoint {
  double along = 0.0;   ///< road s (m)
  double across = 0.0;  ///< metres from the lane's centre line
  double width = 0.0;   ///< the lane's width (m); 0 off the lanes (no lane coordinates)
  int64_t lane = 0;     ///< the lane's index across (|id| - 1 on road meshes)
};

AsphaltLanePoint asphalt_lane_point(const TexturePoint& p) {
  AsphaltLanePoint l;
  // u is metres along, v lanes across: uv_per_m^2 is 1 / the lane's width.
  if (p.uv_per_m <= 0.0 || (p.u == 0.0 && p.v == 0.0)) {
    return l;
  }
  l.width = 1.0 / (p.uv_per_m * p.uv_per_m);
  const double lane = std::floor(p.v);
  l.lane = static_cast<int64_t>(lane);
  l.across = (p.v - lane - 0.5) * l.width;
  l.along = p.u;
  return l;
}

/// Largest feature (m) of asphalt's aggregate grain.
constexpr double kAsphaltGrainSize = 0.03;

SurfaceSample asphalt(const Material& m, const TexturePoint& p) {
  SurfaceSample s = base(m);
  const Plane q = plane_of(p, m.seed);
  const double fp = p.footprint;
  // The aggregate's grain: the fBm's features under 3 cm alone (the field less its average over
  // 3 cm; ~6 mm texels), so that it is a grain and not soft patches (the whole fBm of a 1.5 m
  // tile has features up to a metre). Where a pixel covers 3 cm or more both reads give the
  // average: 0, without reading.
  double grain = 0.0;
  if (fp < kAsphaltGrainSize) {
    grain = pattern_noise(p, 0, q.a, q.b, 1.5, fp) -
            pattern_noise(p, 0, q.a, q.b, 1.5, kAsphaltGrainSize);
  }
  const double mid = pattern_noise(p, 1, q.a, q.b, 40.0, fp);   // tone over tens of metres
  const double wear = pattern_noise(p, 2, q.a, q.b, 90.0, fp);  // older, lighter stretches
  // Mostly the aggregate's grain; the large-scale tone is subtle (asphalt laid in one go).
  double tone = 1.0 + 2.0 * grain + 0.14 * (mid - 0.5);
  tone *= 1.0 + 0.14 * m.params[0] * smoothstep(0.5, 0.75, wear);
  // Light stones of the aggregate: one in ten 1 cm cells.
  const double stone_weight = detail_weight(fp, 0.01);
  if (stone_weight > 0.0) {
    const double r = cell_random(static_cast<int64_t>(std::floor(q.a * 100.0)),
                                 static_cast<int64_t>(std::floor(q.b * 100.0)), m.seed);
    tone += stone_weight * (r < 0.1 ? 0.5 : 0.0) - stone_weight * 0.05;
  }
  double polish = 0.0;
  const AsphaltLanePoint lane = asphalt_lane_point(p);
  // Traffic lanes only (not shoulders, bike lanes or wide areas).
  const double traffic =
      lane.width > 0.0 ? smoothstep(2.2, 2.8, lane.width) * (1.0 - smoothstep(5.0, 6.0, lane.width))
                       : 0.0;
  if (traffic > 0.0) {
    // Wheel paths: oil and rubber darken two bands 0.85 m either side of the lane's centre
    // (a car's track), more in some stretches than others; drips darken the centre a little.
    const double wheels = filtered_band(std::fabs(lane.across) - 0.85, 0.25, fp);
    const double drips = filtered_band(lane.across, 0.3, fp);
    const double traffic_wear = traffic * (0.6 + 0.8 * mid);
    tone *= 1.0 - traffic_wear * (0.16 * wheels + 0.05 * drips);
    polish = traffic * wheels;
    // Repairs: in some 10 m stretches of a lane a rectangle of newer, darker asphalt with a
    // finer grain (a patched pothole or trench), boxes filtered over the footprint.
    const auto cell = static_cast<int64_t>(std::floor(lane.along / 10.0));
    const uint32_t seed = m.seed ^ 0x5EA1u;
    if (cell_random(cell, lane.lane, seed) < 0.05 + 0.1 * m.params[0]) {
      const double length = 1.0 + 3.0 * cell_random(cell, lane.lane, seed + 1);
      const double start = cell * 10.0 + (10.0 - length) * cell_random(cell, lane.lane, seed + 2);
      const double w = (0.3 + 0.5 * cell_random(cell, lane.lane, seed + 3)) * lane.width;
      const double left =
          (cell_random(cell, lane.lane, seed + 4) - 0.5) * (lane.width - w) - 0.5 * w;
      const double patch = box_coverage(lane.along, start, start + length, fp) *
                           box_coverage(lane.across, left, left + w, fp);
      tone = lerp(tone, 0.8 + 0.8 * grain, patch);
    }
  }
  // Cracks, sealed with bitumen on worn asphalt: the 0.5 level line of a field, a dark line of a
  // few centimetres that fades out (to its small average) before the field's filtering would
  // widen it into blotches. The field is read only where they can show; elsewhere a factor is
  // exactly 0, and skipping the read keeps every value.
  const double resolved = 1.0 - smoothstep(0.01, 0.04, fp);
  const double worn = smoothstep(0.6, 0.75, wear);
  if (resolved > 0.0 && worn > 0.0) {
    const double field = pattern_noise(p, 3, q.a, q.b, 9.0, fp);
    const double crack = (1.0 - smoothstep(0.004, 0.012, std::fabs(field - 0.5))) * resolved * worn;
    tone *= 1.0 - 0.45 * crack;
  }
  s.albedo = m.base_color * std::max(0.2, tone);
  s.roughness = std::clamp(m.roughness - 0.15 * (1.0 - wear) - 0.1 * polish, 0.3, 1.0);
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

/// A wall's colour at (a along it, z above the mesh's base): the tone varying over metres and
/// tens of metres, darker vertical rain streaks.
Color wall_albedo(const Material& m, const TexturePoint& p, double a, double z) {
  const double fp = p.footprint;
  const double wall_tone = 1.0 + 0.16 * (pattern_noise(p, 0, a, z, 6.0, fp) - 0.5) +
                           0.12 * (pattern_noise(p, 2, a, z, 40.0, fp) - 0.5);
  const double streaks = smoothstep(0.55, 0.8, pattern_noise(p, 3, a * 6.0, z * 0.25, 30.0, fp));
  return m.base_color * wall_tone * (1.0 - 0.12 * streaks);
}

/// Walls without painted windows; horizontal faces (the heads and bottoms of window reveals)
/// in the wall's tone.
SurfaceSample plaster(const Material& m, const TexturePoint& p) {
  const Plane q = plane_of(p, m.seed);
  SurfaceSample s = base(m);
  s.albedo = wall_albedo(m, p, q.a, p.position.z - p.base_z);
  return s;
}

/// A window pane: the frame around it with its mullions and transom, and behind the glass a
/// dark room, curtains drawn to the sides, a blind part lowered or net curtains, chosen per
/// window (the uv's integer parts); some rooms lit at night.
SurfaceSample glazing(const Material& m, const TexturePoint& p) {
  SurfaceSample s = base(m);
  const double w = std::max(0.2, m.params[0]);
  const double h = std::max(0.2, m.params[1]);
  const double col = std::floor(p.u);
  const double row = std::floor(p.v);
  const double x = (p.u - col) * w;  // metres across the pane from its left edge
  const double z = (p.v - row) * h;  // metres up from its bottom
  const double fp = p.footprint;
  const auto cx = static_cast<int64_t>(col);
  const auto cy = static_cast<int64_t>(row);
  constexpr double kFrame = 0.06;  // m, frame and bar widths
  const double inside =
      box_coverage(x, kFrame, w - kFrame, fp) * box_coverage(z, kFrame, h - kFrame, fp);
  double bars = 0.0;
  const int mullions = static_cast<int>(std::clamp(m.params[2], 0.0, 3.0));
  for (int k = 1; k <= mullions; ++k) {
    const double at = k * w / (mullions + 1);
    bars = either(bars, box_coverage(x, at - 0.5 * kFrame, at + 0.5 * kFrame, fp));
  }
  if (m.params[3] > 0.0) {
    const double at = h * (1.0 - m.params[3]);
    bars = either(bars, box_coverage(z, at - 0.5 * kFrame, at + 0.5 * kFrame, fp));
  }
  const double glass = inside * (1.0 - bars);
  const double pick = cell_random(cx, cy, m.seed ^ 0xC0u);
  const double shade = cell_random(cx, cy, m.seed ^ 0xC1u);
  static constexpr Color kFabrics[] = {
      {0.62, 0.6, 0.55}, {0.55, 0.47, 0.36}, {0.4, 0.4, 0.42}, {0.7, 0.68, 0.64}};
  const Color fabric = kFabrics[static_cast<size_t>(shade * 4.0) % 4];
  double cloth = 0.0;
  if (pick < 0.3) {  // curtains drawn to both sides
    const double open = (0.15 + 0.15 * shade) * w;
    cloth = either(box_coverage(x, 0.0, open, fp), box_coverage(x, w - open, w, fp));
  } else if (pick < 0.45) {  // a blind lowered part of the way
    cloth = box_coverage(z, h * (0.3 + 0.5 * shade), h, fp);
  } else if (pick < 0.55) {  // net curtains: the room shows faintly through
    cloth = 0.7;
  }
  const Color room = m.base_color * (0.7 + 0.8 * cell_random(cx, cy, m.seed ^ 0xC2u));
  s.albedo = mix(m.secondary, mix(room, fabric, cloth), glass);
  s.roughness = lerp(0.55, 0.04, glass);
  // Lit rooms at night: warm or cool light, 60-250 cd/m^2 as lit interiors seen through glass
  // are (renderer radiance unit: kNitsPerUnit, about 32 kcd/m^2); through cloth a dimmer glow.
  if (p.darkness > 0.0 && cell_random(cx, cy, m.seed ^ 0xC3u) < 0.3) {
    const double tint = cell_random(cx, cy, m.seed ^ 0xC4u);
    const Color light = tint < 0.6 ? Color{1.0, 0.72, 0.42} : Color{0.75, 0.85, 1.0};
    s.emission = light * ((0.002 + 0.006 * tint) * glass * (1.0 - 0.5 * cloth) * p.darkness);
  }
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
  const Color wall = wall_albedo(m, p, q.a, z);
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
  // Single leaves (a few centimetres) and the dark gaps between them, from a 0.4 m tile read
  // slanted through the crown: a clump seen up close is speckled, not a smooth green ball
  // (the tile's fine octaves fade to their mean as the footprint grows, so a far crown is not).
  const double leaf = pattern_noise(p, 3, x.x + 0.55 * x.z + 0.3 * x.y, x.y - 0.45 * x.z, 0.4, fp);
  s.albedo = mix(m.secondary, m.base_color, t) *
             (0.75 + 0.5 * pattern_noise(p, 2, x.x, x.y + x.z, 2.0, fp)) *
             (0.5 + 0.8 * smoothstep(0.35, 0.65, leaf));
  return s;
}

/// The lawn's blade tiles fade out from a footprint of a quarter of this (m) to three quarters
/// (detail_weight): gone before a pixel covers half of their coarsest cells (17.5 cm).
constexpr double kLawnClumpSize = 0.12;

/// Lawn with a blade-scale grain, patches of lusher and thinner growth and dry (straw) patches:
/// the grass's colour before any bare soil. `dry_color` is straw. The metre-scale noise is read
/// from two tiles of incommensurate sizes turned against each other, so that a wide lawn shows
/// no period of the noise tile (a single tile repeats every few metres: a faint checker).
Color lawn(const Material& m, const TexturePoint& p, const Plane& q, Color dry_color) {
  // Read at the footprint's long axis: grass seen at a grazing angle (all of it, from a car)
  // shows moire stripes of the noise lattice when read at the mean footprint.
  const double fp = p.footprint * p.stretch;
  // The plane turned by 36.87 degrees (a 3-4-5 rotation): the second tile's axes.
  const double ra = 0.8 * q.a - 0.6 * q.b;
  const double rb = 0.6 * q.a + 0.8 * q.b;
  const double patch =
      0.5 * (pattern_noise(p, 1, q.a, q.b, 7.3, fp) + pattern_noise(p, 2, ra, rb, 11.9, fp));
  const double field = pattern_noise(p, 3, rb, -ra, 97.0, fp);  // tens of metres
  // Blades and clumps: 3 mm texels of a 0.7 m tile and a 1.13 m one turned against it, faded
  // out between footprints of 3 and 9 cm (a single tile's coarse 17.5 cm cells repeat every
  // 0.7 m: read at the bird's-eye view's 11 cm pixels they were a diagonal hatch over every
  // lawn); and one value per 1.5 cm cell (a tuft of blades) while the pixel resolves it; beyond,
  // their average (0).
  double blades = 0.0;
  const double clump_w = detail_weight(fp, kLawnClumpSize);
  if (clump_w > 0.0) {
    blades = clump_w * 0.7 *
             (pattern_noise(p, 0, ra, rb, 0.7, fp) + pattern_noise(p, 2, rb, -ra, 1.13, fp) - 1.0);
  }
  const double tuft_w = detail_weight(fp, 0.015);
  if (tuft_w > 0.0) {
    const double r = cell_random(static_cast<int64_t>(std::floor(q.a * 66.0)),
                                 static_cast<int64_t>(std::floor(q.b * 66.0)), m.seed ^ 0x51u);
    blades += tuft_w * 0.5 * (r - 0.5);
  }
  // Clover and weeds: a darker, bluer green in some 10 cm cells.
  double clover = 0.0;
  const double clover_w = detail_weight(fp, 0.1);
  if (clover_w > 0.0) {
    const double r = cell_random(static_cast<int64_t>(std::floor(ra * 10.0)),
                                 static_cast<int64_t>(std::floor(rb * 10.0)), m.seed ^ 0xc1u);
    clover = r < 0.08 ? clover_w : 0.0;
  }
  // Lusher (darker, bluer) and thinner (lighter, yellower) growth by patch and field.
  const double lush = (patch - 0.5) * 1.6 + (field - 0.5) * 0.8;
  Color green = m.base_color * Color{1.0 - 0.1 * lush, 1.0 - 0.04 * lush, 1.0 + 0.12 * lush};
  green = mix(green, m.base_color * Color{0.7, 0.85, 0.9}, 0.6 * clover);
  const double dry = smoothstep(0.56, 0.74, 0.55 * field + 0.45 * patch);
  const Color c = mix(green, dry_color, 0.75 * dry);
  // Mottle: thicker and thinner growth over 0.1-1 m where the blades fade, from a 2.9 m tile and
  // a 4.7 m one turned against it (weak: no period shows). Read only where it shows: up close
  // the blades' clumps are that scale's variation.
  double mottle = 0.0;
  if (clump_w < 1.0) {
    mottle = (1.0 - clump_w) *
             (pattern_noise(p, 3, q.a, q.b, 2.9, fp) + pattern_noise(p, 1, rb, -ra, 4.7, fp) - 1.0);
  }
  return c * (1.0 + 1.1 * blades + 0.3 * mottle - 0.12 * (patch - 0.5));
}

SurfaceSample grass(const Material& m, const TexturePoint& p) {
  SurfaceSample s = base(m);
  s.albedo = lawn(m, p, plane_of(p, m.seed), m.secondary);
  return s;
}

SurfaceSample dirt(const Material& m, const TexturePoint& p) {
  SurfaceSample s = base(m);
  const Plane q = plane_of(p, m.seed);
  const double fp = p.footprint;
  // Clods and grit: a 1.2 m tile and a 1.93 m one turned against it, so that no period shows
  // (one tile repeated every 1.2 m: diagonal streaks across bare soil in the bird's-eye view).
  const double fine =
      0.5 +
      0.7 * (pattern_noise(p, 0, q.a, q.b, 1.2, fp) +
             pattern_noise(p, 2, 0.8 * q.b - 0.6 * q.a, 0.6 * q.b + 0.8 * q.a, 1.93, fp) - 1.0);
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

/// Metres from a point of a terrain strip to its nearer hard edge (kerb, road edge), from the
/// lane coordinates its mesh carries as uvs (as asphalt reads them: u along, v lanes across,
/// uv_per_m^2 = 1 / the strip's width); infinite without them (the open ground).
double verge_distance(const TexturePoint& p) {
  const AsphaltLanePoint l = asphalt_lane_point(p);
  if (l.width <= 0.0) {
    return 1e9;
  }
  return std::max(0.0, 0.5 * l.width - std::fabs(l.across));
}

/// Grass and bare soil, and a verge along hard edges: the last 0.1-0.35 m of a strip beside a
/// kerb or a road's edge is trodden, dusty and thin (dirt and grit showing through), its inner
/// border wavering with the noise so that no line is drawn.
SurfaceSample terrain(const Material& m, const TexturePoint& p) {
  SurfaceSample s = base(m);
  const Plane q = plane_of(p, m.seed);
  const double fp = p.footprint * p.stretch;  // as the lawn's (no stripes at grazing views)
  const double soil =
      pattern_noise(p, 3, q.a, q.b, 160.0, fp) * 0.7 +
      pattern_noise(p, 1, 0.6 * q.a + 0.8 * q.b, 0.8 * q.a - 0.6 * q.b, 13.1, fp) * 0.3;
  double bare = smoothstep(0.6, 0.72, soil);
  const double edge = verge_distance(p);
  if (edge < 1.0) {
    // Soil shows through thin, trodden grass by the edge: most at the edge, none beyond a width
    // that wavers along it, patchy within.
    const AsphaltLanePoint l = asphalt_lane_point(p);
    const double width = std::clamp(0.25 * l.width, 0.08, 0.25);
    const double waver = pattern_noise(p, 2, q.a, q.b, 3.1, fp) - 0.5;
    const double patchy = pattern_noise(p, 0, q.b, q.a, 1.3, fp);
    const double worn = 1.0 - smoothstep(0.0, width, edge + 0.8 * width * waver);
    bare = either(bare, worn * (0.35 + 0.5 * patchy));
  }
  s.albedo = lawn(m, p, q, Color{0.16, 0.14, 0.05});  // straw
  if (bare > 0.0) {
    Material d = m;
    d.base_color = m.secondary;
    d.secondary = m.secondary * 0.7;
    TexturePoint wide = p;
    wide.footprint = fp;
    s.albedo = mix(s.albedo, dirt(d, wide).albedo, bare);
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
    case Pattern::kPlaster:
      return plaster(m, p);
    case Pattern::kGlazing:
      return glazing(m, p);
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
