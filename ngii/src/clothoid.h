#pragma once

// Forward evaluation of a clothoid (curvature k0 + k1 s) at increasing arc lengths, with the
// derivatives of the position by the start heading and both curvature parameters, for the
// Gauss-Newton fit in plan_view_fit.cpp. Integrates cos/sin of the heading with 3-point
// Gauss-Legendre on short panels (heading change per panel <= 0.2 rad, so the position error is
// below 1e-10 m per metre), which avoids Fresnel-integral special cases (k1 = 0, tiny k1, sign
// changes).

#include <vector>

namespace corsa::ngii::detail {

struct Clothoid {
  double x0 = 0.0;
  double y0 = 0.0;
  double theta0 = 0.0;  ///< heading at s = 0 (rad)
  double k0 = 0.0;      ///< curvature at s = 0 (1/m)
  double k1 = 0.0;      ///< curvature rate (1/m^2)

  double heading(double s) const { return theta0 + s * (k0 + 0.5 * k1 * s); }
  double curvature(double s) const { return k0 + k1 * s; }
};

struct ClothoidPoint {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
  /// d(x, y)/d k0 and d(x, y)/d k1 (only when requested).
  double dx_dk0 = 0.0, dy_dk0 = 0.0;
  double dx_dk1 = 0.0, dy_dk1 = 0.0;
};

/// Evaluates `curve` at every s of `s_sorted` (non-decreasing, >= 0) into `out`.
void evaluate_clothoid(const Clothoid& curve, const std::vector<double>& s_sorted,
                       std::vector<ClothoidPoint>& out, bool derivatives);

/// Single point (no derivatives).
ClothoidPoint clothoid_at(const Clothoid& curve, double s);

}  // namespace corsa::ngii::detail
