#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "corsa/xodr/geometry.h"

namespace {

/// Independent reference: composite Simpson rule on cos/sin(πt²/2), fine enough for ~1e-11.
corsa::xodr::Fresnel simpson_fresnel(double x) {
  const int n = 40000;
  const double h = x / n;
  double c = 0.0;
  double s = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double t = i * h;
    const double w = (i == 0 || i == n) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    const double phase = 0.5 * std::numbers::pi * t * t;
    c += w * std::cos(phase);
    s += w * std::sin(phase);
  }
  return {c * h / 3.0, s * h / 3.0};
}

}  // namespace

TEST_CASE("Fresnel integrals match tabulated values", "[xodr][fresnel]") {
  using corsa::xodr::fresnel;
  // Abramowitz & Stegun table 7.7 / DLMF values.
  CHECK(fresnel(0.5).c == Approx(0.4923442258714464).margin(1e-14));
  CHECK(fresnel(0.5).s == Approx(0.0647324328599993).margin(1e-14));
  CHECK(fresnel(1.0).c == Approx(0.7798934003768228).margin(1e-14));
  CHECK(fresnel(1.0).s == Approx(0.4382591473903548).margin(1e-14));
  CHECK(fresnel(2.0).c == Approx(0.4882534060753408).margin(1e-14));
  CHECK(fresnel(2.0).s == Approx(0.3434156783636982).margin(1e-14));
  CHECK(fresnel(0.0).c == 0.0);
  CHECK(fresnel(0.0).s == 0.0);
}

TEST_CASE("Fresnel integrals agree with numerical integration on both branches",
          "[xodr][fresnel]") {
  for (const double x : {0.1, 0.7, 1.2, 1.49, 1.51, 2.3, 3.0, 4.5, 6.0, 8.0}) {
    const auto exact = simpson_fresnel(x);
    const auto ours = corsa::xodr::fresnel(x);
    INFO("x = " << x);
    CHECK(ours.c == Approx(exact.c).margin(1e-10));
    CHECK(ours.s == Approx(exact.s).margin(1e-10));
  }
}

TEST_CASE("Fresnel integrals are odd and continuous where the method switches", "[xodr][fresnel]") {
  using corsa::xodr::fresnel;
  for (const double x : {0.3, 1.7, 5.0}) {
    CHECK(fresnel(-x).c == -fresnel(x).c);
    CHECK(fresnel(-x).s == -fresnel(x).s);
  }
  // Across x = 1.5 the values change by the derivative (C' = cos(πx²/2), S' = sin(πx²/2))
  // times the step, and nothing more.
  const double h = 1e-9;
  const auto below = fresnel(1.5 - h);
  const auto above = fresnel(1.5 + h);
  const double phase = 0.5 * std::numbers::pi * 2.25;
  CHECK(std::abs(above.c - below.c - 2.0 * h * std::cos(phase)) < 1e-14);
  CHECK(std::abs(above.s - below.s - 2.0 * h * std::sin(phase)) < 1e-14);
}

TEST_CASE("Fresnel integrals approach one half for large arguments", "[xodr][fresnel]") {
  for (const double x : {50.0, 100.0, 1000.0}) {
    const auto f = corsa::xodr::fresnel(x);
    // Asymptotically C = 1/2 + sin(πx²/2)/(πx) + O(x^-3), S = 1/2 - cos(πx²/2)/(πx) + ...
    const double phase = 0.5 * std::numbers::pi * std::fmod(x * x, 4.0);
    CHECK(f.c == Approx(0.5 + std::sin(phase) / (std::numbers::pi * x)).margin(1.0 / (x * x * x)));
    CHECK(f.s == Approx(0.5 - std::cos(phase) / (std::numbers::pi * x)).margin(1.0 / (x * x * x)));
  }
}
