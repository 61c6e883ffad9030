#pragma once

// Parts of Map's answers computed alone, to the bit as Map gives them, for callers that read
// only those parts: they skip what only the rest needs (the reference line's point and heading,
// their trigonometry).

#include <cstddef>

#include "corsa/xodr/map.h"

namespace corsa::xodr {

/// The road surface's part of a WorldPose: z, pitch and roll.
struct SurfacePose {
  double z = 0.0;
  double p = 0.0;
  double r = 0.0;
};

/// map.reference(road, s).curvature, without the heading (no atan2 on a paramPoly3).
double reference_curvature(const Map& map, size_t road, double s);

/// map.world_pose(road, s, t, h)'s z, p and r, without the reference line's point and heading.
SurfacePose surface_pose(const Map& map, size_t road, double s, double t, double h = 0.0);

}  // namespace corsa::xodr
