#include "noise_tile.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace corsa::sensors::detail {
namespace {

/// Tileable value noise: random values on a `cells` x `cells` lattice that wraps around the
/// tile, interpolated with the quintic fade (C2 continuous).
float value_noise(double x, double y, int cells, uint32_t seed) {
  const double fx = std::floor(x);
  const double fy = std::floor(y);
  const double tx = x - fx;
  const double ty = y - fy;
  auto fade = [](double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); };
  const double sx = fade(tx);
  const double sy = fade(ty);
  auto at = [&](int64_t i, int64_t j) {
    return cell_random(((i % cells) + cells) % cells, ((j % cells) + cells) % cells, seed);
  };
  const auto i = static_cast<int64_t>(fx);
  const auto j = static_cast<int64_t>(fy);
  const double a = at(i, j) + (at(i + 1, j) - at(i, j)) * sx;
  const double b = at(i, j + 1) + (at(i + 1, j + 1) - at(i, j + 1)) * sx;
  return static_cast<float>(a + (b - a) * sy);
}

}  // namespace

NoiseTile::NoiseTile() {
  Level base;
  base.size = kSize;
  base.texels.resize(static_cast<size_t>(kSize) * kSize * 4);
  // Octaves of 4 to 128 lattice cells across the tile (the finest has 2 texels per cell), with
  // amplitudes falling by 0.55 per octave: a broad-band field whose mean is 0.5.
  constexpr int kOctaves = 6;
  double total = 0.0;
  for (int o = 0; o < kOctaves; ++o) {
    total += std::pow(0.55, o);
  }
  for (int c = 0; c < 4; ++c) {
    for (int y = 0; y < kSize; ++y) {
      for (int x = 0; x < kSize; ++x) {
        double sum = 0.0;
        for (int o = 0; o < kOctaves; ++o) {
          const int cells = 4 << o;
          const double k = static_cast<double>(cells) / kSize;
          sum += std::pow(0.55, o) * value_noise((x + 0.5) * k, (y + 0.5) * k, cells,
                                                 0x51ED5EEDu + 977u * c + 131u * o);
        }
        base.texels[4 * (static_cast<size_t>(y) * kSize + x) + c] = static_cast<float>(sum / total);
      }
    }
  }
  // Stretch each channel to about 0..1 around 0.5 (sums of octaves bunch up in the middle).
  for (int c = 0; c < 4; ++c) {
    double mean = 0.0;
    double var = 0.0;
    const size_t n = static_cast<size_t>(kSize) * kSize;
    for (size_t i = 0; i < n; ++i) {
      mean += base.texels[4 * i + c];
    }
    mean /= static_cast<double>(n);
    for (size_t i = 0; i < n; ++i) {
      const double d = base.texels[4 * i + c] - mean;
      var += d * d;
    }
    const double sd = std::sqrt(var / static_cast<double>(n));
    for (size_t i = 0; i < n; ++i) {
      float& v = base.texels[4 * i + c];
      v = static_cast<float>(std::clamp(0.5 + 0.17 * (v - mean) / sd, 0.0, 1.0));
    }
  }
  levels_.push_back(std::move(base));
  while (levels_.back().size > 1) {
    const Level& up = levels_.back();
    Level down;
    down.size = up.size / 2;
    down.texels.resize(static_cast<size_t>(down.size) * down.size * 4);
    for (int y = 0; y < down.size; ++y) {
      for (int x = 0; x < down.size; ++x) {
        for (int c = 0; c < 4; ++c) {
          auto at = [&](int xi, int yi) {
            return up.texels[4 * (static_cast<size_t>(yi) * up.size + xi) + c];
          };
          down.texels[4 * (static_cast<size_t>(y) * down.size + x) + c] =
              0.25f * (at(2 * x, 2 * y) + at(2 * x + 1, 2 * y) + at(2 * x, 2 * y + 1) +
                       at(2 * x + 1, 2 * y + 1));
        }
      }
    }
    levels_.push_back(std::move(down));
  }
  // Stored one channel after another: a read of one channel then touches a quarter of the
  // cache lines it would touch in interleaved texels (the reads are memory-bound).
  for (Level& level : levels_) {
    const size_t n = static_cast<size_t>(level.size) * level.size;
    std::vector<float> planar(4 * n);
    for (size_t i = 0; i < n; ++i) {
      for (size_t c = 0; c < 4; ++c) {
        planar[c * n + i] = level.texels[4 * i + c];
      }
    }
    level.texels = std::move(planar);
  }
}

namespace {

/// floor(v) wrapped into [0, n) (n a power of two) and v - floor(v). Whole numbers below 2^52
/// convert exactly and their two's complement low bits are the wrapped index, so there the
/// floor is a truncation corrected by one below zero (the same values as std::floor, without
/// its call); larger coordinates are first brought near 0 in double precision so that the
/// integer conversion never overflows.
void wrap_split(double v, int n, int& index, float& frac) {
  constexpr double kExact = 4503599627370496.0;  // 2^52
  if (std::fabs(v) < kExact) {
    auto i = static_cast<int64_t>(v);
    i -= v < static_cast<double>(i) ? 1 : 0;
    index = static_cast<int>(i & (n - 1));
    frac = static_cast<float>(v - static_cast<double>(i));
    return;
  }
  const double f = std::floor(v);
  const double period = static_cast<double>(n);
  index = static_cast<int>(static_cast<int64_t>(f - period * std::floor(f / period)) & (n - 1));
  frac = static_cast<float>(v - f);
}

}  // namespace

