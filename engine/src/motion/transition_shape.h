#pragma once

// TransitionDynamics (OpenSCENARIO 1.3 §7.4.1.1): how a value goes from its start to its target,
// with a shape (step, linear, cubic, sinusoidal) over a dimension (time in s, distance in m, or
// a rate in unit/s).

#include <cstdint>

#include "corsa/xosc/enums.h"

namespace corsa::engine::detail {

/// The shape as a function of progress p in [0, 1]: 0 at p = 0, 1 at p = 1.
///   linear p;  cubic 3p^2 - 2p^3 (zero slope at both ends);  sinusoidal (1 - cos(pi p)) / 2;
///   step 1 for every p > 0.
double shape_value(xosc::DynamicsShape shape, double p);

/// Peak slope of the shape over progress (d value / dp) for unit change: linear 1, cubic 1.5,
/// sinusoidal pi/2 (step: unbounded, reported as 1). Turns a rate into a duration so that the
/// rate is the largest rate of change on the way.
double shape_peak_slope(xosc::DynamicsShape shape);

/// Progress of a transition measured in its dimension: elapsed time or distance against the
/// total (a rate has been turned into a total time by the caller).
class TransitionProgress {
 public:
  /// `total` in s (time, rate) or m (distance); <= 0 means immediate.
  TransitionProgress(xosc::DynamicsDimension dimension, double total)
      : by_distance_(dimension == xosc::DynamicsDimension::kDistance), total_(total) {}
  /// Progress at the end of the next step, given the time (s) and distance (m) elapsed since
  /// the start at that point.
  double at(double elapsed_time, double elapsed_distance) const {
    if (total_ <= 0.0) {
      return 1.0;
    }
    const double p = (by_distance_ ? elapsed_distance : elapsed_time) / total_;
    return p < 0.0 ? 0.0 : p > 1.0 ? 1.0 : p;
  }

 private:
  bool by_distance_;
  double total_;
};

}  // namespace corsa::engine::detail
