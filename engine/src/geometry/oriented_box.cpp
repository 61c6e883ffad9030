#include "corsa/engine/oriented_box.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "geometry/box_placement.h"
#include "geometry/segment.h"

namespace corsa::engine {

[[gnu::hot]] OrientedBox detail::box_at_heading(const Box& box, const Pose& pose, double cos_h,
                                                double sin_h) {
  OrientedBox out;
  out.cos_h = cos_h;
  out.sin_h = sin_h;
  out.cx = pose.x + out.cos_h * box.center_x - out.sin_h * box.center_y;
  out.cy = pose.y + out.sin_h * box.center_x + out.cos_h * box.center_y;
  out.half_length = 0.5 * box.length;
  out.half_width = 0.5 * box.width;
  out.z_min = pose.z + box.center_z - 0.5 * box.height;
  out.z_max = pose.z + box.center_z + 0.5 * box.height;
  return out;
}

[[gnu::hot]] OrientedBox box_of(const Box& box, const Pose& pose) {
  return detail::box_at_heading(box, pose, std::cos(pose.h), std::sin(pose.h));
}

[[gnu::hot]] Interval project(const OrientedBox& box, double ux, double uy) {
  const double center = box.cx * ux + box.cy * uy;
  const double reach = std::abs(box.half_length * (box.cos_h * ux + box.sin_h * uy)) +
                       std::abs(box.half_width * (-box.sin_h * ux + box.cos_h * uy));
  return {center - reach, center + reach};
}

namespace {

bool separated_on(const OrientedBox& a, const OrientedBox& b, double ux, double uy) {
  const Interval ia = project(a, ux, uy);
  const Interval ib = project(b, ux, uy);
  return ia.high < ib.low || ib.high < ia.low;
}

std::array<Vec2, 4> corners(const OrientedBox& box) {
  const double lx = box.cos_h * box.half_length, ly = box.sin_h * box.half_length;
  const double wx = -box.sin_h * box.half_width, wy = box.cos_h * box.half_width;
  return {{{box.cx + lx + wx, box.cy + ly + wy},
           {box.cx - lx + wx, box.cy - ly + wy},
           {box.cx - lx - wx, box.cy - ly - wy},
           {box.cx + lx - wx, box.cy + ly - wy}}};
}

using detail::point_segment;
using detail::SegmentOffset;

// Relative margin on squared distances that covers the rounding of dx^2 + dy^2 (a few ulps)
// against hypot's correctly rounded result: every candidate whose hypot could be the smallest
// has its squared distance within it of the smallest squared distance.
constexpr double kSquaredMargin = 1e-12;

// Squared distance (m^2) from (x, y) to the box, 0 inside: in the box's frame, the parts of the
// offset beyond the half length and half width.
double box_point_squared(const OrientedBox& box, double x, double y) {
  const double dx = x - box.cx, dy = y - box.cy;
  const double along = std::max(std::abs(dx * box.cos_h + dy * box.sin_h) - box.half_length, 0.0);
  const double across = std::max(std::abs(-dx * box.sin_h + dy * box.cos_h) - box.half_width, 0.0);
  return along * along + across * across;
}

// Far above the rounding of corners, projections and distances (a few ulps of the coordinates,
// 1e-12 m at 10 km from the origin) and far below any distance that matters: 1 um, more far
// from the origin.
double rounding_margin(const OrientedBox& a, const OrientedBox& b) {
  return 1e-6 + 1e-12 * (std::abs(a.cx) + std::abs(a.cy) + std::abs(b.cx) + std::abs(b.cy) +
                         a.half_length + a.half_width + b.half_length + b.half_width);
}

}  // namespace

double box_reach(const Box& box) {
  return std::hypot(std::abs(box.center_x) + 0.5 * box.length,
                    std::abs(box.center_y) + 0.5 * box.width);
}

bool overlap(const OrientedBox& a, const OrientedBox& b) {
  if (a.z_max < b.z_min || b.z_max < a.z_min) {
    return false;
  }
  return !separated_on(a, b, a.cos_h, a.sin_h) && !separated_on(a, b, -a.sin_h, a.cos_h) &&
         !separated_on(a, b, b.cos_h, b.sin_h) && !separated_on(a, b, -b.sin_h, b.cos_h);
}

double box_point_distance(const OrientedBox& box, double x, double y) {
  const double dx = x - box.cx, dy = y - box.cy;
  const double along = std::abs(dx * box.cos_h + dy * box.sin_h) - box.half_length;
  const double across = std::abs(-dx * box.sin_h + dy * box.cos_h) - box.half_width;
  return std::hypot(std::max(along, 0.0), std::max(across, 0.0));
}

double box_distance(const OrientedBox& a, const OrientedBox& b) {
  OrientedBox flat_a = a, flat_b = b;
  flat_a.z_min = flat_b.z_min = 0.0;
  flat_a.z_max = flat_b.z_max = 0.0;
  if (overlap(flat_a, flat_b)) {
    return 0.0;
  }
  // Two disjoint convex polygons: the closest points are a corner of one and an edge of the
  // other, so the distance is the least of 32 corner-edge distances. A corner's distance to the
  // other box (closed form, cheap) is the least of its four; only corners within a rounding
  // margin of the nearest corner can hold the least candidate, so only their edges are measured
  // (one or two corners of eight, usually). hypot (libm, ~100 instructions) is then taken only of
  // the candidates that can be the nearest by their squared distances. The result is the same
  // minimum of hypot over all 32 pairs, bit for bit.
  const auto ca = corners(a);
  const auto cb = corners(b);
  std::array<double, 8> corner_squared;
  for (int i = 0; i < 4; ++i) {
    corner_squared[i] = box_point_squared(b, ca[i].x, ca[i].y);
    corner_squared[4 + i] = box_point_squared(a, cb[i].x, cb[i].y);
  }
  const double nearest = std::sqrt(*std::min_element(corner_squared.begin(), corner_squared.end()));
  const double reach = nearest + rounding_margin(a, b);
  std::array<SegmentOffset, 32> offsets;
  size_t n = 0;
  for (int i = 0; i < 8; ++i) {
    if (!(corner_squared[i] <= reach * reach)) {
      continue;
    }
    const Vec2 corner = i < 4 ? ca[i] : cb[i - 4];
    const auto& edges = i < 4 ? cb : ca;
    for (int j = 0; j < 4; ++j) {
      offsets[n++] = point_segment(corner, edges[j], edges[(j + 1) % 4]);
    }
  }
  double least = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < n; ++k) {
    least = std::min(least, offsets[k].squared());
  }
  const double cutoff = least * (1.0 + kSquaredMargin);
  double best = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < n; ++k) {
    if (offsets[k].squared() <= cutoff) {
      best = std::min(best, std::hypot(offsets[k].dx, offsets[k].dy));
    }
  }
  return best;
}

double box_distance_lower_bound(const OrientedBox& a, const OrientedBox& b) {
  const double centres = std::hypot(b.cx - a.cx, b.cy - a.cy);
  return centres - std::hypot(a.half_length, a.half_width) -
         std::hypot(b.half_length, b.half_width) - rounding_margin(a, b);
}

std::optional<double> time_to_contact(const OrientedBox& a, Vec2 va, const OrientedBox& b,
                                      Vec2 vb) {
  // b moves relative to a with velocity v; on each axis b's interval slides by (v.n) t, and the
  // boxes touch exactly when every axis overlaps (separating axis theorem).
  const Vec2 v = vb - va;
  const std::array<Vec2, 4> axes = {
      {{a.cos_h, a.sin_h}, {-a.sin_h, a.cos_h}, {b.cos_h, b.sin_h}, {-b.sin_h, b.cos_h}}};
  double enter = 0.0;
  double exit = std::numeric_limits<double>::infinity();
  for (const Vec2 n : axes) {
    const Interval ia = project(a, n.x, n.y);
    const Interval ib = project(b, n.x, n.y);
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

}  // namespace corsa::engine
