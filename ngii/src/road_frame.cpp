#include "road_frame.h"

#include <algorithm>
#include <cmath>

namespace corsa::ngii::detail {

RoadFrame::RoadFrame(const xodr::Road& road) : road_(road) {
  const int count = std::max(1, static_cast<int>(std::ceil(road.length / 0.5)));
  s_.resize(static_cast<size_t>(count) + 1);
  for (int i = 0; i <= count; ++i) {
    s_[static_cast<size_t>(i)] = road.length * i / count;
  }
  samples_ = sample_reference(road.plan_view, s_);
  std::vector<Point3> points;
  points.reserve(samples_.size());
  for (const RefSample& sample : samples_) {
    if (points.empty() ||
        norm(Vec2{sample.x - points.back().x, sample.y - points.back().y}) > 1e-9) {
      points.push_back(Point3{sample.x, sample.y, 0.0});
    }
  }
  line_ = Polyline(points);
  x0_ = x1_ = points.front().x;
  y0_ = y1_ = points.front().y;
  for (const Point3& p : points) {
    x0_ = std::min(x0_, p.x);
    x1_ = std::max(x1_, p.x);
    y0_ = std::min(y0_, p.y);
    y1_ = std::max(y1_, p.y);
  }
}

double RoadFrame::box_distance(Vec2 point) const {
  const double dx = std::max({x0_ - point.x, 0.0, point.x - x1_});
  const double dy = std::max({y0_ - point.y, 0.0, point.y - y1_});
  return std::hypot(dx, dy);
}

double RoadFrame::box_gap(const RoadFrame& other) const {
  const double dx = std::max({x0_ - other.x1_, 0.0, other.x0_ - x1_});
  const double dy = std::max({y0_ - other.y1_, 0.0, other.y0_ - y1_});
  return std::hypot(dx, dy);
}

RoadFrame::Position RoadFrame::project(Vec2 point) const {
  // The samples are 0.5 m apart, so chord length and road s agree to well under a millimetre.
  const Projection p = line_.project(point);
  Position position;
  const double scale = line_.length() > 0.0 ? road_.length / line_.length() : 1.0;
  position.s = std::clamp(p.u * scale, 0.0, road_.length);
  position.outside = p.along;
  position.t = p.lateral;
  return position;
}

double RoadFrame::heading(double s) const {
  const auto it = std::upper_bound(s_.begin(), s_.end(), s);
  const size_t i = it == s_.begin() ? 0 : static_cast<size_t>(it - s_.begin()) - 1;
  return samples_[std::min(i, samples_.size() - 1)].hdg;
}

size_t RoadFrame::lane_count() const { return road_.lane_sections.front().lanes.size() - 1; }

double RoadFrame::border(double s, size_t k) const {
  double t = piecewise_value(road_.lane_offsets, s);
  const auto& lanes = road_.lane_sections.front().lanes;  // [0] centre, then -1, -2, ...
  for (size_t j = 1; j <= k && j < lanes.size(); ++j) {
    t -= piecewise_value(lanes[j].widths, s);
  }
  return t;
}

}  // namespace corsa::ngii::detail
