#pragma once

// Microfacet reflection for the camera shading (private): the GGX / Trowbridge-Reitz normal
// distribution with the height-correlated Smith masking-shadowing term (Walter, Marschner, Li and
// Torrance, "Microfacet Models for Refraction through Rough Surfaces", EGSR 2007; Heitz,
// "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs", JCGT 2014),
// Schlick's Fresnel approximation, and the split-sum environment term in Karis' analytic fit
// ("Physically Based Shading on Mobile", 2014). Roughness is perceptual (glTF): alpha = r^2.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "corsa/sensors/color.h"
#include "corsa/sensors/geometry.h"
#include "scalar_math.h"

namespace corsa::sensors::detail {

inline Vec3 reflect(Vec3 d, Vec3 n) { return d - n * (2.0 * dot(d, n)); }

inline double luminance(Color c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

/// Schlick: F0 + (1 - F0) (1 - cos)^5.
inline double schlick_weight(double cos_theta) {
  const double m = std::clamp(1.0 - cos_theta, 0.0, 1.0);
  const double m2 = m * m;
  return m2 * m2 * m;
}
inline Color fresnel_schlick(Color f0, double cos_theta) {
  const double w = schlick_weight(cos_theta);
  return f0 * (1.0 - w) + Color{w, w, w};
}

/// GGX normal distribution D(h) for alpha = roughness^2.
inline double ggx_d(double n_dot_h, double alpha) {
  const double a2 = alpha * alpha;
  const double d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
  return a2 / (kPi * d * d);
}

/// Height-correlated Smith visibility V = G / (4 n.l n.v).
inline double smith_visibility(double n_dot_l, double n_dot_v, double alpha) {
  const double a2 = alpha * alpha;
  const double gv = n_dot_l * std::sqrt(n_dot_v * n_dot_v * (1.0 - a2) + a2);
  const double gl = n_dot_v * std::sqrt(n_dot_l * n_dot_l * (1.0 - a2) + a2);
  return 0.5 / std::max(gv + gl, 1e-9);
}

/// pi * f_spec * n.l for light from l seen from v (both unit, pointing away from the surface):
/// multiplied by an irradiance in the renderer's units it gives radiance.
inline Color ggx_specular(Vec3 n, Vec3 v, Vec3 l, double roughness, Color f0) {
  const double n_dot_l = dot(n, l);
  const double n_dot_v = dot(n, v);
  if (n_dot_l <= 0.0 || n_dot_v <= 0.0) {
    return {};
  }
  const Vec3 h = normalized(l + v);
  // Very smooth surfaces would give a point light an infinitely small, infinitely bright glint;
  // the lights have a size, so the lobe is never narrower than alpha 0.002.
  const double alpha = std::max(roughness * roughness, 0.002);
  const double s = ggx_d(dot(n, h), alpha) * smith_visibility(n_dot_l, n_dot_v, alpha);
  return fresnel_schlick(f0, dot(v, h)) * (kPi * s * n_dot_l);
}

/// Directional albedo of the specular lobe under uniform light, F0 scale and bias (Karis' fit
/// of the split-sum DFG term).
inline Color environment_brdf(Color f0, double roughness, double n_dot_v) {
  const double r0 = roughness * -1.0 + 1.0;
  const double r1 = roughness * -0.0275 + 0.0425;
  const double r2 = roughness * -0.572 + 1.04;
  const double r3 = roughness * 0.022 - 0.04;
  // min(r0^2, 2^e) without the exponential where 2^e is certainly the larger: r0^2 is below
  // 2^(b - 1022) for its biased binary exponent b, and 2^e >= 2^(b - 1021) when e >= b - 1021
  // (the same value as always calling exp2).
  const double r0_2 = r0 * r0;
  const double e = -9.28 * n_dot_v;
  const auto biased = static_cast<int>(std::bit_cast<uint64_t>(r0_2) >> 52);
  const double a004 =
      (r0_2 >= 0.0 && e >= biased - 1021 ? r0_2 : std::min(r0_2, std::exp2(e))) * r0 + r1;
  const double scale = a004 * -1.04 + r2;
  const double bias = a004 * 1.04 + r3;
  return f0 * scale + Color{bias, bias, bias};
}

/// Orthonormal basis around unit n (Duff et al., "Building an Orthonormal Basis, Revisited",
/// JCGT 2017).
inline void basis(Vec3 n, Vec3& t, Vec3& b) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double c = n.x * n.y * a;
  t = {1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x};
  b = {c, sign + n.y * n.y * a, -n.y};
}

/// cos and sin of the angle 2 pi u, in single precision: the sampled directions go to Embree
/// as floats, so a double-precision sincos (a tenth of a camera ray's set-up) bought nothing.
inline void turn(double u, double& c, double& s) {
  const float phi = static_cast<float>(2.0 * kPi * u);
  c = std::cos(phi);
  s = std::sin(phi);
}

/// Cosine-weighted direction about n from two uniforms in [0, 1).
inline Vec3 cosine_direction(Vec3 n, double u1, double u2) {
  Vec3 t, b;
  basis(n, t, b);
  const double r = std::sqrt(u1);
  double c = 0.0, s = 0.0;
  turn(u2, c, s);
  const double z = std::sqrt(std::max(0.0, 1.0 - u1));
  return normalized(t * (r * c) + b * (r * s) + n * z);
}

/// A direction inside the cone of half-angle `radius` about unit axis d, uniform over the disc.
inline Vec3 cone_direction(Vec3 d, double radius, double u1, double u2) {
  Vec3 t, b;
  basis(d, t, b);
  const double r = radius * std::sqrt(u1);
  double c = 0.0, s = 0.0;
  turn(u2, c, s);
  return normalized(d + t * (r * c) + b * (r * s));
}

/// Counter-based 64 random bits: splitmix64 of a key and a counter, the same on any thread.
inline uint64_t hash_bits(uint64_t key, uint64_t counter) {
  uint64_t z = key + (counter + 1) * 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

/// Counter-based uniform in [0, 1) from hash_bits.
inline double hash_uniform(uint64_t key, uint64_t counter) {
  return static_cast<double>(hash_bits(key, counter) >> 11) * (1.0 / 9007199254740992.0);
}

/// Key of a pixel's random numbers in a frame.
inline uint64_t pixel_key(uint64_t frame_seed, uint64_t pixel, uint64_t purpose) {
  return frame_seed * 0xD1B54A32D192ED03ULL + pixel * 0x8CB92BA72F3D8DD7ULL + purpose * 0x9E37ULL;
}

/// Point n of Roberts' R2 low-discrepancy sequence, rotated by (r1, r2) (Cranley-Patterson):
/// stratified sample pairs whose rotation differs per pixel.
inline void r2_point(int n, double r1, double r2, double& u1, double& u2) {
  const double a1 = 0.7548776662466927, a2 = 0.5698402909980532;
  u1 = r1 + a1 * n;
  u2 = r2 + a2 * n;
  u1 -= std::floor(u1);
  u2 -= std::floor(u2);
}

/// One pixel's sample of an interleaved pattern (below): a point of [0, 1)^2.
struct InterleavedSample {
  double u1 = 0.0, u2 = 0.0;
};

/// A stratified pattern shared by each aligned 8x8 block of pixels (interleaved sampling:
/// Keller and Heidrich, "Interleaved Sampling", Eurographics Workshop on Rendering 2001). A
/// pixel's cell of an 8x8 grid over [0, 1)^2 has its column and row bits reversed, so each
/// aligned 8x8 block of pixels holds one point in each of the 64 cells, each aligned 4x4 block
/// one in each cell of the 4x4 grid and each 2x2 block one in each quadrant; the cells are dealt
/// to a block's pixels by a per-block XOR (which keeps all three: no regular dither where the
/// filter cannot average) and each pixel's point is jittered within its cell. The visibility
/// filter (camera_denoise.cpp), whose 3x3 taps at steps 1, 2 and 4 reach 7 pixels either way,
/// so averages stratified rays: on a plane under the sky their spread is what is left within
/// each cell, not across the hemisphere, which independent rays left as soft blotches a metre
/// across on walls. (One jitter for the whole frame would leave no spread, but bias each frame:
/// a few directions cannot weigh a bright sky near the sun right; walls came out 10% dark.)
class InterleavedPattern {
 public:
  InterleavedPattern() = default;
  /// `key`: the frame's key for one use (another use, another dealing and jitter).
  explicit InterleavedPattern(uint64_t key) : key_(key) {}

  InterleavedSample at(uint64_t col, uint64_t row) const {
    // 3-bit reversal: bit 0 of the pixel's coordinate decides the half, bit 1 the quarter.
    auto reversed = [](uint64_t v) { return ((v & 1u) << 2) | (v & 2u) | ((v >> 2) & 1u); };
    const uint64_t block = ((row >> 3) << 32) ^ (col >> 3);
    const uint64_t deal = hash_bits(key_, block);
    const uint64_t cx = reversed(col & 7u) ^ (deal >> 61);
    const uint64_t cy = reversed(row & 7u) ^ ((deal >> 58) & 7u);
    const uint64_t jitter = hash_bits(key_ ^ 0x6a09e667f3bcc909ULL, (row << 32) ^ col);
    constexpr double kUnit = 1.0 / 4294967296.0;  // 2^-32
    const double j1 = static_cast<double>(jitter >> 32) * kUnit;
    const double j2 = static_cast<double>(jitter & 0xFFFFFFFFu) * kUnit;
    return {(static_cast<double>(cx) + j1) * 0.125, (static_cast<double>(cy) + j2) * 0.125};
  }

 private:
  uint64_t key_ = 0;
};

}  // namespace corsa::sensors::detail
