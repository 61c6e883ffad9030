#include "corsa/core/random.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "corsa/core/det_math.h"

namespace corsa {
namespace {

uint64_t splitmix64(uint64_t& x) {
  uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

}  // namespace

uint64_t stable_hash(std::string_view text) {
  uint64_t hash = 0xcbf29ce484222325ULL;
  for (unsigned char c : text) {
    hash ^= c;
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

uint64_t derive_seed(uint64_t seed, std::string_view name) {
  uint64_t x = seed ^ stable_hash(name);
  return splitmix64(x);
}

RandomStream::RandomStream(uint64_t seed) {
  uint64_t x = seed;
  for (auto& word : state_) {
    word = splitmix64(x);
  }
}

uint64_t RandomStream::next_u64() {
  const uint64_t result = rotl(state_[1] * 5, 7) * 9;
  const uint64_t t = state_[1] << 17;
  state_[2] ^= state_[0];
  state_[3] ^= state_[1];
  state_[1] ^= state_[2];
  state_[0] ^= state_[3];
  state_[2] ^= t;
  state_[3] = rotl(state_[3], 45);
  return result;
}

double RandomStream::uniform01() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }

double RandomStream::uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }

int64_t RandomStream::uniform_int(int64_t lo, int64_t hi) {
  if (lo > hi) {
    throw std::invalid_argument("uniform_int: lo > hi");
  }
  const uint64_t range = static_cast<uint64_t>(hi) - static_cast<uint64_t>(lo);
  if (range == UINT64_MAX) {
    return static_cast<int64_t>(next_u64());
  }
  const uint64_t span = range + 1;
  // Reject the top partial block so that every value is equally likely.
  const uint64_t limit = UINT64_MAX - (UINT64_MAX % span);
  uint64_t draw = 0;
  do {
    draw = next_u64();
  } while (draw >= limit);
  return static_cast<int64_t>(static_cast<uint64_t>(lo) + draw % span);
}

double RandomStream::normal(double mean, double stddev) {
  double u = 0.0;
  double v = 0.0;
  double s = 0.0;
  do {
    u = 2.0 * uniform01() - 1.0;
    v = 2.0 * uniform01() - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double factor = std::sqrt(-2.0 * det::log(s) / s);
  return mean + stddev * u * factor;
}

double RandomStream::log_normal(double mu, double sigma) { return det::exp(normal(mu, sigma)); }

int64_t RandomStream::poisson(double lambda) {
  if (!std::isfinite(lambda) || lambda < 0.0) {
    throw std::invalid_argument("poisson: lambda must be finite and >= 0");
  }
  if (lambda == 0.0) {
    return 0;
  }
  if (lambda < 30.0) {
    // Knuth: count uniforms until their product drops below e^-lambda.
    const double limit = det::exp(-lambda);
    double product = uniform01();
    int64_t k = 0;
    while (product > limit) {
      product *= uniform01();
      ++k;
    }
    return k;
  }
  // W. Hoermann, "The transformed rejection method for generating Poisson random variables" (1993).
  const double slam = std::sqrt(lambda);
  const double loglam = det::log(lambda);
  const double b = 0.931 + 2.53 * slam;
  const double a = -0.059 + 0.02483 * b;
  const double inv_alpha = 1.1239 + 1.1328 / (b - 3.4);
  const double vr = 0.9277 - 3.6224 / (b - 2.0);
  while (true) {
    const double u = uniform01() - 0.5;
    const double v = uniform01();
    const double us = 0.5 - std::fabs(u);
    const double k = std::floor((2.0 * a / us + b) * u + lambda + 0.43);
    if (us >= 0.07 && v <= vr) {
      return static_cast<int64_t>(k);
    }
    if (k < 0.0 || (us < 0.013 && v > us)) {
      continue;
    }
    if (det::log(v) + det::log(inv_alpha) - det::log(a / (us * us) + b) <=
        -lambda + k * loglam - det::lgamma(k + 1.0)) {
      return static_cast<int64_t>(k);
    }
  }
}

size_t RandomStream::weighted_index(std::span<const double> weights) {
  double total = 0.0;
  for (double w : weights) {
    if (!(w >= 0.0) || !std::isfinite(w)) {
      throw std::invalid_argument("weighted_index: weights must be finite and >= 0");
    }
    total += w;
  }
  if (!(total > 0.0)) {
    throw std::invalid_argument("weighted_index: weights sum to zero");
  }
  const double target = uniform01() * total;
  double cumulative = 0.0;
  for (size_t i = 0; i < weights.size(); ++i) {
    cumulative += weights[i];
    if (target < cumulative) {
      return i;
    }
  }
  // Rounding left target at the very top: the last index with a positive weight.
  for (size_t i = weights.size(); i-- > 0;) {
    if (weights[i] > 0.0) {
      return i;
    }
  }
  return 0;
}

WeightedTable::WeightedTable(std::span<const double> weights) {
  cumulative_.reserve(weights.size());
  double total = 0.0;
  for (size_t i = 0; i < weights.size(); ++i) {
    const double w = weights[i];
    if (!(w >= 0.0) || !std::isfinite(w)) {
      throw std::invalid_argument("weighted_index: weights must be finite and >= 0");
    }
    total += w;
    cumulative_.push_back(total);
    if (w > 0.0) {
      last_positive_ = i;
    }
  }
  if (!(total > 0.0)) {
    throw std::invalid_argument("weighted_index: weights sum to zero");
  }
}

size_t WeightedTable::draw(RandomStream& random) const {
  const double target = random.uniform01() * cumulative_.back();
  // The first running sum above target, as weighted_index's scan finds it (the sums never
  // decrease, so the scan's first hit is the upper bound).
  const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), target);
  return it == cumulative_.end() ? last_positive_ : static_cast<size_t>(it - cumulative_.begin());
}

}  // namespace corsa
