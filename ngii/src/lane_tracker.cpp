#include "lane_tracker.h"

#include <algorithm>
#include <cmath>

namespace corsa::ngii::detail {

Crossing LaneTracker::measure(double s, Vec2 r, Vec2 tangent) {
  expected_u_ = last_u_ + (s - last_s_);
  last_s_ = s;
  Crossing c = measure_absolute(r, tangent);
  // The lane's direction over a few metres (a coarse polyline's segment direction jumps at
  // every vertex).
  constexpr double kHalfChord = 1.5;  // m
  const double u = std::clamp(c.u, 0.0, line_.length());
  const double from = direction_from_;
  const double to = std::max(direction_to_, from);
  double u0 = std::clamp(u - kHalfChord, from, to);
  double u1 = std::clamp(u + kHalfChord, from, to);
  if (u >= to) {
    u0 = std::max(from, to - kHalfChord);
  } else if (u <= from) {
    u1 = std::min(to, from + kHalfChord);
  }
  if (u1 - u0 < kMinChord) {  // a stretch too short to give a direction: the whole line
    u0 = u - kHalfChord;
    u1 = u + kHalfChord;
  }
  const Vec2 chord = xy(line_.at(u1)) - xy(line_.at(u0));
  if (norm(chord) > 1e-6) {
    c.direction = (1.0 / norm(chord)) * chord;
  }
  c.u -= start_u_;
  return c;
}

Crossing LaneTracker::measure_absolute(Vec2 r, Vec2 tangent) {
  const auto& p = line_.points();
  const size_t segments = p.size() - 1;
  const auto g = [&](size_t i) { return dot(xy(p[i]) - r, tangent); };
  const Vec2 normal{-tangent.y, tangent.x};
  const double low = last_u_ - kBehind;
  const double high = last_u_ + kAhead;
  std::optional<Crossing> best;
  for (size_t i = line_.segment_at(std::max(0.0, low)); i < segments; ++i) {
    if (line_.u()[i] > high) {
      break;
    }
    const double g0 = g(i);
    const double g1 = g(i + 1);
    if ((g0 <= 0.0) != (g1 <= 0.0) || g0 == 0.0) {
      const double f = g0 == g1 ? 0.0 : g0 / (g0 - g1);
      const Vec2 q = xy(p[i]) + f * (xy(p[i + 1]) - xy(p[i]));
      const Crossing c{dot(q - r, normal), line_.u()[i] + f * (line_.u()[i + 1] - line_.u()[i]),
                       p[i].z + f * (p[i + 1].z - p[i].z), line_.segment_direction(i)};
      if (!best || cost(c) < cost(*best)) {
        best = c;
      }
    }
  }
  // The end segments extended as straight lines are candidates too (stations just before
  // the start or past the end, where the lane itself is not crossed).
  for (const bool at_start : {true, false}) {
    if ((at_start && low > 0.0) || (!at_start && high < line_.length())) {
      continue;
    }
    const size_t i = at_start ? 0 : segments - 1;
    const Vec2 a = xy(p[at_start ? 0 : segments]);
    const Vec2 d = line_.segment_direction(i);
    const double denominator = dot(d, tangent);
    if (std::abs(denominator) < 0.3) {
      continue;
    }
    const double lambda = -dot(a - r, tangent) / denominator;
    if ((at_start && lambda > 0.5) || (!at_start && lambda < -0.5)) {
      continue;  // that crossing is on the lane itself, found above if anywhere
    }
    const Crossing c{dot(a + lambda * d - r, normal), (at_start ? 0.0 : line_.length()) + lambda,
                     p[at_start ? 0 : segments].z, d};
    if (!best || cost(c) < cost(*best)) {
      best = c;
    }
  }
  if (best && std::abs(best->t) < kMaxOffset) {
    last_u_ = std::clamp(best->u, 0.0, line_.length());
    last_t_ = best->t;
    return *best;
  }
  // No usable crossing: the offset of the nearest point in the window.
  Crossing nearest;
  double best_distance = 1e300;
  for (double u = std::max(0.0, low); u <= std::min(high, line_.length()); u += 0.25) {
    const Point3 q = line_.at(u);
    const double d = norm(xy(q) - r);
    if (d < best_distance) {
      best_distance = d;
      nearest = Crossing{dot(xy(q) - r, normal), u, q.z, line_.direction(u)};
    }
  }
  last_u_ = nearest.u;
  last_t_ = nearest.t;
  return nearest;
}

}  // namespace corsa::ngii::detail
