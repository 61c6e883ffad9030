#include "motion/transition_shape.h"

#include <cmath>
#include <numbers>

namespace corsa::engine::detail {

double shape_value(xosc::DynamicsShape shape, double p) {
  if (p <= 0.0) {
    return 0.0;
  }
  if (p >= 1.0) {
    return 1.0;
  }
  switch (shape) {
    case xosc::DynamicsShape::kStep:
      return 1.0;
    case xosc::DynamicsShape::kLinear:
      return p;
    case xosc::DynamicsShape::kCubic:
      return p * p * (3.0 - 2.0 * p);
    case xosc::DynamicsShape::kSinusoidal:
      return 0.5 * (1.0 - std::cos(std::numbers::pi * p));
  }
  return p;
}

double shape_peak_slope(xosc::DynamicsShape shape) {
  switch (shape) {
    case xosc::DynamicsShape::kCubic:
      return 1.5;
    case xosc::DynamicsShape::kSinusoidal:
      return 0.5 * std::numbers::pi;
    default:
      return 1.0;
  }
}

}  // namespace corsa::engine::detail
