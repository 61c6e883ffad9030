#pragma once

// Internal: an entity's bounding box seen from above (a rectangle in map x/y, metres) moving
// with a constant velocity, for the free-space distance and time-to-collision metrics.

#include <array>
#include <optional>

#include "corsa/engine/entity_state.h"

namespace corsa::sweep::detail {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};

struct Footprint {
  Vec2 center;  ///< box centre, m
  Vec2 axis;    ///< unit vector along the heading
  double half_length = 0.0;
  double half_width = 0.0;
  Vec2 velocity;  ///< m/s in map coordinates

  std::array<Vec2, 4> corners() const;
};

/// The footprint of an entity's box at its current state: the box centre offset (entity frame)
/// rotated by the heading; velocity from speed along and lateral speed across the heading.
/// Pitch, roll and the box height are ignored.
Footprint footprint_of(const engine::EntityInfo& info, const engine::EntityState& state);

/// The smallest distance between the two rectangles, 0 when they touch or overlap (m).
double free_distance(const Footprint& a, const Footprint& b);

/// A lower bound of free_distance(a, b) (m), cheap enough to skip the exact distance with: the
/// centre distance less both half diagonals, less a margin far above the rounding of either
/// computation, so that it never exceeds the free_distance computed for the same footprints.
double free_distance_bound(const Footprint& a, const Footprint& b);

/// The time from now until the rectangles first touch if both keep their current velocities and
/// headings (s): 0 when they overlap now, nothing when they never would. Exact for the constant-
/// velocity prediction: the separating axis test on the four edge normals, with each axis'
/// projections moving linearly in time.
std::optional<double> time_to_contact(const Footprint& a, const Footprint& b);

}  // namespace corsa::sweep::detail
