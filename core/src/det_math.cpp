#include "corsa/core/det_math.h"

#include <cmath>
#include <limits>

namespace corsa::det {
namespace {

// ln 2 split so that k * kLn2Hi is exact for |k| < 2^11 (Cody-Waite reduction).
constexpr double kLn2Hi = 6.93147180369123816490e-01;
constexpr double kLn2Lo = 1.90821492927058770002e-10;
constexpr double kInvLn2 = 1.44269504088896338700e+00;

}  // namespace

double log(double x) {
  if (std::isnan(x) || x < 0.0) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  if (x == 0.0) {
    return -std::numeric_limits<double>::infinity();
  }
  if (std::isinf(x)) {
    return x;
  }
  int e = 0;
  double m = std::frexp(x, &e);  // exact: x = m * 2^e, m in [0.5, 1)
  if (m < 0.70710678118654752440) {
    m *= 2.0;  // exact
    e -= 1;
  }
  // m in [sqrt(1/2), sqrt(2)): log(m) = 2 atanh(s), s = (m - 1) / (m + 1), |s| < 0.1716.
  const double f = m - 1.0;
  const double s = f / (m + 1.0);
  const double s2 = s * s;
  // Series 2(s + s^3/3 + s^5/5 + ...); s^2 < 0.0295 so 11 terms reach 1e-19 relative.
  double series = 1.0 / 23.0;
  for (int k = 21; k >= 3; k -= 2) {
    series = series * s2 + 1.0 / k;
  }
  const double log_m = 2.0 * s + 2.0 * s * s2 * series;
  return e * kLn2Hi + (log_m + e * kLn2Lo);
}

double exp(double x) {
  if (std::isnan(x)) {
    return x;
  }
  if (x > 709.782712893384) {
    return std::numeric_limits<double>::infinity();
  }
  if (x < -745.2) {
    return 0.0;
  }
  // x = k ln2 + r, |r| <= ln2 / 2.
  const double k = std::nearbyint(x * kInvLn2);
  const double r = (x - k * kLn2Hi) - k * kLn2Lo;
  // Taylor series of e^r to r^18 / 18!: |r| < 0.347, remainder < 1e-20.
  double sum = 1.0;
  for (int n = 18; n >= 1; --n) {
    sum = 1.0 + sum * r / n;
  }
  return std::ldexp(sum, static_cast<int>(k));  // exact scaling (denormals round once)
}

double lgamma(double x) {
  if (!(x > 0.0)) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  // Shift x up to >= 10 with the recurrence Gamma(x+1) = x Gamma(x), then Stirling's series.
  double shift = 0.0;
  while (x < 10.0) {
    shift += log(x);
    x += 1.0;
  }
  constexpr double kHalfLog2Pi = 0.91893853320467274178;
  const double inv = 1.0 / x;
  const double inv2 = inv * inv;
  // Bernoulli terms B2n / (2n (2n-1) x^(2n-1)).
  const double series =
      inv *
      (1.0 / 12.0 -
       inv2 * (1.0 / 360.0 -
               inv2 * (1.0 / 1260.0 -
                       inv2 * (1.0 / 1680.0 - inv2 * (1.0 / 1188.0 - inv2 * (691.0 / 360360.0))))));
  return (x - 0.5) * log(x) - x + kHalfLog2Pi + series - shift;
}

namespace {

// pi/2 in three parts for range reduction.
constexpr double kPio2Hi = 1.57079632673412561417e+00;
constexpr double kPio2Mid = 6.07710050650619224932e-11;
constexpr double kPio2Lo = 2.02226624879595063154e-21;
constexpr double kTwoOverPi = 6.36619772367581382433e-01;

// sin and cos on |r| <= pi/4 by Taylor series (remainder < 1e-18).
double sin_kernel(double r) {
  const double r2 = r * r;
  double sum = 1.0;
  for (int n = 21; n >= 3; n -= 2) {
    sum = 1.0 - sum * r2 / (n * (n - 1));
  }
  return r * sum;
}

double cos_kernel(double r) {
  const double r2 = r * r;
  double sum = 1.0;
  for (int n = 22; n >= 2; n -= 2) {
    sum = 1.0 - sum * r2 / (n * (n - 1));
  }
  return sum;
}

// Returns r in [-pi/4, pi/4] and the quadrant of x.
double reduce(double x, int& quadrant) {
  const double k = std::nearbyint(x * kTwoOverPi);
  quadrant = static_cast<int>(std::fmod(k, 4.0));
  if (quadrant < 0) {
    quadrant += 4;
  }
  return ((x - k * kPio2Hi) - k * kPio2Mid) - k * kPio2Lo;
}

// sin(r + q pi/2) for the reduced argument r, from the kernels.
double sin_in_quadrant(double r, int q) {
  switch (q & 3) {
    case 0:
      return sin_kernel(r);
    case 1:
      return cos_kernel(r);
    case 2:
      return -sin_kernel(r);
    default:
      return -cos_kernel(r);
  }
}

}  // namespace

double sin(double x) {
  if (!std::isfinite(x)) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  int q = 0;
  const double r = reduce(x, q);
  return sin_in_quadrant(r, q);
}

double cos(double x) {
  if (!std::isfinite(x)) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  int q = 0;
  const double r = reduce(x, q);
  return sin_in_quadrant(r, q + 1);  // cos x = sin(x + pi/2)
}

}  // namespace corsa::det
