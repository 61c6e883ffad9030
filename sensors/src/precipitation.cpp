// Falling rain and snow in the RGB image: drops and flakes at random distances in front of the
// camera, drawn into the linear image before development where the scene lies farther away.
// A raindrop falls at about 6.5 m/s (Gunn and Kinzer 1949, 2 mm drops) and is seen as a streak
// over the exposure time; a snowflake falls at about 1 m/s and is seen as a soft disc. Drops
// gather light from a wide cone, so they are brighter than what they cover (the sky light, at
// least). Streaks are drawn over at least 4 ms: at the very short exposures of a bright day
// real drops are points a viewer barely notices, and a 4 ms streak is what a viewer sees.

#include <algorithm>
#include <cmath>

#include "brdf.h"
#include "corsa/core/random.h"
#include "fast_normal.h"
#include "shading.h"

namespace corsa::sensors::detail {
namespace {

struct Canvas {
  std::vector<float>& linear;
  const std::vector<float>& depth;
  int width;
  int height;

  /// Blends `colour` over pixel (x, y) with opacity a if the scene there is beyond z.
  void blend(int x, int y, double z, Color colour, double a, double brighten) {
    if (x < 0 || y < 0 || x >= width || y >= height || a <= 0.0) {
      return;
    }
    const size_t px = static_cast<size_t>(y) * width + x;
    if (!(depth[px] > z)) {
      return;
    }
    float* v = &linear[3 * px];
    const double c[3] = {colour.r, colour.g, colour.b};
    for (int k = 0; k < 3; ++k) {
      const double drop = std::max(c[k], v[k] * brighten);
      v[k] = static_cast<float>(v[k] * (1.0 - a) + drop * a);
    }
  }
};

void rain(Canvas& canvas, double fx, const Lighting& l, double lateral_wind, double exposure_s,
          RandomStream& rng) {
  const int w = canvas.width;
  const int h = canvas.height;
  const auto count =
      static_cast<int>(std::min(25.0, l.rain_intensity) * static_cast<double>(w) * h / 30000.0);
  const double streak_time = std::max(exposure_s, 0.004);
  const double wind = std::atan(lateral_wind / 6.5);
  const Color light = l.ambient * 1.2 + l.fog_color * 0.3;
  for (int i = 0; i < count; ++i) {
    // Uniform in the volume of the view: distances grow as the cube root.
    const double z = 0.6 + 11.4 * std::cbrt(rng.uniform01());
    const double x0 = rng.uniform(0.0, w);
    const double y0 = rng.uniform(-0.1 * h, h);
    const double length = std::max(2.0, 6.5 * streak_time * fx / z);
    const double angle = wind + rng.uniform(-0.04, 0.04);
    const double dx = std::sin(angle), dy = std::cos(angle);
    const double alpha = std::clamp(0.5 / z, 0.04, 0.3);
    const int steps = static_cast<int>(2.0 * length) + 1;
    for (int s = 0; s < steps; ++s) {
      const double t = 0.5 * s;
      canvas.blend(static_cast<int>(x0 + dx * t), static_cast<int>(y0 + dy * t), z, light,
                   alpha * 0.5, 1.25);
    }
  }
}

void snow(Canvas& canvas, double fx, const Lighting& l, double lateral_wind, double exposure_s,
          RandomStream& rng) {
  const int w = canvas.width;
  const int h = canvas.height;
  const auto count =
      static_cast<int>(std::min(10.0, l.snow_intensity) * static_cast<double>(w) * h / 9000.0);
  const Color light = (l.ambient + l.sun * 0.3) * 0.85;
  for (int i = 0; i < count; ++i) {
    const double z = 0.5 + 14.5 * std::cbrt(rng.uniform01());
    const double x0 = rng.uniform(0.0, w);
    const double y0 = rng.uniform(0.0, h);
    const double radius = std::max(0.6, 0.003 * fx / z);  // 6 mm flakes
    const double fall = std::max(1.0 * exposure_s * fx / z, 0.0);
    const double drift = lateral_wind * exposure_s * fx / z;
    const int steps = static_cast<int>(std::ceil(std::hypot(fall, drift))) + 1;
    const double alpha = std::clamp(1.5 / z, 0.2, 0.85) / steps;
    const int reach = static_cast<int>(std::ceil(radius + 1.0));
    for (int s = 0; s < steps; ++s) {
      const double f = steps > 1 ? static_cast<double>(s) / (steps - 1) : 0.0;
      const double cxp = x0 + drift * f, cyp = y0 + fall * f;
      for (int y = static_cast<int>(cyp) - reach; y <= static_cast<int>(cyp) + reach; ++y) {
        for (int x = static_cast<int>(cxp) - reach; x <= static_cast<int>(cxp) + reach; ++x) {
          const double d = std::hypot(x + 0.5 - cxp, y + 0.5 - cyp) / radius;
          const double cover = std::clamp(1.5 - d, 0.0, 1.0);
          canvas.blend(x, y, z, light, alpha * cover, 1.6);
        }
      }
    }
  }
}

}  // namespace

void draw_precipitation(std::vector<float>& linear, const std::vector<float>& depth, int width,
                        int height, double fx, const Lighting& lighting, double lateral_wind,
                        double exposure_s, uint64_t frame_seed) {
  if (lighting.rain_intensity <= 0.0 && lighting.snow_intensity <= 0.0) {
    return;
  }
  Canvas canvas{linear, depth, width, height};
  RandomStream rng(block_seed(frame_seed ^ 0x7261696eULL, 0));
  if (lighting.rain_intensity > 0.0) {
    rain(canvas, fx, lighting, lateral_wind, exposure_s, rng);
  }
  if (lighting.snow_intensity > 0.0) {
    snow(canvas, fx, lighting, lateral_wind, exposure_s, rng);
  }
}

}  // namespace corsa::sensors::detail
