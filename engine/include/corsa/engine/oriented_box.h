#pragma once

// Oriented bounding boxes of entities in the horizontal plane (OpenSCENARIO BoundingBox placed
// at the entity's pose, heading only), with a vertical extent: collisions, the free-space
// distances of the distance conditions, and the sweep metrics (free distance, time to contact),
// all from this one implementation. Map frame, metres, seconds.

#include <cmath>
#include <optional>

#include "corsa/core/vec.h"
#include "corsa/engine/entity_state.h"
#include "corsa/engine/world_snapshot.h"

namespace corsa::engine {

struct OrientedBox {
  double cx = 0.0, cy = 0.0;  ///< centre, m
  double half_length = 0.0, half_width = 0.0;
  double cos_h = 1.0, sin_h = 0.0;  ///< box axes: (cos, sin) forward, (-sin, cos) left
  double z_min = 0.0, z_max = 0.0;
};

/// `box` (in the entity frame) placed at `pose`: heading and position only.
OrientedBox box_of(const Box& box, const Pose& pose);

/// The farthest (m) a point of `box` lies from the entity's reference point, horizontally: two
/// boxes closer than some distance have reference points closer than that plus both reaches.
double box_reach(const Box& box);

/// An entity's velocity in the map frame (m/s): its speed along the heading and its lateral
/// speed across it (to the left). Inline: conditions ask for it every step, and the compiler
/// then shares one sincos between the two components.
inline Vec2 velocity_of(const EntityState& state) {
  const double c = std::cos(state.pose.h), s = std::sin(state.pose.h);
  return {state.speed * c - state.lateral_speed * s, state.speed * s + state.lateral_speed * c};
}

/// Separating-axis test on the four box axes, plus the vertical extents.
bool overlap(const OrientedBox& a, const OrientedBox& b);

/// Smallest horizontal distance (m) between two boxes, 0 when they overlap in the plane: the
/// least distance over every corner of one box to every edge of the other, each distance a
/// hypot.
double box_distance(const OrientedBox& a, const OrientedBox& b);
/// Smallest horizontal distance (m) from a box to a point, 0 inside.
double box_point_distance(const OrientedBox& box, double x, double y);

/// A lower bound of box_distance(a, b) (m), cheap enough to skip the exact distance with: the
/// centre distance less both half diagonals, less a margin far above the rounding of either
/// computation, so that it never exceeds the box_distance of the same boxes.
double box_distance_lower_bound(const OrientedBox& a, const OrientedBox& b);

/// The time (s) from now until the boxes first touch in the plane if they keep the velocities
/// `va` and `vb` (m/s, map frame) and their headings: 0 when they overlap now, nothing when they
/// never would. Exact for this constant-velocity prediction: the separating axis test on the
/// four edge normals, each axis' projections moving linearly in time.
std::optional<double> time_to_contact(const OrientedBox& a, Vec2 va, const OrientedBox& b, Vec2 vb);

/// The box's extent along the unit axis (ux, uy): [low, high] of the dot products of its
/// corners with the axis.
struct Interval {
  double low = 0.0;
  double high = 0.0;
};
Interval project(const OrientedBox& box, double ux, double uy);

}  // namespace corsa::engine
