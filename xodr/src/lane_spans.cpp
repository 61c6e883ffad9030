#include <algorithm>

#include "road_eval.h"

namespace corsa::xodr::detail {

size_t center_index(const LaneSection& section) {
  for (size_t i = 0; i < section.lanes.size(); ++i) {
    if (section.lanes[i].id <= 0) {
      return i;
    }
  }
  return section.lanes.size();
}

namespace {

double outer_border(const Lane& lane, double ds, double inner, double side) {
  if (!lane.widths.empty()) {
    return inner + side * std::max(0.0, offset_poly_value(lane.widths, ds));
  }
  if (!lane.borders.empty()) {
    return offset_poly_value(lane.borders, ds);
  }
  return inner;  // a lane with neither has no width
}

}  // namespace

size_t compute_spans(const LaneSection& section, double s, double offset, LaneSpan* out) {
  const double ds = s - section.s;
  const size_t n = section.lanes.size();
  const size_t center = center_index(section);
  // Left lanes: from the centre outward (ids 1, 2, ...), which is backwards in `lanes`.
  size_t count = 0;
  double t = offset;
  for (size_t i = center; i-- > 0;) {
    const Lane& lane = section.lanes[i];
    const double outer = outer_border(lane, ds, t, 1.0);
    out[i] = LaneSpan{lane.id, t, outer};
    t = outer;
    ++count;
  }
  const bool has_center = center < n && section.lanes[center].id == 0;
  t = offset;
  for (size_t i = center + (has_center ? 1 : 0); i < n; ++i) {
    const Lane& lane = section.lanes[i];
    const double outer = outer_border(lane, ds, t, -1.0);
    out[i - (has_center ? 1 : 0)] = LaneSpan{lane.id, t, outer};
    t = outer;
    ++count;
  }
  return count;
}

bool find_lane_at(const LaneSection& section, double s, double offset, double t, LaneSpan& out) {
  const double ds = s - section.s;
  const size_t n = section.lanes.size();
  const size_t center = center_index(section);
  const bool has_center = center < n && section.lanes[center].id == 0;
  double inner = offset;
  if (t >= offset) {
    for (size_t i = center; i-- > 0;) {
      const Lane& lane = section.lanes[i];
      const double outer = outer_border(lane, ds, inner, 1.0);
      if (outer > inner && t <= outer) {
        out = LaneSpan{lane.id, inner, outer};
        return true;
      }
      inner = std::max(inner, outer);
    }
    return false;
  }
  for (size_t i = center + (has_center ? 1 : 0); i < n; ++i) {
    const Lane& lane = section.lanes[i];
    const double outer = outer_border(lane, ds, inner, -1.0);
    if (outer < inner && t >= outer) {
      out = LaneSpan{lane.id, inner, outer};
      return true;
    }
    inner = std::min(inner, outer);
  }
  return false;
}

}  // namespace corsa::xodr::detail
