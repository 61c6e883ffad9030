#pragma once

// Oriented bounding boxes of entities in the horizontal plane (OpenSCENARIO BoundingBox placed
// at the entity's pose, heading only), with a vertical extent: for collisions and free-space
// distances.

#include "corsa/engine/world_snapshot.h"

namespace corsa::engine::detail {

struct OrientedBox {
  double cx = 0.0, cy = 0.0;  ///< centre, m
  double half_length = 0.0, half_width = 0.0;
  double cos_h = 1.0, sin_h = 0.0;  ///< box axes: (cos, sin) forward, (-sin, cos) left
  double z_min = 0.0, z_max = 0.0;
};

/// `box` (in the entity frame) placed at `pose`: heading and position only.
OrientedBox box_of(const Box& box, const Pose& pose);

/// Separating-axis test on the four box axes, plus the vertical extents.
bool overlap(const OrientedBox& a, const OrientedBox& b);

/// Smallest horizontal distance (m) between two boxes, 0 when they overlap.
double box_distance(const OrientedBox& a, const OrientedBox& b);
/// Smallest horizontal distance (m) from a box to a point, 0 inside.
double box_point_distance(const OrientedBox& box, double x, double y);

/// The box's extent along the unit axis (ux, uy): [low, high] of the dot products of its
/// corners with the axis.
struct Interval {
  double low = 0.0;
  double high = 0.0;
};
Interval project(const OrientedBox& box, double ux, double uy);

}  // namespace corsa::engine::detail
