#pragma once

// The exponentials of the air's transmittance, two rays at a time (private): e^x and
// (1 - e^-x) / x on pairs of doubles (GCC vector extensions: one SSE2 register, on any x86-64),
// without a call into the maths library. Against the library's: e^x within 1 ulp (the same
// value for 91% of arguments), (1 - e^-x) / x within 3 ulp (the same for 81%). Additions,
// multiplications, one division and integer operations on the bits, in a fixed order (the build
// compiles with -ffp-contract=off): the same bits on every x86-64 and at any thread count.

#include <bit>
#include <cstdint>

namespace corsa::sensors::detail {

using AirLanes = double __attribute__((vector_size(16)));
using AirLaneBits = int64_t __attribute__((vector_size(16)));

inline AirLanes air_lanes(double a, double b) { return AirLanes{a, b}; }

/// e^x for |x| <= 700 (callers select the result for arguments beyond).
inline AirLanes air_exp(AirLanes x) {
  constexpr double kLog2e = 1.4426950408889634;
  // ln 2 split so that k * kLn2Hi is exact for |k| < 2^11 (fdlibm's constants).
  constexpr double kLn2Hi = 6.93147180369123816490e-01;
  constexpr double kLn2Lo = 1.90821492927058770002e-10;
  // Adding 1.5 * 2^52 rounds to an integer, which then sits in the low bits of the mantissa.
  constexpr double kShift = 0x1.8p52;
  const AirLanes shifted = x * kLog2e + kShift;
  const AirLanes k = shifted - kShift;
  const AirLanes r = (x - k * kLn2Hi) - k * kLn2Lo;  // |r| <= ln(2) / 2
  // e^r = 1 + r + r^2 q(r), q from Taylor's series to r^13 (the rest is below 1e-17 for
  // |r| <= 0.35), evaluated in Estrin's scheme (pairs, then pairs of pairs: a short chain of
  // dependent operations instead of Horner's eleven).
  const AirLanes r2 = r * r;
  const AirLanes r4 = r2 * r2;
  const AirLanes q01 = 0.5 + r * (1.0 / 6.0);
  const AirLanes q23 = 1.0 / 24.0 + r * (1.0 / 120.0);
  const AirLanes q45 = 1.0 / 720.0 + r * (1.0 / 5040.0);
  const AirLanes q67 = 1.0 / 40320.0 + r * (1.0 / 362880.0);
  const AirLanes q89 = 1.0 / 3628800.0 + r * (1.0 / 39916800.0);
  const AirLanes q1011 = 1.0 / 479001600.0 + r * (1.0 / 6227020800.0);
  const AirLanes q0_3 = q01 + r2 * q23;
  const AirLanes q4_7 = q45 + r2 * q67;
  const AirLanes q8_11 = q89 + r2 * q1011;
  const AirLanes q = q0_3 + r4 * (q4_7 + r4 * q8_11);
  const AirLanes e_r = 1.0 + (r + r2 * q);
  // 2^k from k's bits: its exponent field k + 1023 (k >= -1010: a normal number).
  const AirLaneBits two_k = (std::bit_cast<AirLaneBits>(shifted) + 1023) << 52;
  return e_r * std::bit_cast<AirLanes>(two_k);
}

/// e^x with the limits: 0 below -700, infinite above 700 (the air's transmittances there are
/// 0 and 1 to far below a float's precision either way).
inline AirLanes air_exp_limited(AirLanes x) {
  const AirLanes inside = x < -700.0 ? -700.0 : (x > 700.0 ? 700.0 : x);
  const AirLanes e = air_exp(inside);
  constexpr double kInf = __builtin_inf();
  return x < -700.0 ? 0.0 : (x > 700.0 ? kInf : e);
}

/// (1 - e^-x) / x, and 1 - x / 2 for |x| < 1e-5 (as the scalar air code: environment.cpp).
inline AirLanes air_expm1_ratio(AirLanes x) {
  // Near 0 the series sum (-x)^n / (n + 1)! (no cancellation; to n = 14 for |x| <= 0.35) as
  // 1 + y t(y), y = -x, t in Estrin's scheme; beyond, 1 - e^-x loses at most two bits.
  const AirLanes y = -x;
  const AirLanes y2 = y * y;
  const AirLanes y4 = y2 * y2;
  const AirLanes y8 = y4 * y4;
  const AirLanes t01 = 0.5 + y * (1.0 / 6.0);
  const AirLanes t23 = 1.0 / 24.0 + y * (1.0 / 120.0);
  const AirLanes t45 = 1.0 / 720.0 + y * (1.0 / 5040.0);
  const AirLanes t67 = 1.0 / 40320.0 + y * (1.0 / 362880.0);
  const AirLanes t89 = 1.0 / 3628800.0 + y * (1.0 / 39916800.0);
  const AirLanes t1011 = 1.0 / 479001600.0 + y * (1.0 / 6227020800.0);
  const AirLanes t1213 = 1.0 / 87178291200.0 + y * (1.0 / 1307674368000.0);
  const AirLanes t0_7 = (t01 + y2 * t23) + y4 * (t45 + y2 * t67);
  const AirLanes t8_13 = (t89 + y2 * t1011) + y4 * t1213;
  const AirLanes s = 1.0 + y * (t0_7 + y8 * t8_13);
  const AirLanes magnitude = x < 0.0 ? -x : x;
  const AirLanes near = magnitude < 1e-5 ? 1.0 - 0.5 * x : s;
  if (magnitude[0] <= 0.35 && magnitude[1] <= 0.35) {
    return near;  // most rays of a street scene: no exponential needed
  }
  const AirLanes far = (1.0 - air_exp_limited(y)) / x;
  return magnitude <= 0.35 ? near : far;
}

}  // namespace corsa::sensors::detail
