#pragma once

// Ticks and seconds. The run counts integer ticks of the fixed step so that nothing drifts: a
// time is always tick * dt, computed as tick / N when dt is 1/N for an integer N (0.01 s -> N =
// 100) so that e.g. tick 30 prints as 0.3 and not 0.30000000000000004.

#include <cmath>
#include <cstdint>

namespace corsa::engine::detail {

class TimeBase {
 public:
  explicit TimeBase(double dt) : dt_(dt) {
    const double n = std::round(1.0 / dt);
    if (n >= 1.0 && n < 1e9 && std::abs(1.0 / n - dt) <= 1e-15 * dt) {
      per_second_ = static_cast<int64_t>(n);
    }
  }
  double dt() const { return dt_; }
  double time(int64_t tick) const {
    return per_second_ > 0 ? static_cast<double>(tick) / static_cast<double>(per_second_)
                           : static_cast<double>(tick) * dt_;
  }
  /// Seconds rounded to whole ticks (delays, durations on the tick grid).
  int64_t ticks(double seconds) const { return std::llround(seconds / dt_); }

 private:
  double dt_;
  int64_t per_second_ = 0;  ///< N when dt == 1/N exactly, else 0
};

}  // namespace corsa::engine::detail
