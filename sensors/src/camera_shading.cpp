#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "corsa/core/random.h"
#include "fast_normal.h"
#include "shading.h"

namespace corsa::sensors::detail {
namespace {

Color linear_from_srgb8(Rgb8 c) {
  return {std::pow(c.r / 255.0, 2.2), std::pow(c.g / 255.0, 2.2), std::pow(c.b / 255.0, 2.2)};
}

/// Paint colours of vehicles, picked by instance id so that a vehicle keeps its colour.
Color vehicle_paint(uint32_t instance_id) {
  static constexpr Rgb8 kPaints[] = {{220, 220, 222}, {25, 25, 28},  {150, 152, 158}, {160, 20, 25},
                                     {25, 55, 130},   {90, 95, 100}, {200, 190, 170}, {30, 90, 60}};
  const uint64_t h = block_seed(0x5eed, instance_id);
  return linear_from_srgb8(kPaints[h % (sizeof(kPaints) / sizeof(kPaints[0]))]);
}

/// Surface colours of the classes (sRGB), for meshes without a colour of their own.
Rgb8 class_color(SemanticClass c) {
  switch (c) {
    case SemanticClass::kRoad:
    case SemanticClass::kParking:
      return {90, 90, 92};
    case SemanticClass::kBikeLane:
      return {120, 80, 75};
    case SemanticClass::kLaneMarking:
      return {235, 235, 225};
    case SemanticClass::kSidewalk:
      return {170, 165, 155};
    case SemanticClass::kBuilding:
      return {185, 170, 150};
    case SemanticClass::kRoadside:
      return {110, 125, 80};
    case SemanticClass::kRailTrack:
      return {105, 95, 85};
    default:
      return {140, 140, 140};
  }
}

Color entity_albedo(SemanticClass c, uint32_t instance_id) {
  switch (c) {
    case SemanticClass::kPedestrian:
      return linear_from_srgb8({120, 95, 80});
    case SemanticClass::kAnimal:
      return linear_from_srgb8({140, 110, 70});
    case SemanticClass::kObstacle:
      return linear_from_srgb8({200, 120, 40});
    default:
      return vehicle_paint(instance_id);
  }
}

bool is_road_like(SemanticClass c) {
  return c == SemanticClass::kRoad || c == SemanticClass::kLaneMarking ||
         c == SemanticClass::kParking || c == SemanticClass::kBikeLane ||
         c == SemanticClass::kSidewalk;
}

bool has_headlights(SemanticClass c) {
  return c == SemanticClass::kCar || c == SemanticClass::kTruck || c == SemanticClass::kBus ||
         c == SemanticClass::kMotorcycle;
}

Vec3 reflect(Vec3 d, Vec3 n) { return d - n * (2.0 * dot(d, n)); }

}  // namespace

ShadingContext make_shading_context(const SceneData& scene, const Lighting& lighting) {
  ShadingContext c;
  c.scene = &scene;
  c.lighting = &lighting;
  for (const auto& g : scene.static_geometries) {
    c.static_albedo.push_back(linear_from_srgb8(g.color.value_or(Rgb8{})));
    c.static_has_color.push_back(g.color.has_value() ? 1 : 0);
  }
  for (int k = 0; k < kSemanticClassCount; ++k) {
    c.class_albedo[k] = linear_from_srgb8(class_color(static_cast<SemanticClass>(k)));
  }
  const double dip = -3.0 * std::numbers::pi / 180.0;  // low beams aim slightly down
  for (const auto& inst : scene.instances) {
    c.entity_albedo.push_back(entity_albedo(inst.semantic, inst.instance_id));
    if (!lighting.headlights || !has_headlights(inst.semantic)) {
      continue;
    }
    const engine::EntitySnapshot& e = scene.entities[inst.snapshot_index];
    const Rigid pose = rigid_from_pose(e.pose.x, e.pose.y, e.pose.z, e.pose.h, e.pose.p, e.pose.r);
    const Vec3 dir = pose.apply_direction({std::cos(dip), 0.0, std::sin(dip)});
    const double front = e.box.center_x + 0.5 * e.box.length + 0.05;
    const double z = e.box.center_z - 0.5 * e.box.height + 0.65;
    const int lamps = inst.semantic == SemanticClass::kMotorcycle ? 1 : 2;
    for (int i = 0; i < lamps; ++i) {
      const double y = lamps == 1 ? 0.0 : (i == 0 ? 0.35 : -0.35) * e.box.width;
      c.headlights.push_back({scene.to_local(pose.apply({front, y, z})), dir, 30.0});
    }
  }
  return c;
}

Color shade_surface(const ShadingContext& c, Vec3 position, Vec3 normal, Vec3 view_dir,
                    SemanticClass semantic, Color albedo, bool sunlit) {
  const Lighting& l = *c.lighting;
  const bool wet = l.wet_road && is_road_like(semantic);
  if (wet) {
    albedo = albedo * 0.55;  // water darkens porous surfaces
  }
  Color light = l.ambient * (0.6 + 0.4 * std::max(0.0, normal.z));
  if (sunlit) {
    light = light + l.sun * std::max(0.0, dot(normal, l.sun_direction));
  }
  for (const Headlight& h : c.headlights) {
    const Vec3 to_light = h.position - position;
    const double d2 = dot(to_light, to_light);
    if (d2 > 6400.0 || d2 < 1e-4) {
      continue;  // beyond 80 m the beam is negligible
    }
    const Vec3 dir = to_light * (1.0 / std::sqrt(d2));
    const double cos_beam = -dot(dir, h.direction);
    const double cos_surface = dot(dir, normal);
    if (cos_beam < 0.85 || cos_surface <= 0.0) {
      continue;
    }
    const double cone = std::clamp((cos_beam - 0.85) / 0.12, 0.0, 1.0);
    light = light + Color{1.0, 0.95, 0.85} * (h.intensity * cone * cos_surface / d2);
  }
  Color color = albedo * light;
  if (wet) {
    // A wet film reflects the sky (Schlick's Fresnel for water) and glints in the sun.
    const Vec3 r = reflect(view_dir, normal);
    const double cos_view = std::clamp(-dot(view_dir, normal), 0.0, 1.0);
    const double fresnel = 0.02 + 0.98 * std::pow(1.0 - cos_view, 5.0);
    color = color + l.sky(r) * (0.8 * fresnel);
    if (sunlit) {
      color = color + l.sun * (2.0 * std::pow(std::max(0.0, dot(r, l.sun_direction)), 300.0));
    }
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

void motion_blur(std::vector<float>& linear, const std::vector<float>& motion, int width,
                 int height) {
  const std::vector<float> sharp = linear;
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& r) {
    for (int row = r.begin(); row != r.end(); ++row) {
      for (int col = 0; col < width; ++col) {
        const size_t px = static_cast<size_t>(row) * width + col;
        const double mx = motion[2 * px];
        const double my = motion[2 * px + 1];
        const double length = std::sqrt(mx * mx + my * my);
        if (length < 0.5) {
          continue;
        }
        // One sample per pixel of motion, at most 16 (longer streaks are sampled more sparsely).
        const int samples = std::min(16, static_cast<int>(std::ceil(length)) + 1);
        double sum[3] = {0.0, 0.0, 0.0};
        for (int s = 0; s < samples; ++s) {
          const double f = static_cast<double>(s) / (samples - 1) - 0.5;
          // Nearest pixel: clamp first, then round the non-negative coordinate by truncation.
          const int c = static_cast<int>(std::clamp(col + f * mx, 0.0, width - 1.0) + 0.5);
          const int q = static_cast<int>(std::clamp(row + f * my, 0.0, height - 1.0) + 0.5);
          const float* v = &sharp[3 * (static_cast<size_t>(q) * width + c)];
          sum[0] += v[0];
          sum[1] += v[1];
          sum[2] += v[2];
        }
        for (int k = 0; k < 3; ++k) {
          linear[3 * px + k] = static_cast<float>(sum[k] / samples);
        }
      }
    }
  });
}

std::vector<uint8_t> develop(const std::vector<float>& linear, int width, int height,
                             const RgbOptions& o, uint64_t frame_seed) {
  // Exposure relative to ISO 100 at 1/250 s, where a sunlit 18% grey is mid-grey.
  const double exposure =
      (o.iso / 100.0) * (o.shutter_speed_s / 0.004) * std::pow(2.0, o.exposure_compensation_ev);
  const double gain = o.iso / 100.0;
  const double shot = 0.0004 * gain;  // photon noise variance per unit signal
  const double read = 0.002 * gain;   // read noise standard deviation
  const double inv_gamma = 1.0 / o.gamma;
  // Encoding through a 4096-entry table keeps pow() out of the per-pixel loop.
  std::vector<uint8_t> table(4097);
  for (int i = 0; i <= 4096; ++i) {
    table[i] = static_cast<uint8_t>(std::lround(255.0 * std::pow(i / 4096.0, inv_gamma)));
  }
  std::vector<uint8_t> out(linear.size());
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& r) {
    for (int row = r.begin(); row != r.end(); ++row) {
      RandomStream rng(block_seed(frame_seed ^ 0x6e6f697365ULL, static_cast<uint64_t>(row)));
      for (size_t i = static_cast<size_t>(row) * width * 3;
           i < static_cast<size_t>(row + 1) * width * 3; ++i) {
        double v = linear[i] * exposure;
        if (o.noise) {
          // Irwin-Hall: the sum of four 16-bit uniforms, rescaled, is close to a unit normal
          // and costs one 64-bit draw (image noise need not be exactly Gaussian).
          const uint64_t bits = rng.next_u64();
          const double s = static_cast<double>(bits & 0xFFFF) + ((bits >> 16) & 0xFFFF) +
                           ((bits >> 32) & 0xFFFF) + (bits >> 48);
          const double z = (s / 65536.0 - 2.0) * std::sqrt(3.0);
          v += z * std::sqrt(std::max(0.0, v) * shot + read * read);
        }
        const double c = std::clamp(v, 0.0, 1.0);
        out[i] = table[static_cast<size_t>(c * 4096.0 + 0.5)];
      }
    }
  });
  return out;
}

