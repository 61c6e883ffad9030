#include "polyline.h"

#include <algorithm>

namespace corsa::ngii::detail {

Polyline::Polyline(std::span<const Point3> points) : points_(points.begin(), points.end()) {
  u_.resize(points_.size());
  double u = 0.0;
  for (size_t i = 0; i < points_.size(); ++i) {
    if (i > 0) {
      u += norm(xy(points_[i]) - xy(points_[i - 1]));
    }
    u_[i] = u;
  }
  for (size_t first = 0; first + 1 < points_.size(); first += kBlock) {
    const size_t last = std::min(first + kBlock, points_.size() - 1);
    Block block{points_[first].x, points_[first].y, points_[first].x, points_[first].y};
    for (size_t i = first; i <= last; ++i) {
      block.x0 = std::min(block.x0, points_[i].x);
      block.y0 = std::min(block.y0, points_[i].y);
      block.x1 = std::max(block.x1, points_[i].x);
      block.y1 = std::max(block.y1, points_[i].y);
    }
    blocks_.push_back(block);
  }
}

Vec2 Polyline::segment_direction(size_t i) const {
  const Vec2 d = xy(points_[i + 1]) - xy(points_[i]);
  const double n = norm(d);
  return n > 0.0 ? (1.0 / n) * d : Vec2{1.0, 0.0};
}

void Polyline::consider_segment(size_t i, Vec2 q, Projection& best) const {
  const size_t last = points_.size() - 2;
  const Vec2 a = xy(points_[i]);
  const Vec2 d = segment_direction(i);
  const double len = u_[i + 1] - u_[i];
  const double f = dot(q - a, d);
  const double clamped = std::clamp(f, 0.0, len);
  const double distance = norm(q - (a + clamped * d));
  // Ties go to the earlier segment, so the result does not depend on the visiting order.
  if (distance < best.distance || (distance == best.distance && i < best.segment)) {
    best.distance = distance;
    best.u = u_[i] + clamped;
    best.segment = i;
    best.lateral = cross(d, q - a);
    best.along = (i == 0 && f < 0.0) ? f : (i == last && f > len) ? f - len : 0.0;
  }
}

Projection Polyline::project(Vec2 q) const {
  Projection best;
  best.distance = 1e300;
  if (points_.size() < 2) {
    if (!points_.empty()) {
      best.distance = norm(q - xy(points_[0]));
    }
    return best;
  }
  // The block with the nearest box first, then every block whose box is nearer than the best
  // segment so far.
  size_t first_block = 0;
  double first_distance = 1e300;
  for (size_t b = 0; b < blocks_.size(); ++b) {
    const double d = blocks_[b].distance(q);
    if (d < first_distance) {
      first_distance = d;
      first_block = b;
    }
  }
  const auto visit = [&](size_t b) {
    const size_t first = b * kBlock;
    const size_t end = std::min(first + kBlock, points_.size() - 1);
    for (size_t i = first; i < end; ++i) {
      consider_segment(i, q, best);
    }
  };
  visit(first_block);
  for (size_t b = 0; b < blocks_.size(); ++b) {
    if (b != first_block && blocks_[b].distance(q) <= best.distance) {
      visit(b);
    }
  }
  return best;
}

Projection Polyline::project_within(Vec2 q, double u0, double u1) const {
  Projection best;
  best.distance = 1e300;
  if (points_.size() < 2) {
    return project(q);
  }
  for (size_t i = segment_at(std::max(0.0, u0)); i + 1 < points_.size() && u_[i] <= u1; ++i) {
    consider_segment(i, q, best);
  }
  return best;
}

size_t Polyline::segment_at(double u) const {
  if (points_.size() < 2) {
    return 0;
  }
  const auto it = std::upper_bound(u_.begin(), u_.end(), u);
  const size_t i = it == u_.begin() ? 0 : static_cast<size_t>(it - u_.begin()) - 1;
  return std::min(i, points_.size() - 2);
}

Point3 Polyline::at(double u) const {
  if (points_.size() < 2) {
    return points_.empty() ? Point3{} : points_[0];
  }
  u = std::clamp(u, 0.0, length());
  const size_t i = segment_at(u);
  const double len = u_[i + 1] - u_[i];
  const double f = len > 0.0 ? (u - u_[i]) / len : 0.0;
  const Point3& a = points_[i];
  const Point3& b = points_[i + 1];
  return {a.x + f * (b.x - a.x), a.y + f * (b.y - a.y), a.z + f * (b.z - a.z)};
}

Vec2 Polyline::direction(double u) const {
  if (points_.size() < 2) {
    return {1.0, 0.0};
  }
  return segment_direction(segment_at(u));
}

std::vector<Point3> Polyline::slice(double u0, double u1) const {
  std::vector<Point3> out;
  out.push_back(at(u0));
  for (size_t i = 0; i < points_.size(); ++i) {
    if (u_[i] > u0 + 1e-6 && u_[i] < u1 - 1e-6) {
      out.push_back(points_[i]);
    }
  }
  out.push_back(at(u1));
  return out;
}

size_t remove_duplicates(std::vector<Point3>& points, double min_gap) {
  if (points.empty()) {
    return 0;
  }
  size_t kept = 1;
  for (size_t i = 1; i < points.size(); ++i) {
    if (norm(xy(points[i]) - xy(points[kept - 1])) >= min_gap) {
      points[kept++] = points[i];
    }
  }
  // Keep the true end point when the last vertices were within min_gap of each other.
  if (kept >= 2 && kept < points.size()) {
    points[kept - 1] = points.back();
  }
  const size_t dropped = points.size() - kept;
  points.resize(kept);
  return dropped;
}

}  // namespace corsa::ngii::detail

