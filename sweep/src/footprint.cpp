#include "footprint.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace corsa::sweep::detail {
namespace {

double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }

struct Interval {
  double low = 0.0;
  double high = 0.0;
};

// Projection of a rectangle onto the unit axis `n`.
Interval project(const Footprint& f, Vec2 n) {
  const double c = dot(f.center, n);
  const double r = f.half_length * std::fabs(dot(f.axis, n)) +
                   f.half_width * std::fabs(f.axis.x * n.y - f.axis.y * n.x);
  return {c - r, c + r};
}

std::array<Vec2, 4> axes_of(const Footprint& a, const Footprint& b) {
  return {a.axis, Vec2{-a.axis.y, a.axis.x}, b.axis, Vec2{-b.axis.y, b.axis.x}};
}

// Squared distance from p to the segment s0-s1 (m^2).
double point_segment_squared(Vec2 p, Vec2 s0, Vec2 s1) {
  const Vec2 d{s1.x - s0.x, s1.y - s0.y};
  const Vec2 w{p.x - s0.x, p.y - s0.y};
  const double len2 = dot(d, d);
  const double u = len2 > 0.0 ? std::clamp(dot(w, d) / len2, 0.0, 1.0) : 0.0;
  const double dx = w.x - u * d.x;
  const double dy = w.y - u * d.y;
  return dx * dx + dy * dy;
}

// Squared distance (m^2) from p to the rectangle, 0 inside.
double point_box_squared(Vec2 p, const Footprint& f) {
  const Vec2 w{p.x - f.center.x, p.y - f.center.y};
  const double along = std::max(std::fabs(dot(w, f.axis)) - f.half_length, 0.0);
  const double across = std::max(std::fabs(f.axis.x * w.y - f.axis.y * w.x) - f.half_width, 0.0);
  return along * along + across * across;
}

// Rounding of corners and projections is a few ulps of the coordinates (1e-12 m at 10 km); the
// margin is a micrometre more, scaled for maps far from their origin.
double rounding_margin(const Footprint& a, const Footprint& b) {
  return 1e-6 + 1e-12 * (std::fabs(a.center.x) + std::fabs(a.center.y) + std::fabs(b.center.x) +
                         std::fabs(b.center.y) + a.half_length + a.half_width + b.half_length +
                         b.half_width);
}

}  // namespace

std::array<Vec2, 4> Footprint::corners() const {
  const Vec2 l{axis.x * half_length, axis.y * half_length};
  const Vec2 w{-axis.y * half_width, axis.x * half_width};
  return {Vec2{center.x + l.x + w.x, center.y + l.y + w.y},
          Vec2{center.x + l.x - w.x, center.y + l.y - w.y},
          Vec2{center.x - l.x - w.x, center.y - l.y - w.y},
          Vec2{center.x - l.x + w.x, center.y - l.y + w.y}};
}

Footprint footprint_of(const engine::EntityInfo& info, const engine::EntityState& state) {
  Footprint f;
  const double c = std::cos(state.pose.h);
  const double s = std::sin(state.pose.h);
  f.axis = {c, s};
  f.center = {state.pose.x + c * info.box.center_x - s * info.box.center_y,
              state.pose.y + s * info.box.center_x + c * info.box.center_y};
  f.half_length = 0.5 * info.box.length;
  f.half_width = 0.5 * info.box.width;
  f.velocity = {state.speed * c - state.lateral_speed * s,
                state.speed * s + state.lateral_speed * c};
  return f;
}

double free_distance(const Footprint& a, const Footprint& b) {
  bool separated = false;
  for (const Vec2 n : axes_of(a, b)) {
    const Interval ia = project(a, n);
    const Interval ib = project(b, n);
    separated = separated || ia.high < ib.low || ib.high < ia.low;
  }
  if (!separated) {
    return 0.0;
  }
  // Separated convex polygons: the closest pair has a vertex of one on an edge of the other. A
  // corner's distance to the other rectangle (closed form) is the least over its four edges, so
  // only the corners within a rounding margin of the nearest one are measured edge by edge.
  // sqrt is correctly rounded and monotonic, so the square root of the least squared distance is
  // exactly the least of the distances: the result is the same as over all 32 pairs.
  const auto ca = a.corners();
  const auto cb = b.corners();
  std::array<double, 8> corner_squared;
  for (size_t i = 0; i < 4; ++i) {
    corner_squared[i] = point_box_squared(ca[i], b);
    corner_squared[4 + i] = point_box_squared(cb[i], a);
  }
  const double reach = std::sqrt(*std::min_element(corner_squared.begin(), corner_squared.end())) +
                       rounding_margin(a, b);
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < 8; ++i) {
    if (!(corner_squared[i] <= reach * reach)) {
      continue;
    }
    const Vec2 corner = i < 4 ? ca[i] : cb[i - 4];
    const auto& edges = i < 4 ? cb : ca;
    for (size_t j = 0; j < 4; ++j) {
      best = std::min(best, point_segment_squared(corner, edges[j], edges[(j + 1) % 4]));
    }
  }
  return std::sqrt(best);
}

double free_distance_bound(const Footprint& a, const Footprint& b) {
  const double margin = rounding_margin(a, b);
  const double centres = std::hypot(b.center.x - a.center.x, b.center.y - a.center.y);
  return centres - std::hypot(a.half_length, a.half_width) -
         std::hypot(b.half_length, b.half_width) - margin;
}

std::optional<double> time_to_contact(const Footprint& a, const Footprint& b) {
  // b moves relative to a with velocity v; on each axis b's interval slides by (v.n) t, and the
  // rectangles touch exactly when every axis overlaps (separating axis theorem).
  const Vec2 v{b.velocity.x - a.velocity.x, b.velocity.y - a.velocity.y};
  double enter = 0.0;
  double exit = std::numeric_limits<double>::infinity();
  for (const Vec2 n : axes_of(a, b)) {
    const Interval ia = project(a, n);
    const Interval ib = project(b, n);
    const double rate = dot(v, n);
    if (rate == 0.0) {
      if (ib.high < ia.low || ia.high < ib.low) return std::nullopt;  // apart on this axis forever
      continue;
    }
    // Overlap while ia.low <= ib.high + rate t and ib.low + rate t <= ia.high.
    double t0 = (ia.low - ib.high) / rate;
    double t1 = (ia.high - ib.low) / rate;
    if (t0 > t1) std::swap(t0, t1);
    enter = std::max(enter, t0);
    exit = std::min(exit, t1);
    if (enter > exit) return std::nullopt;
  }
  return enter;
}

}  // namespace corsa::sweep::detail
