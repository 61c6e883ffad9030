#pragma once

// Where the normals of a road's reference line cross one lane's centre line, station after
// station: the lane's lateral offset (t), its arc length and height there.

#include <optional>

#include "polyline.h"

namespace corsa::ngii::detail {

/// Where the normal of the reference line at a station crosses a lane's centre line.
struct Crossing {
  double t = 0.0;  ///< lateral offset (m, + left)
  double u = 0.0;  ///< arc length along the lane line (may run past its ends when extrapolated)
  double z = 0.0;
  /// The lane's unit direction there: the chord over +-1.5 m, cut to the stretch of the line
  /// the tracker takes directions from (the 1.5 m next to its end beyond it).
  Vec2 direction{1.0, 0.0};
};

/// Walks a lane polyline along increasing stations. Each station's crossing is searched only
/// near where the previous one was (a window of arc length), so that a lane folding back on
/// itself (a U-turn path) is never matched on its far leg.
class LaneTracker {
 public:
  /// `start_u`: arc length where the lane proper starts (after its lead-in); crossings are
  /// reported relative to it. Directions are taken within [direction_from, direction_to].
  LaneTracker(const Polyline& line, double start_u, double direction_from, double direction_to)
      : line_(line),
        start_u_(start_u),
        direction_from_(direction_from),
        direction_to_(direction_to),
        last_u_(start_u) {}

  /// The crossing of the normal at station s (stations in increasing order) through r with
  /// unit tangent `tangent`.
  Crossing measure(double s, Vec2 r, Vec2 tangent);

 private:
  Crossing measure_absolute(Vec2 r, Vec2 tangent);
  /// A lane advances about as fast as the stations and keeps its offset: the crossing closest
  /// to the expected arc length and to the previous offset is the one on this stretch of the
  /// lane (not its far leg at a U-turn, nor a later part of a sharp turn).
  double cost(const Crossing& c) const {
    return std::abs(c.u - expected_u_) + std::abs(c.t - last_t_);
  }

  static constexpr double kBehind = 5.0;      // m of lane searched behind the last crossing
  static constexpr double kAhead = 25.0;      // m searched ahead of it
  static constexpr double kMaxOffset = 30.0;  // m: farther crossings are not this lane's
  static constexpr double kMinChord = 0.5;    // m: shorter stretches give no direction

  const Polyline& line_;
  double start_u_ = 0.0;
  double direction_from_ = 0.0;
  double direction_to_ = 0.0;
  double last_s_ = 0.0;
  double expected_u_ = 0.0;
  double last_u_ = 0.0;
  double last_t_ = 0.0;  ///< the first station starts from the crossing nearest the line
};

}  // namespace corsa::ngii::detail
