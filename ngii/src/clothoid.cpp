#include "clothoid.h"

#include <algorithm>
#include <cmath>

namespace corsa::ngii::detail {
namespace {

// 3-point Gauss-Legendre on [0, 1]: nodes and weights.
constexpr double kNode[3] = {0.5 - 0.3872983346207417, 0.5, 0.5 + 0.3872983346207417};
constexpr double kWeight[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
constexpr double kMaxTurn = 0.2;  // rad per panel

struct Integrator {
  const Clothoid& curve;
  bool derivatives;
  double s = 0.0;
  double x = 0.0, y = 0.0;
  double ax = 0.0, ay = 0.0;  // ∫ v e⊥(θ(v)) dv
  double bx = 0.0, by = 0.0;  // ∫ v²/2 e⊥(θ(v)) dv

  double panel_length() const {
    // Heading change over a panel stays below 0.2 rad (3-point Gauss-Legendre error below
    // 1e-10 m per metre), and panels are at most 2 m.
    const double k = std::max(std::abs(curve.curvature(s)), std::abs(curve.curvature(s + 2.0)));
    return k * 2.0 > kMaxTurn ? kMaxTurn / k : 2.0;
  }

  void advance(double target) {
    while (s < target) {
      const double h = std::min(panel_length(), target - s);
      // One sincos per panel; the nodes rotate from the panel start by at most 0.2 rad, where
      // these Taylor series are exact to rounding (the first omitted term is below 3e-14).
      const double base = curve.heading(s);
      const double base_c = std::cos(base);
      const double base_s = std::sin(base);
      for (int i = 0; i < 3; ++i) {
        const double v = s + kNode[i] * h;
        const double delta = curve.heading(v) - base;
        const double d2 = delta * delta;
        const double dc =
            1.0 - d2 / 2.0 * (1.0 - d2 / 12.0 * (1.0 - d2 / 30.0 * (1.0 - d2 / 56.0)));
        const double ds =
            delta * (1.0 - d2 / 6.0 * (1.0 - d2 / 20.0 * (1.0 - d2 / 42.0 * (1.0 - d2 / 72.0))));
        const double c = base_c * dc - base_s * ds;
        const double sn = base_s * dc + base_c * ds;
        const double w = kWeight[i] * h;
        x += w * c;
        y += w * sn;
        if (derivatives) {
          ax += w * v * -sn;
          ay += w * v * c;
          bx += w * 0.5 * v * v * -sn;
          by += w * 0.5 * v * v * c;
        }
      }
      s += h;
    }
  }
};

}  // namespace

void evaluate_clothoid(const Clothoid& curve, const std::vector<double>& s_sorted,
                       std::vector<ClothoidPoint>& out, bool derivatives) {
  out.resize(s_sorted.size());
  Integrator integrator{curve, derivatives};
  for (size_t i = 0; i < s_sorted.size(); ++i) {
    integrator.advance(s_sorted[i]);
    ClothoidPoint& p = out[i];
    p.x = curve.x0 + integrator.x;
    p.y = curve.y0 + integrator.y;
    p.theta = curve.heading(std::max(s_sorted[i], 0.0));
    p.dx_dk0 = integrator.ax;
    p.dy_dk0 = integrator.ay;
    p.dx_dk1 = integrator.bx;
    p.dy_dk1 = integrator.by;
  }
}

ClothoidPoint clothoid_at(const Clothoid& curve, double s) {
  std::vector<ClothoidPoint> out;
  evaluate_clothoid(curve, std::vector<double>{s}, out, false);
  return out.front();
}

}  // namespace corsa::ngii::detail
