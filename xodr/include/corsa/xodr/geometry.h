#pragma once

// Reference-line evaluation of single planView records (OpenDRIVE 1.8 §7): each kind in its own
// source file; Map caches nothing here beyond the records themselves, so these are also the
// functions Map uses.

#include "corsa/xodr/model.h"

namespace corsa::xodr {

/// A point of the reference line: position (m), heading (rad, counter-clockwise from +x) and
/// curvature (1/m, positive turning left).
struct RefPoint {
  double x = 0.0;
  double y = 0.0;
  double hdg = 0.0;
  double curvature = 0.0;
};

/// Evaluates `geometry` at `ds` metres from its start. Outside 0 <= ds <= length the record goes
/// on straight along the tangent at its nearer end (curvature 0): a record describes the line
/// over its declared length only, and is read beyond it only where a map's records overlap or
/// leave gaps.
RefPoint evaluate_geometry(const Geometry& geometry, double ds);

/// Per-kind evaluation in the geometry's local frame (start at the origin, heading 0); the
/// result is then rotated/translated by evaluate_geometry.
RefPoint evaluate_line(double ds);
RefPoint evaluate_arc(const ArcGeometry& arc, double ds);
/// Clothoid whose curvature runs linearly from curv_start to curv_end over `length` (any start
/// and end curvature, either sign), exact to rounding: a piecewise Taylor series, or Fresnel
/// integrals for records that turn many times.
RefPoint evaluate_spiral(const SpiralGeometry& spiral, double length, double ds);
/// Deprecated cubic v(u) (§7.6.1): ds is arc length, so u is found by inverting the arc length.
RefPoint evaluate_poly3(const Poly3Geometry& poly, double ds);
/// Parametric cubic (§7.6.2): p = ds for pRange arcLength, p = ds / length for normalized.
RefPoint evaluate_param_poly3(const ParamPoly3Geometry& poly, double length, double ds);

/// Fresnel integrals C(x) = ∫0^x cos(πt²/2) dt and S(x) = ∫0^x sin(πt²/2) dt, to about 1e-15
/// (power series near 0, continued fraction beyond). Odd in x.
struct Fresnel {
  double c = 0.0;
  double s = 0.0;
};
Fresnel fresnel(double x);

/// Short name of a geometry kind: "line", "arc", "spiral", "poly3", "paramPoly3".
const char* geometry_kind_name(const GeometryShape& shape);

}  // namespace corsa::xodr
