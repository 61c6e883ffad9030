// Clothoid (OpenDRIVE 1.8 §7.4): curvature k(σ) = k0 + c σ with c = (k1 - k0) / length, heading
// θ(σ) = k0 σ + c σ²/2. Completing the square, θ = (c/2)(σ + k0/c)² - k0²/(2c), so the position
// is a difference of Fresnel integrals in w = (σ + k0/c)·sqrt(|c|/π):
//   ∫0^ds e^{iθ} dσ = e^{-i k0²/(2c)} sqrt(π/|c|) [ΔC + i sign(c) ΔS].
// When k0/c is huge (a nearly constant curvature), both w are large and the difference loses
// digits, so such spirals are integrated by Gauss-Legendre quadrature instead, in pieces short
// enough (≤ 0.5 rad of heading each) that the quadrature is exact to rounding.

#include <array>
#include <cmath>
#include <numbers>

#include "corsa/xodr/geometry.h"

namespace corsa::xodr {
namespace {

constexpr double kMaxFresnelArgument = 8.0;

// 10-point Gauss-Legendre nodes and weights on [-1, 1].
constexpr std::array<double, 5> kNodes = {0.1488743389816312, 0.4333953941292472,
                                          0.6794095682990244, 0.8650633666889845,
                                          0.9739065285171717};
constexpr std::array<double, 5> kWeights = {0.2955242247147529, 0.2692667193099963,
                                            0.2190863625159820, 0.1494513491505806,
                                            0.0666713443086881};

RefPoint spiral_by_quadrature(double k0, double c, double ds) {
  const double turn = std::abs(k0 * ds) + 0.5 * std::abs(c) * ds * ds;
  const int pieces = 1 + static_cast<int>(turn / 0.5);
  const double step = ds / pieces;
  double x = 0.0;
  double y = 0.0;
  for (int piece = 0; piece < pieces; ++piece) {
    const double mid = (piece + 0.5) * step;
    for (size_t i = 0; i < kNodes.size(); ++i) {
      for (const double sign : {-1.0, 1.0}) {
        const double sigma = mid + sign * kNodes[i] * 0.5 * step;
        const double theta = sigma * (k0 + 0.5 * c * sigma);
        x += kWeights[i] * std::cos(theta);
        y += kWeights[i] * std::sin(theta);
      }
    }
  }
  x *= 0.5 * step;
  y *= 0.5 * step;
  return RefPoint{x, y, ds * (k0 + 0.5 * c * ds), k0 + c * ds};
}

}  // namespace

RefPoint evaluate_spiral(const SpiralGeometry& spiral, double length, double ds) {
  const double k0 = spiral.curv_start;
  const double c = length > 0.0 ? (spiral.curv_end - k0) / length : 0.0;
  if (c == 0.0) {
    return evaluate_arc(ArcGeometry{k0}, ds);
  }
  const double scale = std::sqrt(std::abs(c) / std::numbers::pi);
  const double u0 = k0 / c;
  const double w0 = u0 * scale;
  const double w1 = (u0 + ds) * scale;
  if (std::abs(w0) > kMaxFresnelArgument || std::abs(w1) > kMaxFresnelArgument) {
    return spiral_by_quadrature(k0, c, ds);
  }
  const Fresnel f0 = fresnel(w0);
  const Fresnel f1 = fresnel(w1);
  const double sign = c > 0.0 ? 1.0 : -1.0;
  const double dc = (f1.c - f0.c) / scale;
  const double dsn = sign * (f1.s - f0.s) / scale;
  const double phase = -0.5 * k0 * u0;  // -k0²/(2c)
  const double cp = std::cos(phase);
  const double sp = std::sin(phase);
  return RefPoint{cp * dc - sp * dsn, sp * dc + cp * dsn, ds * (k0 + 0.5 * c * ds), k0 + c * ds};
}

}  // namespace corsa::xodr
