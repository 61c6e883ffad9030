#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

#include "corsa/core/det_math.h"
#include "corsa/core/random.h"

namespace corsa::sensors::detail {

/// Natural logarithm of s in (0, 1] from IEEE basic operations only (so deterministic
/// everywhere), accurate to about 1e-13 relative: plenty for noise, and faster than det::log.
inline double noise_log(double s) {
  const auto bits = std::bit_cast<uint64_t>(s);
  const int biased = static_cast<int>((bits >> 52) & 0x7ff);
  if (biased == 0) {
    return det::log(s);  // subnormal: never in practice
  }
  int e = biased - 1023;
  double m = std::bit_cast<double>((bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL);
  if (m > 1.4142135623730951) {
    m *= 0.5;  // exact
    e += 1;
  }
  // log(m) = 2 atanh(t), t = (m - 1) / (m + 1), |t| < 0.1716: eight odd terms reach 1e-13.
  const double t = (m - 1.0) / (m + 1.0);
  const double t2 = t * t;
  double series = 1.0 / 15.0;
  for (int k = 13; k >= 1; k -= 2) {
    series = series * t2 + 1.0 / k;
  }
  return 2.0 * t * series + e * 0.6931471805599453;
}

/// Standard normal draws from a RandomStream, two per polar-method iteration (the core stream
/// keeps only one). Deterministic: IEEE basic operations and corsa::det::log only.
class NormalPairs {
 public:
  double next(RandomStream& stream) {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u = 0.0, v = 0.0, s = 0.0;
    do {
      u = 2.0 * stream.uniform01() - 1.0;
      v = 2.0 * stream.uniform01() - 1.0;
      s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    const double f = std::sqrt(-2.0 * noise_log(s) / s);
    spare_ = v * f;
    has_spare_ = true;
    return u * f;
  }

 private:
  double spare_ = 0.0;
  bool has_spare_ = false;
};

/// Seed of work block `block` of a frame: blocks have fixed sizes, so draws never depend on how
/// blocks are spread over threads.
inline uint64_t block_seed(uint64_t frame_seed, uint64_t block) {
  uint64_t z = frame_seed + 0x9e3779b97f4a7c15ULL * (block + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace corsa::sensors::detail
