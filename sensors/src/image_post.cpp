// Image post-processing of the RGB camera: motion blur along per-pixel motion, development
// (exposure, sensor noise, gamma) and rain streaks.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "corsa/core/random.h"
#include "fast_normal.h"
#include "shading.h"

namespace corsa::sensors::detail {

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
