#pragma once

// Scalar helpers shared by the sensor code (private): angle constants and the smoothstep ramp.

#include <algorithm>
#include <numbers>

namespace corsa::sensors::detail {

inline constexpr double kPi = std::numbers::pi;
/// Radians per degree.
inline constexpr double kDeg = std::numbers::pi / 180.0;

/// Hermite ramp: 0 at or below e0, 1 at or above e1, and 3t^2 - 2t^3 between, where
/// t = (x - e0) / (e1 - e0).
inline double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

}  // namespace corsa::sensors::detail
