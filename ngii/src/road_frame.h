#pragma once

// A converted road's reference line sampled every half metre, for placing marks and signals:
// world point -> (s, t), and lane border offsets at s from the road's laneOffset and widths.

#include <vector>

#include "corsa/xodr/model.h"
#include "polyline.h"
#include "reference_line.h"

namespace corsa::ngii::detail {

class RoadFrame {
 public:
  explicit RoadFrame(const xodr::Road& road);

  struct Position {
    double s = 0.0;
    double t = 0.0;
    double outside = 0.0;  ///< how far (m) the point's foot lies before 0 / past the length
  };
  Position project(Vec2 point) const;
  /// Heading of the reference line at s.
  double heading(double s) const;
  /// t of the border between lane index k-1 and k (k = 0: the centre lane's border, i.e. the
  /// laneOffset; k = n: the outer border of the last lane). Lanes are the section's right lanes.
  double border(double s, size_t k) const;
  size_t lane_count() const;
  const xodr::Road& road() const { return road_; }
  /// Distance (m) from a point to the bounding box of the reference line (0 inside).
  double box_distance(Vec2 point) const;
  /// Gap (m) between the bounding boxes of two reference lines (0 where they overlap).
  double box_gap(const RoadFrame& other) const;

 private:
  const xodr::Road& road_;
  std::vector<double> s_;
  std::vector<RefSample> samples_;
  Polyline line_;  ///< the samples as a polyline, for fast nearest-point queries
  double x0_ = 0.0, y0_ = 0.0, x1_ = 0.0, y1_ = 0.0;
};

}  // namespace corsa::ngii::detail
