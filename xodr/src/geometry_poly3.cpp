// Polynomial reference lines (OpenDRIVE 1.8 §7.6).
// poly3 (deprecated, §7.6.1): v(u) = a + b u + c u² + d u³ in the local u/v frame; the record's
//   s runs along the curve, so u for a given ds solves arc length L(u) = ds (Newton, with L by
//   Gauss-Legendre quadrature).
// paramPoly3 (§7.6.2): u(p), v(p) cubics; p = ds for pRange="arcLength" (p runs over
//   [0, length]) and p = ds / length for pRange="normalized" (p over [0, 1]), exactly as the
//   standard defines the parameter; no re-parametrisation by true arc length.

#include <array>
#include <cmath>

#include "corsa/xodr/geometry.h"
#include "geometry_local.h"

namespace corsa::xodr {
namespace {

double poly3_slope(const Poly3Geometry& p, double u) {
  return p.b + u * (2.0 * p.c + 3.0 * p.d * u);
}

/// Arc length of v(u) from 0 to u: ∫ sqrt(1 + v'²), in pieces of at most 20 m of u.
double poly3_arc_length(const Poly3Geometry& p, double u) {
  const int pieces = 1 + static_cast<int>(std::abs(u) / 20.0);
  const double step = u / pieces;
  double total = 0.0;
  for (int piece = 0; piece < pieces; ++piece) {
    const double mid = (piece + 0.5) * step;
    for (size_t i = 0; i < detail::kGaussNodes.size(); ++i) {
      for (const double sign : {-1.0, 1.0}) {
        const double slope = poly3_slope(p, mid + sign * detail::kGaussNodes[i] * 0.5 * step);
        total += detail::kGaussWeights[i] * std::sqrt(1.0 + slope * slope);
      }
    }
  }
  return total * 0.5 * step;
}

}  // namespace

RefPoint evaluate_poly3(const Poly3Geometry& poly, double ds) {
  double u = ds;
  for (int iteration = 0; iteration < 50; ++iteration) {
    const double slope = poly3_slope(poly, u);
    const double step = (poly3_arc_length(poly, u) - ds) / std::sqrt(1.0 + slope * slope);
    u -= step;
    if (std::abs(step) < 1e-12 * (1.0 + std::abs(u))) {
      break;
    }
  }
  const double v = poly.a + u * (poly.b + u * (poly.c + u * poly.d));
  const double slope = poly3_slope(poly, u);
  const double second = 2.0 * poly.c + 6.0 * poly.d * u;
  const double norm = 1.0 + slope * slope;
  return RefPoint{u, v, std::atan(slope), second / (norm * std::sqrt(norm))};
}

namespace {

/// A paramPoly3's parameter at ds and its first derivatives (du/dp, dv/dp) there.
struct ParamTangent {
  double p = 0.0;
  double du = 0.0;
  double dv = 0.0;
};

ParamTangent param_tangent(const ParamPoly3Geometry& poly, double length, double ds) {
  const double p = poly.range == ParamRange::kNormalized ? (length > 0.0 ? ds / length : 0.0) : ds;
  return ParamTangent{p, poly.bu + p * (2.0 * poly.cu + 3.0 * poly.du * p),
                      poly.bv + p * (2.0 * poly.cv + 3.0 * poly.dv * p)};
}

double param_curvature(const ParamPoly3Geometry& poly, const ParamTangent& tangent) {
  const double p = tangent.p;
  const double du = tangent.du;
  const double dv = tangent.dv;
  const double ddu = 2.0 * poly.cu + 6.0 * poly.du * p;
  const double ddv = 2.0 * poly.cv + 6.0 * poly.dv * p;
  const double speed2 = du * du + dv * dv;
  return speed2 > 0.0 ? (du * ddv - dv * ddu) / (speed2 * std::sqrt(speed2)) : 0.0;
}

}  // namespace

RefPoint evaluate_param_poly3(const ParamPoly3Geometry& poly, double length, double ds) {
  const ParamTangent tangent = param_tangent(poly, length, ds);
  const double p = tangent.p;
  const double u = poly.au + p * (poly.bu + p * (poly.cu + p * poly.du));
  const double v = poly.av + p * (poly.bv + p * (poly.cv + p * poly.dv));
  return RefPoint{u, v, std::atan2(tangent.dv, tangent.du), param_curvature(poly, tangent)};
}

namespace detail {

double param_poly3_curvature(const ParamPoly3Geometry& poly, double length, double ds) {
  return param_curvature(poly, param_tangent(poly, length, ds));
}

}  // namespace detail

}  // namespace corsa::xodr
