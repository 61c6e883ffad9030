#pragma once

// The nearest point of a segment in the horizontal plane (map frame, metres).

#include <algorithm>

#include "corsa/core/vec.h"

namespace corsa::engine::detail {

/// Offset (m) from a point to the nearest point of a segment.
struct SegmentOffset {
  double dx = 0.0, dy = 0.0;
  double squared() const { return dx * dx + dy * dy; }
};

/// Offset from the point p to the nearest point of segment a-b (to a when a and b coincide): the
/// projection's parameter along a-b, clamped to [0, 1].
inline SegmentOffset point_segment(Vec2 p, Vec2 a, Vec2 b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0.0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return {p.x - (a.x + t * dx), p.y - (a.y + t * dy)};
}

}  // namespace corsa::engine::detail
