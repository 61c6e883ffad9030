#pragma once

#include <cmath>

#include "corsa/core/det_math.h"
#include "corsa/core/random.h"

namespace corsa::sensors::detail {

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
    const double f = std::sqrt(-2.0 * det::log(s) / s);
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