NoiseTile::Footprint NoiseTile::footprint(const Level& level, double x, double y) const {
  const int n = level.size;
  Footprint f;
  int x0 = 0, y0 = 0;
  wrap_split(x * n / kSize - 0.5, n, x0, f.ax);
  wrap_split(y * n / kSize - 0.5, n, y0, f.ay);
  const int x1 = (x0 + 1) & (n - 1);
  const int y1 = (y0 + 1) & (n - 1);
  f.plane = static_cast<size_t>(n) * n;
  f.texel[0] = &level.texels[static_cast<size_t>(y0) * n + x0];
  f.texel[1] = &level.texels[static_cast<size_t>(y0) * n + x1];
  f.texel[2] = &level.texels[static_cast<size_t>(y1) * n + x0];
  f.texel[3] = &level.texels[static_cast<size_t>(y1) * n + x1];
  return f;
}

std::array<float, 4> NoiseTile::bilinear(const Level& level, double x, double y) const {
  const Footprint f = footprint(level, x, y);
  std::array<float, 4> out{};
  for (int k = 0; k < 4; ++k) {
    out[k] = f.lerp(k);
  }
  return out;
}

float NoiseTile::bilinear(const Level& level, double x, double y, int k) const {
  // footprint(level, x, y).lerp(k), reading the one plane without the four pointers of all.
  const int n = level.size;
  int x0 = 0, y0 = 0;
  float ax = 0.0f, ay = 0.0f;
  wrap_split(x * n / kSize - 0.5, n, x0, ax);
  wrap_split(y * n / kSize - 0.5, n, y0, ay);
  const int x1 = (x0 + 1) & (n - 1);
  const int y1 = (y0 + 1) & (n - 1);
  const float* plane = level.texels.data() + static_cast<size_t>(k) * n * n;
  const float* row0 = plane + static_cast<size_t>(y0) * n;
  const float* row1 = plane + static_cast<size_t>(y1) * n;
  const float top = row0[x0] + (row0[x1] - row0[x0]) * ax;
  const float bottom = row1[x0] + (row1[x1] - row1[x0]) * ax;
  return top + (bottom - top) * ay;
}

std::array<float, 4> NoiseTile::sample(double x, double y, double texels) const {
  if (!std::isfinite(x) || !std::isfinite(y)) {
    return {0.5f, 0.5f, 0.5f, 0.5f};
  }
  const double lod = texels > 1.0 ? std::log2(texels) : 0.0;
  const double top = static_cast<double>(levels_.size() - 1);
  if (lod >= top) {
    return {levels_.back().texels[0], levels_.back().texels[1], levels_.back().texels[2],
            levels_.back().texels[3]};
  }
  const auto l0 = static_cast<size_t>(lod);
  const auto t = static_cast<float>(lod - static_cast<double>(l0));
  std::array<float, 4> a = bilinear(levels_[l0], x, y);
  if (t > 0.0f) {
    const std::array<float, 4> b = bilinear(levels_[l0 + 1], x, y);
    for (int k = 0; k < 4; ++k) {
      a[k] += (b[k] - a[k]) * t;
    }
  }
  return a;
}

float NoiseTile::sample(int channel, double x, double y, double texels) const {
  if (!std::isfinite(x) || !std::isfinite(y)) {
    return 0.5f;
  }
  const double lod = texels > 1.0 ? std::log2(texels) : 0.0;
  const double top = static_cast<double>(levels_.size() - 1);
  if (lod >= top) {
    return levels_.back().texels[channel];
  }
  const auto l0 = static_cast<size_t>(lod);
  const auto t = static_cast<float>(lod - static_cast<double>(l0));
  float a = bilinear(levels_[l0], x, y, channel);
  if (t > 0.0f) {
    a += (bilinear(levels_[l0 + 1], x, y, channel) - a) * t;
  }
  return a;
}

float NoiseTile::sample_one_level(int channel, double x, double y, double texels) const {
  if (!std::isfinite(x) || !std::isfinite(y)) {
    return 0.5f;
  }
  // round(log2(texels)) is the binary exponent of texels * sqrt(2) (read from its bits; texels
  // above 1 is a normal positive double).
  size_t level = 0;
  if (texels > 1.0) {
    const double scaled = texels * 1.4142135623730951;
    level = static_cast<size_t>((std::bit_cast<uint64_t>(scaled) >> 52) - 1023);
  }
  if (level >= levels_.size() - 1) {
    return levels_.back().texels[channel];
  }
  return bilinear(levels_[level], x, y, channel);
}

double filtered_pulse(double x, double period, double duty, double w) {
  // Integral of the pulse train from 0 to x, in units of the period: floor(x) d + min(frac, d).
  const double d = std::clamp(duty, 0.0, 1.0);
  auto integral = [d](double t) {
    const double f = std::floor(t);
    return f * d + std::min(t - f, d);
  };
  const double a = x / period;
  const double width = w / period;
  if (width < 1e-6) {
    return a - std::floor(a) < d ? 1.0 : 0.0;
  }
  return (integral(a + 0.5 * width) - integral(a - 0.5 * width)) / width;
}

}  // namespace corsa::sensors::detail
