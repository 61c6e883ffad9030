#pragma once

// A speed plan over time whose acceleration changes at bounded rates (jerk): the `follow` mode
// of SpeedProfileAction (OpenSCENARIO 1.3 SpeedProfileAction.followingMode: "apply jerk (change
// rate of acceleration/deceleration) and other optional constraints [...] resulting in a
// smoother speed profile curve"; FollowingMode `follow`: "as good as possible by observing the
// dynamic constraints").
//
// The plan is a chain of pieces of constant jerk. The speed profile's entries are points
// (time, speed); the straight lines between them are what `position` mode drives. `follow`
// rounds each corner between two lines with a piece of constant jerk tangent to both, centred on
// the corner, so that between corners the speed runs on the lines themselves. The first piece
// starts where the action starts, from the entity's acceleration, so the first line is met late
// and driven parallel to it until the next corner; the last corner, onto the final speed, ends
// half its length after the last entry's time with zero acceleration. A single entry is reached
// with a ramp up, a constant acceleration and a ramp down, on time when the limits allow, else
// as soon as they allow.

#include <vector>

namespace corsa::engine::detail {

/// Limits of a jerk-limited plan, all magnitudes > 0 (m/s^2 and m/s^3; infinity: none).
struct JerkLimits {
  double acceleration = 0.0;       ///< largest acceleration, m/s^2
  double deceleration = 0.0;       ///< largest deceleration, m/s^2
  double acceleration_rate = 0.0;  ///< largest rate at which the acceleration grows, m/s^3
  double deceleration_rate = 0.0;  ///< largest rate at which the acceleration falls, m/s^3
};

/// One point of a profile: the speed (m/s) to have at time `t` (s from the plan's start).
struct SpeedVertex {
  double t = 0.0;
  double v = 0.0;
};

/// From `t` (s from the plan's start) on: speed v + a tau + j tau^2 / 2, tau = time - t.
struct JerkPiece {
  double t = 0.0;
  double v = 0.0;
  double a = 0.0;
  double j = 0.0;
};

class JerkProfile {
 public:
  /// Plans through `vertices` (the first the start: t 0 and the current speed; times rising)
  /// from acceleration `a0` (m/s^2) within `limits`.
  JerkProfile(const std::vector<SpeedVertex>& vertices, double a0, const JerkLimits& limits);

  /// Speed (m/s) at `t` s from the start; the final speed from end_time() on.
  double speed_at(double t) const;
  /// When the final speed is reached (s from the start).
  double end_time() const { return pieces_.back().t; }
  const std::vector<JerkPiece>& pieces() const { return pieces_; }

 private:
  void reach(double v1, double duration, const JerkLimits& limits);
  void append(double t, double a, double j);

  std::vector<JerkPiece> pieces_;
};

}  // namespace corsa::engine::detail
