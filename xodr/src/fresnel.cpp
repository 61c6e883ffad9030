// Fresnel integrals C(x), S(x) in double precision, our own evaluation:
// - |x| < 1.5: the Maclaurin series of ∫0^x exp(iπt²/2) dt, whose terms alternate between C and
//   S; at x = 1.5 the largest term is ~7, so cancellation costs at most one digit.
// - otherwise: C + iS = (1+i)/2 erf(z) with z = (√π/2)(1-i)x, and erfc(z) from its even
//   continued fraction erfc z = (2z/√π) e^{-z²} / (2z²+1 - 1·2/(2z²+5 - 3·4/(2z²+9 - ...))),
//   evaluated with the modified Lentz method. With 2z² = -iπx² this gives
//   C + iS = (1+i)/2 - x e^{iπx²/2} / K,  K = b0 + a1/(b1 + a2/(b2 + ...)),
//   b_k = 4k+1 - iπx², a_k = -(2k-1)(2k).

#include <cmath>
#include <complex>
#include <numbers>

#include "corsa/xodr/geometry.h"

namespace corsa::xodr {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kSeriesLimit = 1.5;
constexpr double kEps = 1e-17;

Fresnel fresnel_series(double x) {
  // ∫0^x exp(iπt²/2) dt = Σ_k (iπ/2)^k x^(2k+1) / (k! (2k+1)); even k feed C, odd k feed S.
  const double t = 0.5 * kPi * x * x;
  double power = x;  // t^k x / k!
  Fresnel result;
  for (int k = 0; k < 200; ++k) {
    const double term = power / (2.0 * k + 1.0);
    const int phase = k & 3;  // i^k: 1, i, -1, -i
    if (phase == 0) {
      result.c += term;
    } else if (phase == 1) {
      result.s += term;
    } else if (phase == 2) {
      result.c -= term;
    } else {
      result.s -= term;
    }
    if (std::abs(term) < kEps * (std::abs(result.c) + std::abs(result.s))) {
      break;
    }
    power *= t / (k + 1.0);
  }
  return result;
}

Fresnel fresnel_continued_fraction(double x) {
  using Complex = std::complex<double>;
  const double pix2 = kPi * x * x;
  constexpr double kTiny = 1e-300;
  Complex b(1.0, -pix2);
  Complex f = b;
  Complex c = b;
  Complex d = 0.0;
  for (int k = 1; k < 10000; ++k) {
    const double a = -(2.0 * k - 1.0) * (2.0 * k);
    b += 4.0;
    d = b + a * d;
    if (std::abs(d) < kTiny) {
      d = kTiny;
    }
    d = 1.0 / d;
    c = b + a / c;
    if (std::abs(c) < kTiny) {
      c = kTiny;
    }
    const Complex delta = c * d;
    f *= delta;
    if (std::abs(delta - 1.0) < 1e-16) {
      break;
    }
  }
  // e^{iπx²/2}: reduce x² modulo 4 first so that the phase stays accurate for large x.
  const double reduced = std::fmod(x * x, 4.0);
  const Complex phase = std::polar(1.0, 0.5 * kPi * reduced);
  const Complex value = Complex(0.5, 0.5) - x * phase / f;
  return Fresnel{value.real(), value.imag()};
}

}  // namespace

Fresnel fresnel(double x) {
  const double ax = std::abs(x);
  Fresnel result = ax < kSeriesLimit ? fresnel_series(ax) : fresnel_continued_fraction(ax);
  if (x < 0.0) {
    result.c = -result.c;
    result.s = -result.s;
  }
  return result;
}

}  // namespace corsa::xodr
