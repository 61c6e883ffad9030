#include "geometry/angle.h"

#include <cmath>
#include <numbers>

namespace corsa::engine::detail {

[[gnu::hot]] double wrap_angle(double angle) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  // fmod is exact: within one turn it returns the angle itself (the common case, a heading of
  // a step), and the call is left out.
  if (!(std::abs(angle) < kTwoPi)) {
    angle = std::fmod(angle, kTwoPi);
  }
  if (angle <= -std::numbers::pi) {
    angle += kTwoPi;
  } else if (angle > std::numbers::pi) {
    angle -= kTwoPi;
  }
  return angle;
}

}  // namespace corsa::engine::detail
