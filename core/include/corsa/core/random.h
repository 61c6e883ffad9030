#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace corsa {

/// 64-bit FNV-1a of the bytes of `text`: a stable hash, the same on every platform and run.
uint64_t stable_hash(std::string_view text);

/// Seed for a named stream of a run: mixes the run seed with the stable hash of `name`, so that
/// e.g. each entity gets its own stream and adding an entity does not shift the others' draws.
uint64_t derive_seed(uint64_t seed, std::string_view name);

/// A seeded stream of random numbers with our own distributions (xoshiro256** generator seeded by
/// splitmix64). The standard library's distributions are implementation-defined and differ
/// between platforms; these give identical draws everywhere for the same seed.
class RandomStream {
 public:
  explicit RandomStream(uint64_t seed);
  /// The stream for `name` under run seed `seed` (see derive_seed).
  static RandomStream derive(uint64_t seed, std::string_view name) {
    return RandomStream(derive_seed(seed, name));
  }

  /// Next raw 64-bit value.
  uint64_t next_u64();
  /// Uniform on [0, 1) with 53 random bits.
  double uniform01();
  /// Uniform on [lo, hi).
  double uniform(double lo, double hi);
  /// Uniform integer on [lo, hi], both inclusive, without modulo bias. Requires lo <= hi.
  int64_t uniform_int(int64_t lo, int64_t hi);
  /// Normal (Gaussian) with the given mean and standard deviation (Marsaglia's polar method).
  double normal(double mean, double stddev);
  /// Log-normal: exp(X) with X ~ Normal(mu, sigma), mu and sigma of the underlying normal.
  double log_normal(double mu, double sigma);
  /// Poisson with expected value `lambda` >= 0 (Knuth below 30, Hoermann's PTRS above).
  int64_t poisson(double lambda);
  /// Index i drawn with probability weights[i] / sum(weights). Weights must be >= 0 with a
  /// positive sum.
  size_t weighted_index(std::span<const double> weights);

 private:
  uint64_t state_[4];
};

/// Weights prepared for many draws: draw() gives the index weighted_index(weights) gives for
/// the same stream state (the same running sums, compared the same way), in O(log n) instead of
/// O(n). Weights must be finite and >= 0 with a positive sum (std::invalid_argument otherwise).
class WeightedTable {
 public:
  explicit WeightedTable(std::span<const double> weights);
  size_t draw(RandomStream& random) const;

 private:
  std::vector<double> cumulative_;  ///< running sums, in order
  size_t last_positive_ = 0;        ///< the last index with a positive weight
};

}  // namespace corsa
