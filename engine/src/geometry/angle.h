#pragma once

// Angles in the horizontal plane (rad, counter-clockwise from +x as in OpenDRIVE and
// OpenSCENARIO).

#include <cmath>
#include <numbers>

namespace corsa::engine::detail {

/// Wraps an angle (rad) into (-pi, pi].
double wrap_angle(double angle);

/// std::remainder(angle, 2 pi) (2 pi rounded to a double, as `2.0 * std::numbers::pi`), the
/// same bits, without the library's call for the angles a step turns by and the headings kept
/// in [0, 2 pi): the remainder is angle - n 2 pi with n the quotient rounded to nearest, ties
/// to even. Within [-pi, pi] n is 0 (a tie at +-pi rounds to 0) and the remainder is the angle
/// itself. From pi to 4 pi, angle - 2 pi is exact (Sterbenz: the two are within a factor of 2)
/// and is the remainder while it lies below pi (n is 1; at pi n ties to 2), and it is never -0
/// there; likewise below -pi, where angle + 2 pi = +0 at -2 pi would lose the sign the
/// remainder keeps (-0). Anything else (far angles, infinities, NaN) the library's.
inline double remainder_full_turn(double angle) {
  constexpr double kTurn = 2.0 * std::numbers::pi;
  constexpr double kHalfTurn = std::numbers::pi;  // kTurn / 2, exactly
  if (std::abs(angle) <= kHalfTurn) {
    return angle;
  }
  if (angle > kHalfTurn && angle <= 2.0 * kTurn) {
    const double r = angle - kTurn;
    if (r < kHalfTurn) {
      return r;
    }
  } else if (angle < -kHalfTurn && angle >= -2.0 * kTurn) {
    const double r = angle + kTurn;
    if (r > -kHalfTurn && r != 0.0) {
      return r;
    }
  }
  return std::remainder(angle, kTurn);
}

}  // namespace corsa::engine::detail
