#pragma once

// Planar polyline helpers for the converter: arc length, projection of a point (with its signed
// lateral offset, + to the left of the direction of travel), interpolation.

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "corsa/core/vec.h"
#include "corsa/ngii/layers.h"

namespace corsa::ngii::detail {

using Vec2 = corsa::Vec2;

/// Where a point falls on a polyline.
struct Projection {
  double u = 0.0;         ///< arc length of the foot point (m)
  double distance = 0.0;  ///< distance to the foot point (m)
  double lateral = 0.0;   ///< signed offset: + left of the polyline's direction
  double along = 0.0;     ///< before the start (< 0) or past the end (> 0), else 0
  size_t segment = 0;
};

/// A polyline with cumulative arc lengths; consecutive duplicate vertices must be removed first.
class Polyline {
 public:
  Polyline() = default;
  explicit Polyline(std::span<const Point3> points);

  size_t size() const { return points_.size(); }
  double length() const { return u_.empty() ? 0.0 : u_.back(); }
  const std::vector<Point3>& points() const { return points_; }
  const std::vector<double>& u() const { return u_; }

  /// Nearest point (ends extended along their segments for the `along` report).
  Projection project(Vec2 q) const;
  /// Nearest point among the segments overlapping arc lengths [u0, u1].
  Projection project_within(Vec2 q, double u0, double u1) const;
  /// Position (x, y, z) at arc length u (clamped to the polyline).
  Point3 at(double u) const;
  /// Unit direction at arc length u (of the segment containing it).
  Vec2 direction(double u) const;
  /// Direction of segment i.
  Vec2 segment_direction(size_t i) const;
  /// Index of the segment containing arc length u.
  size_t segment_at(double u) const;
  /// The sub-polyline between arc lengths u0 < u1.
  std::vector<Point3> slice(double u0, double u1) const;

 private:
  /// Bounding box of a run of kBlock segments, to skip far parts of long polylines.
  struct Block {
    double x0, y0, x1, y1;
    double distance(Vec2 q) const {
      const double dx = std::max({x0 - q.x, 0.0, q.x - x1});
      const double dy = std::max({y0 - q.y, 0.0, q.y - y1});
      return std::sqrt(dx * dx + dy * dy);
    }
  };
  static constexpr size_t kBlock = 16;
  void consider_segment(size_t i, Vec2 q, Projection& best) const;

  std::vector<Point3> points_;
  std::vector<double> u_;
  std::vector<Block> blocks_;
};

/// Copies `points` without consecutive vertices closer than `min_gap` (m); returns how many
/// were dropped.
size_t remove_duplicates(std::vector<Point3>& points, double min_gap = 1e-3);

/// Heading difference a - b wrapped to (-pi, pi].
inline double angle_diff(double a, double b) { return std::remainder(a - b, 2.0 * M_PI); }

}  // namespace corsa::ngii::detail

namespace corsa::ngii::detail {

/// Survey noise removal: a Gaussian average along the arc length whose width adapts to the
/// local curvature, so that the shift it causes on a curve (about sigma^2 curvature / 2) stays
/// below `max_bias` (m); sigma is between 0.3 m (tight turns) and 2 m (straights). The ends are
/// kept (odd reflection); no vertex moves more than `max_shift` (m); vertices that would step
/// backwards are dropped. Heights are kept as surveyed.
std::vector<Point3> smooth_polyline(const std::vector<Point3>& points, double max_bias = 0.01,
                                    double max_shift = 0.04);

}  // namespace corsa::ngii::detail
