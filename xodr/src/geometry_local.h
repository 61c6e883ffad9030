#pragma once

// A planView record evaluated in its own frame, and the transform to map coordinates with the
// record's heading cosine/sine precomputed (Map caches them: most lookups are on lines, which
// then need no trigonometry at all). Private to corsa_xodr.

#include "corsa/xodr/geometry.h"

namespace corsa::xodr::detail {

/// The record's shape at ds, start at the origin heading along +x.
RefPoint evaluate_local(const Geometry& geometry, double ds);

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
