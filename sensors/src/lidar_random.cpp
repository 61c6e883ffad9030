#include "lidar_random.h"

#include <cmath>

#include "corsa/core/det_math.h"

namespace corsa::sensors::detail {

const Ziggurat& Ziggurat::get() {
  static const Ziggurat table;  // immutable after construction
  return table;
}

Ziggurat::Ziggurat() {
  // Every layer has area kArea: layer i >= 1 is the rectangle [0, x_i] x [f(x_i), f(x_(i+1))],
  // so f(x_(i+1)) = f(x_i) + kArea / x_i; layer 0 is [0, kR] x [0, f(kR)] plus the tail beyond
  // kR, drawn as a rectangle of width kArea / f(kR).
  x_[1] = kR;
  f_[1] = density(kR);
  x_[0] = kArea / f_[1];
  f_[0] = 0.0;
  for (int i = 1; i < kLayers - 1; ++i) {
    f_[i + 1] = f_[i] + kArea / x_[i];
    x_[i + 1] = std::sqrt(-2.0 * det::log(f_[i + 1]));
  }
  x_[kLayers] = 0.0;
  f_[kLayers] = 1.0;
}

double Ziggurat::tail(double u1, double u2) {
  const double x = -det::log(1.0 - u1) / kR;  // 1 - u in (0, 1]
  const double y = -det::log(1.0 - u2);
  return y + y > x * x ? kR + x : 0.0;
}

double Ziggurat::density(double x) { return det::exp(-0.5 * x * x); }

}  // namespace corsa::sensors::detail
