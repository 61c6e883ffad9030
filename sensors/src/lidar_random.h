#pragma once

// Cheap deterministic pieces of the LiDAR return model: per-beam random draws, standard normal
// deviates and e^x. Everything is built from IEEE-754 basic operations (and corsa::det for the
// rare slow paths), so the same seed gives the same bytes on every platform.

#include <array>
#include <bit>
#include <cstdint>

namespace corsa::sensors::detail {

/// splitmix64's output function (Steele, Lea and Flood, OOPSLA 2014): a bijection of 64-bit
/// words whose outputs for consecutive inputs pass BigCrush.
inline uint64_t mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/// Counter-based draws of one beam: draw n (1, 2, ...) of beam b is
/// mix64(frame_key + (b * 2^32 + n) * golden), i.e. element b * 2^32 + n of the splitmix64
/// sequence seeded by the frame key. A beam's draws depend only on (frame seed, beam index): not
/// on blocks, threads or other beams, and a beam that hits nothing costs no draw at all.
class BeamRandom {
 public:
  static constexpr uint64_t kGolden = 0x9e3779b97f4a7c15ULL;

  /// Key of a frame: its seed mixed once so that neighbouring seeds give unrelated clouds.
  static uint64_t frame_key(uint64_t frame_seed) { return mix64(frame_seed ^ 0x6c69646172ULL); }

  BeamRandom(uint64_t frame_key, uint64_t beam) : state_(frame_key + (beam << 32) * kGolden) {}

  uint64_t next_u64() {
    state_ += kGolden;
    return mix64(state_);
  }
  /// Uniform on [0, 1) with 53 random bits.
  double uniform01() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }

 private:
  uint64_t state_;
};

/// Standard normal deviates by Marsaglia and Tsang's ziggurat (J. Stat. Software 5(8), 2000)
/// with 128 layers: 98.8% of draws cost one 64-bit random word, a table look-up and a multiply;
/// the rest go through the exact wedge test or the tail (corsa::det::exp / log). Exact up to
/// double rounding, unlike a sum of uniforms or a table inversion.
class Ziggurat {
 public:
  static constexpr int kLayers = 128;
  /// Right end of the base layer, and the common area of every layer (for 128 layers).
  static constexpr double kR = 3.442619855899;
  static constexpr double kArea = 9.91256303526217e-3;

  /// The one immutable table (built on first use, thread-safe).
  static const Ziggurat& get();

  template <class Random>
  double operator()(Random& random) const {
    for (;;) {
      const uint64_t u = random.next_u64();
      const auto layer = static_cast<int>(u & (kLayers - 1));
      // Bit 7 is the sign, moved to the sign bit: a coin-flip branch would mispredict half the
      // time. Bits 11-63 place x in the layer.
      const uint64_t sign = (u & 0x80u) << 56;
      const double x = static_cast<double>(u >> 11) * 0x1.0p-53 * x_[layer];
      if (x < x_[layer + 1]) {
        return with_sign(x, sign);  // inside the layer's rectangle under the curve
      }
      if (layer == 0) {
        const double t = tail(random.uniform01(), random.uniform01());
        if (t > 0.0) {
          return with_sign(t, sign);
        }
        continue;
      }
      if (f_[layer] + random.uniform01() * (f_[layer + 1] - f_[layer]) < density(x)) {
        return with_sign(x, sign);  // in the wedge between the rectangle and the curve
      }
    }
  }

  /// Layer edges: x_[0] = kArea / f(kR) (the base layer's virtual width), x_[1] = kR, falling to
  /// x_[128] = 0; f_[i] = e^(-x_[i]^2 / 2).
  const std::array<double, kLayers + 1>& edges() const { return x_; }

 private:
  Ziggurat();
  /// One try of Marsaglia's tail method beyond kR from two uniforms on [0, 1); 0 when rejected.
  static double tail(double u1, double u2);
  /// e^(-x^2 / 2), unnormalised.
  static double density(double x);
  static double with_sign(double x, uint64_t sign) {
    return std::bit_cast<double>(std::bit_cast<uint64_t>(x) ^ sign);
  }

  std::array<double, kLayers + 1> x_{};
  std::array<double, kLayers + 1> f_{};
};

/// e^x for x <= 0 (0 below -700) from IEEE basic operations only: x = k ln 2 + r with
/// |r| <= ln 2 / 2 and a degree-8 Taylor polynomial for e^r, relative error below 3e-10 (the
/// intensities it feeds are stored as float). About a third of the C library's instructions,
/// and the same bits on every platform.
inline double exp_nonpositive(double x) {
  constexpr double kLog2e = 1.4426950408889634;
  constexpr double kLn2Hi = 0.693147180369123816490;  // low bits zero: k * kLn2Hi is exact
  constexpr double kLn2Lo = 1.90821492927058770002e-10;
  constexpr double kShift = 0x1.8p52;  // adding it rounds to an integer (round to nearest)
  const double clamped = x >= -700.0 ? x : -700.0;
  const double shifted = clamped * kLog2e + kShift;  // low mantissa bits: k, two's complement
  const double k = shifted - kShift;
  const double r = (clamped - k * kLn2Hi) - k * kLn2Lo;
  double p = 1.0 / 40320.0;
  p = p * r + 1.0 / 5040.0;
  p = p * r + 1.0 / 720.0;
  p = p * r + 1.0 / 120.0;
  p = p * r + 1.0 / 24.0;
  p = p * r + 1.0 / 6.0;
  p = p * r + 0.5;
  p = p * r + 1.0;
  p = p * r + 1.0;
  // 2^k for k in [-1010, 0]: exponent bits k + 1023 (the shift's own bits fall off the top).
  const double scale = std::bit_cast<double>((std::bit_cast<uint64_t>(shifted) + 1023) << 52);
  const double value = p * scale;
  return x >= -700.0 ? value : 0.0;
}

}  // namespace corsa::sensors::detail