void draw_rain(std::vector<uint8_t>& rgb, int width, int height, const Lighting& l,
               uint64_t frame_seed) {
  if (l.rain_intensity <= 0.0) {
    return;
  }
  RandomStream rng(block_seed(frame_seed ^ 0x7261696eULL, 0));
  const double scale = height / 720.0;
  const auto count = static_cast<int>(std::min(20.0, l.rain_intensity) * width * height / 40000.0);
  const double slant = std::atan(l.wind_speed / 8.0) * std::sin(l.wind_direction);
  for (int i = 0; i < count; ++i) {
    const double x0 = rng.uniform(0.0, width);
    const double y0 = rng.uniform(-20.0 * scale, height);
    const double length = rng.uniform(15.0, 45.0) * scale;
    const double angle = slant + rng.uniform(-0.05, 0.05);
    const double dx = std::sin(angle);
    const double dy = std::cos(angle);
    const double alpha = rng.uniform(0.08, 0.2);
    for (int s = 0; s < static_cast<int>(length); ++s) {
      const int x = static_cast<int>(x0 + dx * s);
      const int y = static_cast<int>(y0 + dy * s);
      if (x < 0 || y < 0 || x >= width || y >= height) {
        continue;
      }
      uint8_t* p = &rgb[3 * (static_cast<size_t>(y) * width + x)];
      for (int k = 0; k < 3; ++k) {
        p[k] = static_cast<uint8_t>(p[k] + std::lround((235 - p[k]) * alpha * (p[k] < 235)));
      }
    }
  }
}

}  // namespace corsa::sensors::detail
