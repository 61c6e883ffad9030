#include "motion/jerk_profile.h"

#include <cmath>

namespace corsa::engine::detail {
namespace {

constexpr double kJerkEps = 1e-9;

double jerk_piece_speed(const JerkPiece& piece, double t) {
  const double tau = t - piece.t;
  if (tau <= 0.0) {
    return piece.v;  // also keeps an unbounded jerk of a zero-length piece out of the sum
  }
  return piece.v + piece.a * tau + 0.5 * piece.j * tau * tau;
}

/// Time (s) to take the acceleration from `from` to `to` (m/s^2) at the limits' rates.
double ramp_time(double from, double to, const JerkLimits& limits) {
  return to > from ? (to - from) / limits.acceleration_rate
                   : (from - to) / limits.deceleration_rate;
}

/// Speed gained (m/s) on that ramp.
double ramp_gain(double from, double to, const JerkLimits& limits) {
  const double time = ramp_time(from, to, limits);
  return time > 0.0 ? 0.5 * (from + to) * time : 0.0;
}

/// The jerk (m/s^3) of a ramp from `from` to `to`.
double ramp_jerk(double from, double to, const JerkLimits& limits) {
  return to > from ? limits.acceleration_rate : -limits.deceleration_rate;
}

/// A ramp from a0 to the peak A and a ramp from A to zero: speed gained and time taken.
struct JerkTriangle {
  double gain = 0.0;
  double time = 0.0;
};
JerkTriangle jerk_triangle(double a0, double peak, const JerkLimits& limits) {
  return {ramp_gain(a0, peak, limits) + ramp_gain(peak, 0.0, limits),
          ramp_time(a0, peak, limits) + ramp_time(peak, 0.0, limits)};
}

}  // namespace

JerkProfile::JerkProfile(const std::vector<SpeedVertex>& vertices, double a0,
                         const JerkLimits& limits) {
  pieces_.push_back({0.0, vertices.empty() ? 0.0 : vertices.front().v, a0, 0.0});
  if (vertices.size() < 2) {
    reach(pieces_.back().v, 0.0, limits);
    return;
  }
  if (vertices.size() == 2) {
    reach(vertices[1].v, vertices[1].t, limits);
    return;
  }
  const size_t n = vertices.size();
  const auto slope = [&](size_t i) {  // of the line from vertex i to i + 1; 0 after the last
    return i + 1 < n ? (vertices[i + 1].v - vertices[i].v) / (vertices[i + 1].t - vertices[i].t)
                     : 0.0;
  };
  // Onto the first line's slope from the entity's acceleration: the line is met late.
  const double k0 = slope(0);
  pieces_.back().j = ramp_jerk(a0, k0, limits);
  append(ramp_time(a0, k0, limits), k0, 0.0);
  for (size_t i = 1; i < n; ++i) {
    const JerkPiece line = pieces_.back();  // on a line: constant acceleration
    const double kb = slope(i);
    const SpeedVertex& corner_vertex = vertices[i];
    const bool last = i + 1 == n;
    if (std::abs(kb - line.a) < kJerkEps) {
      const double gap = jerk_piece_speed(line, corner_vertex.t) - corner_vertex.v;
      if (last && std::abs(gap) > kJerkEps) {
        reach(corner_vertex.v, corner_vertex.t, limits);
      }
      continue;  // parallel: stay on this line
    }
    // Where the lines cross, and the tangent piece of constant jerk centred there.
    const double corner =
        (corner_vertex.v - line.v + line.a * line.t - kb * corner_vertex.t) / (line.a - kb);
    const double jerk = ramp_jerk(line.a, kb, limits);
    const double length = (kb - line.a) / jerk;
    double start = corner - 0.5 * length;
    if (start < line.t) {
      if (last) {  // no room to round the corner: reach the final speed from here
        reach(corner_vertex.v, corner_vertex.t, limits);
        return;
      }
      start = line.t;  // round it from here: the next line is met late, as the first
    }
    append(start, line.a, jerk);
    append(start + length, kb, 0.0);
  }
  pieces_.back().v = vertices.back().v;
  pieces_.back().a = 0.0;
}

double JerkProfile::speed_at(double t) const {
  size_t i = 0;
  while (i + 1 < pieces_.size() && pieces_[i + 1].t <= t) {
    ++i;
  }
  return jerk_piece_speed(pieces_[i], t);
}

void JerkProfile::append(double t, double a, double j) {
  JerkPiece& last = pieces_.back();
  if (t <= last.t + kJerkEps) {  // a piece of no length: the new one replaces it
    last.a = a;
    last.j = j;
    return;
  }
  pieces_.push_back({t, jerk_piece_speed(last, t), a, j});
}

/// From the last piece's start (its speed and acceleration) to speed `v1` with zero
/// acceleration at time `target` (s from the plan's start): a ramp to a peak acceleration A, A
/// held, a ramp to zero. On time when the limits allow (the smallest |A| that arrives then),
/// else as soon as they allow (the largest A up to the acceleration or deceleration limit).
void JerkProfile::reach(double v1, double target, const JerkLimits& limits) {
  const JerkPiece from = pieces_.back();
  const double a0 = from.a;
  const double dv = v1 - from.v;
  const double settle = ramp_gain(a0, 0.0, limits);  // gained by only bringing a0 to zero
  if (std::abs(dv - settle) < kJerkEps) {
    pieces_.back().j = ramp_jerk(a0, 0.0, limits);
    append(from.t + ramp_time(a0, 0.0, limits), 0.0, 0.0);
    pieces_.back().v = v1;
    return;
  }
  const double sign = dv > settle ? 1.0 : -1.0;
  const double cap = sign * (sign > 0.0 ? limits.acceleration : limits.deceleration);
  // Time-optimal peak: the triangle whose gain is dv, else the capped trapezoid.
  double peak = cap;
  double hold = 0.0;
  const JerkTriangle capped = jerk_triangle(a0, cap, limits);
  if (sign * (capped.gain - dv) >= 0.0) {
    double lo = sign > 0.0 ? std::max(a0, 0.0) : std::min(a0, 0.0);
    double hi = cap;
    for (int k = 0; k < 200; ++k) {
      const double mid = 0.5 * (lo + hi);
      (sign * (jerk_triangle(a0, mid, limits).gain - dv) < 0.0 ? lo : hi) = mid;
    }
    peak = 0.5 * (lo + hi);
  } else {
    hold = (dv - capped.gain) / cap;
  }
  const double fastest = jerk_triangle(a0, peak, limits).time + hold;
  const double duration = target - from.t;
  if (duration > fastest + kJerkEps) {
    // More time than needed: a smaller peak held longer. The time taken falls as |A| grows.
    double lo = 0.0;
    double hi = peak;
    for (int k = 0; k < 200; ++k) {
      const double mid = 0.5 * (lo + hi);
      const JerkTriangle tri = jerk_triangle(a0, mid, limits);
      const double time = tri.time + (dv - tri.gain) / mid;
      (time > duration ? lo : hi) = mid;
    }
    peak = hi;
    const JerkTriangle tri = jerk_triangle(a0, peak, limits);
    hold = std::max(0.0, (dv - tri.gain) / peak);
  }
  const double up = ramp_time(a0, peak, limits);
  pieces_.back().j = ramp_jerk(a0, peak, limits);
  append(from.t + up, peak, 0.0);
  append(from.t + up + hold, peak, ramp_jerk(peak, 0.0, limits));
  append(from.t + up + hold + ramp_time(peak, 0.0, limits), 0.0, 0.0);
  pieces_.back().v = v1;
}

}  // namespace corsa::engine::detail
