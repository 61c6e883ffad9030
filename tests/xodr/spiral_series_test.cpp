// The clothoid evaluation (a piecewise Taylor series, xodr/src/geometry_spiral.cpp) against two
// independent references at many points: Gauss-Legendre quadrature in long double, and the closed
// form through Fresnel integrals that it replaced.

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <vector>

#include "corsa/xodr/geometry.h"

using namespace corsa::xodr;

namespace {

/// Gauss-Legendre nodes and weights on [-1, 1] in long double (Newton on P_n).
struct GaussRule {
  std::vector<long double> nodes;
  std::vector<long double> weights;
};

GaussRule gauss_rule(int n) {
  GaussRule rule;
  for (int i = 1; i <= n; ++i) {
    long double x = std::cos(std::numbers::pi_v<long double> * (i - 0.25L) / (n + 0.5L));
    long double derivative = 1.0L;
    for (int iteration = 0; iteration < 100; ++iteration) {
      long double p0 = 1.0L;
      long double p1 = x;
      for (int k = 2; k <= n; ++k) {
        const long double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      derivative = n * (x * p1 - p0) / (x * x - 1.0L);
      const long double step = p1 / derivative;
      x -= step;
      if (std::abs(step) < 1e-19L) {
        break;
      }
    }
    rule.nodes.push_back(x);
    rule.weights.push_back(2.0L / ((1.0L - x * x) * derivative * derivative));
  }
  return rule;
}

/// ∫0^ds e^{i(k0 σ + c σ²/2)} dσ by 20-point Gauss-Legendre on pieces turning ≤ 0.5 rad, in long
/// double: exact to well below double rounding.
RefPoint quadrature_reference(double k0, double c, double ds) {
  static const GaussRule rule = gauss_rule(20);
  const long double turn = std::abs(k0 * ds) + 0.5L * std::abs(c) * ds * ds;
  const int pieces = 1 + static_cast<int>(turn / 0.5L);
  const long double step = static_cast<long double>(ds) / pieces;
  long double x = 0.0L;
  long double y = 0.0L;
  for (int piece = 0; piece < pieces; ++piece) {
    const long double mid = (piece + 0.5L) * step;
    for (size_t i = 0; i < rule.nodes.size(); ++i) {
      const long double sigma = mid + 0.5L * step * rule.nodes[i];
      const long double theta = sigma * (k0 + 0.5L * c * sigma);
      x += rule.weights[i] * std::cos(theta);
      y += rule.weights[i] * std::sin(theta);
    }
  }
  return RefPoint{static_cast<double>(0.5L * step * x), static_cast<double>(0.5L * step * y),
                  ds * (k0 + 0.5 * c * ds), k0 + c * ds};
}

/// The closed form through Fresnel integrals (the previous evaluation).
RefPoint fresnel_reference(double k0, double c, double ds) {
  const double scale = std::sqrt(std::abs(c) / std::numbers::pi);
  const Fresnel f0 = fresnel(k0 / c * scale);
  const Fresnel f1 = fresnel((k0 / c + ds) * scale);
  const double sign = c > 0.0 ? 1.0 : -1.0;
  const double dc = (f1.c - f0.c) / scale;
  const double dsn = sign * (f1.s - f0.s) / scale;
  const double phase = -0.5 * k0 * k0 / c;
  return RefPoint{std::cos(phase) * dc - std::sin(phase) * dsn,
                  std::sin(phase) * dc + std::cos(phase) * dsn, 0.0, 0.0};
}

struct Case {
  double k0, k1, length;
};

// Road-like spirals, long ones, sharp ones, sign changes, nearly-arcs and loops that turn many
// times (the latter take the closed-form branch), and tight clothoids turning hundreds of radians
// (closed form with large Fresnel arguments; they once made a map load take seconds).
const Case kCases[] = {
    {0.0, 0.02, 50.0},    {0.02, 0.0, 50.0},     {0.0, -0.004, 250.0},  {-0.01, 0.03, 80.0},
    {0.02, -0.02, 60.0},  {0.0, 1.0 / 30, 90.0}, {0.0, 0.001, 2000.0},  {0.0005, 0.0006, 1500.0},
    {0.1, 0.1000001, 30}, {0.3, 0.5, 100.0},     {-0.8, 0.8, 12.0},     {0.0, 2.0, 3.0},
    {1.5, -0.5, 8.0},     {0.0, 0.2, 400.0},     {-0.05, -0.25, 200.0}, {5.0, 6.0, 20.0},
    {1e-7, 2e-7, 5000.0}, {0.0, 1e-9, 10000.0},  {0.12, 0.1, 1000.0},   {0.0, 0.05, 700.0},
    {10.0, 0.0, 53.0},    {-8.0, 2.0, 40.0},
};

}  // namespace

TEST_CASE("spiral positions agree with long-double quadrature to rounding at many points",
          "[xodr][geometry][spiral]") {
  for (const Case& k : kCases) {
    const double c = (k.k1 - k.k0) / k.length;
    for (int i = 0; i <= 24; ++i) {
      const double ds = k.length * i / 24.0;
      const RefPoint ours = evaluate_spiral(SpiralGeometry{k.k0, k.k1}, k.length, ds);
      const RefPoint ref = quadrature_reference(k.k0, c, ds);
      INFO("k0 " << k.k0 << " k1 " << k.k1 << " L " << k.length << " ds " << ds);
      // Per metre travelled: ~50 roundings (the worst seen is ~3).
      const double tolerance = 1e-14 * std::max(1.0, ds);
      CHECK(std::abs(ours.x - ref.x) <= tolerance);
      CHECK(std::abs(ours.y - ref.y) <= tolerance);
      CHECK(ours.hdg == ref.hdg);
      CHECK(ours.curvature == ref.curvature);
    }
  }
}

TEST_CASE("spiral positions agree with the Fresnel closed form", "[xodr][geometry][spiral]") {
  for (const Case& k : kCases) {
    const double c = (k.k1 - k.k0) / k.length;
    const double scale = std::sqrt(std::abs(c) / std::numbers::pi);
    // The closed form is only accurate while the Fresnel arguments stay moderate.
    if (std::abs(k.k0 / c * scale) > 8.0 || std::abs((k.k0 / c + k.length) * scale) > 8.0) {
      continue;
    }
    for (int i = 0; i <= 24; ++i) {
      const double ds = k.length * i / 24.0;
      const RefPoint ours = evaluate_spiral(SpiralGeometry{k.k0, k.k1}, k.length, ds);
      const RefPoint old = fresnel_reference(k.k0, c, ds);
      INFO("k0 " << k.k0 << " k1 " << k.k1 << " L " << k.length << " ds " << ds);
      // The closed form divides Fresnel differences by sqrt(|c|/π): its own rounding grows as
      // 1/scale.
      const double tolerance = 1e-12 * std::max(1.0, ds) + 4e-16 / scale;
      CHECK(std::abs(ours.x - old.x) <= tolerance);
      CHECK(std::abs(ours.y - old.y) <= tolerance);
    }
  }
}

TEST_CASE("spirals evaluated backwards from the start mirror the forward evaluation",
          "[xodr][geometry][spiral]") {
  // Extrapolation before the start (ds < 0) follows the same clothoid.
  const SpiralGeometry spiral{0.01, 0.03};
  const double c = (0.03 - 0.01) / 100.0;
  for (const double ds : {-1.0, -10.0, -60.0}) {
    const RefPoint ours = evaluate_spiral(spiral, 100.0, ds);
    const RefPoint ref = quadrature_reference(0.01, c, ds);
    CHECK(std::abs(ours.x - ref.x) <= 1e-13 * std::abs(ds));
    CHECK(std::abs(ours.y - ref.y) <= 1e-13 * std::abs(ds));
  }
}