namespace corsa::ngii::detail {
namespace {

constexpr double kSampleStep = 0.25;    // m: resampling step of the smoothing
constexpr double kMinSigma = 0.3;       // m
constexpr double kMaxSigma = 2.0;       // m
constexpr double kCurvatureSpan = 2.5;  // m: half chord for the curvature estimate

/// Point at arc length u of the polyline extended by odd reflection past both ends.
Point3 reflected(const Polyline& line, double u) {
  const double length = line.length();
  if (u < 0.0) {
    const Point3 a = line.at(0.0);
    const Point3 b = line.at(std::min(-u, length));
    return {2 * a.x - b.x, 2 * a.y - b.y, 2 * a.z - b.z};
  }
  if (u > length) {
    const Point3 a = line.at(length);
    const Point3 b = line.at(std::max(2 * length - u, 0.0));
    return {2 * a.x - b.x, 2 * a.y - b.y, 2 * a.z - b.z};
  }
  return line.at(u);
}

}  // namespace

std::vector<Point3> smooth_polyline(const std::vector<Point3>& points, double max_bias,
                                    double max_shift) {
  const Polyline line(points);
  const double length = line.length();
  if (points.size() < 3 || length < 4.0 * kMinSigma) {
    return points;
  }
  // Uniform samples, with a margin of 3 max sigmas on both sides.
  const double margin = 3.0 * kMaxSigma;
  const int count = static_cast<int>(std::ceil((length + 2 * margin) / kSampleStep)) + 1;
  std::vector<Point3> samples(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) {
    samples[static_cast<size_t>(i)] = reflected(line, -margin + i * kSampleStep);
  }
  const auto sample_index = [&](double u) {
    return std::clamp(static_cast<int>(std::lround((u + margin) / kSampleStep)), 0, count - 1);
  };
  std::vector<Point3> out(points);
  for (size_t v = 1; v + 1 < points.size(); ++v) {
    const double u = line.u()[v];
    // Curvature from the turn between the chords before and after the vertex.
    const Point3 a = samples[static_cast<size_t>(sample_index(u - kCurvatureSpan))];
    const Point3 m = samples[static_cast<size_t>(sample_index(u))];
    const Point3 b = samples[static_cast<size_t>(sample_index(u + kCurvatureSpan))];
    const double turn =
        std::abs(angle_diff(std::atan2(b.y - m.y, b.x - m.x), std::atan2(m.y - a.y, m.x - a.x)));
    const double curvature = turn / kCurvatureSpan;
    const double sigma = std::clamp(
        curvature > 0.0 ? std::sqrt(2.0 * max_bias / curvature) : kMaxSigma, kMinSigma, kMaxSigma);
    const int centre = sample_index(u);
    const int half = static_cast<int>(std::ceil(3.0 * sigma / kSampleStep));
    double wx = 0.0, x = 0.0, y = 0.0;
    for (int k = -half; k <= half; ++k) {
      const Point3& p = samples[static_cast<size_t>(std::clamp(centre + k, 0, count - 1))];
      const double d = k * kSampleStep;
      const double w = std::exp(-0.5 * d * d / (sigma * sigma));
      wx += w;
      x += w * p.x;
      y += w * p.y;
    }
    // Never further than max_shift from the surveyed vertex (sharp corners, real or not, are
    // cut by at most that much). Heights stay as surveyed: the elevation fit follows them within
    // its tolerance.
    Point3 smooth{x / wx, y / wx, points[v].z};
    const Vec2 shift = xy(smooth) - xy(points[v]);
    const double moved = norm(shift);
    if (moved > max_shift) {
      smooth.x = points[v].x + shift.x * max_shift / moved;
      smooth.y = points[v].y + shift.y * max_shift / moved;
    }
    out[v] = smooth;
  }
  // Vertices closer together than twice max_shift can swap order once smoothed: drop those
  // that step backwards or (almost) nowhere.
  std::vector<Point3> kept;
  kept.reserve(out.size());
  for (size_t v = 0; v < out.size(); ++v) {
    if (kept.size() >= 1 && v + 1 < out.size()) {
      const Vec2 step = xy(out[v]) - xy(kept.back());
      const Vec2 ahead = xy(out[v + 1]) - xy(kept.back());
      if (norm(step) < 0.05 || dot(step, ahead) <= 0.0) {
        continue;
      }
    }
    if (v + 1 == out.size() && kept.size() > 1 && norm(xy(out[v]) - xy(kept.back())) < 0.05) {
      kept.back() = out[v];  // the true end replaces a vertex right next to it
      continue;
    }
    kept.push_back(out[v]);
  }
  return kept;
}

}  // namespace corsa::ngii::detail
