#pragma once

// A planView record evaluated in its own frame, and the transform to map coordinates with the
// record's heading cosine/sine precomputed (Map caches them: most lookups are on lines, which
// then need no trigonometry at all). Private to corsa_xodr.

#include <array>

#include "corsa/xodr/geometry.h"

namespace corsa::xodr::detail {

/// 10-point Gauss-Legendre quadrature on [-1, 1]: the positive nodes (the others are their
/// negatives) and their weights; exact for polynomials up to degree 19.
inline constexpr std::array<double, 5> kGaussNodes = {0.1488743389816312, 0.4333953941292472,
                                                      0.6794095682990244, 0.8650633666889845,
                                                      0.9739065285171717};
inline constexpr std::array<double, 5> kGaussWeights = {0.2955242247147529, 0.2692667193099963,
                                                        0.2190863625159820, 0.1494513491505806,
                                                        0.0666713443086881};

/// The record's shape at ds, start at the origin heading along +x.
RefPoint evaluate_local(const Geometry& geometry, double ds);

/// evaluate_local(geometry, ds).curvature, to the bit, without what only the point and heading
/// need (paramPoly3's atan2).
double local_curvature(const Geometry& geometry, double ds);

/// The curvature of a paramPoly3 at ds, as evaluate_param_poly3 computes it.
double param_poly3_curvature(const ParamPoly3Geometry& poly, double length, double ds);

/// A local point with the cosine and sine of its local heading (exact from the arc formulas,
/// 1 and 0 on lines), so that callers needing the tangent need no further trigonometry.
struct LocalFrame {
  RefPoint point;
  double cos_h = 1.0;
  double sin_h = 0.0;
};
LocalFrame evaluate_local_frame(const Geometry& geometry, double ds);

/// A spiral record's local frame, with the heading's cosine and sine from the same series as the
/// position (geometry_spiral.cpp) rather than from trigonometry of the heading.
LocalFrame evaluate_spiral_frame(const SpiralGeometry& spiral, double length, double ds);

inline RefPoint to_world(const Geometry& geometry, double cos_h, double sin_h,
                         const RefPoint& local) {
  return RefPoint{geometry.x + cos_h * local.x - sin_h * local.y,
                  geometry.y + sin_h * local.x + cos_h * local.y, geometry.hdg + local.hdg,
                  local.curvature};
}

}  // namespace corsa::xodr::detail
