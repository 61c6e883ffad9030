#include <algorithm>
#include <cmath>

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

// offset_poly_value without the binary search for the usual lane of one record (the same
// record the search would pick: the first one also serves ds before its start).
double poly_at(const std::vector<Poly3>& records, double ds) {
  return records.size() == 1 ? records.front().value(ds) : offset_poly_value(records, ds);
}

double outer_border(const Lane& lane, double ds, double inner, double side) {
  if (!lane.widths.empty()) {
    return inner + side * std::max(0.0, poly_at(lane.widths, ds));
  }
  if (!lane.borders.empty()) {
    return poly_at(lane.borders, ds);
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

bool compute_span(const LaneSection& section, double s, double offset, int lane_id, LaneSpan& out) {
  const double ds = s - section.s;
  const size_t n = section.lanes.size();
  const size_t center = center_index(section);
  // The lanes before the centre index all have positive ids (center_index), so a negative id is
  // only looked for on the right; a positive one on the left first, then on the right as
  // compute_spans would (ids are sorted and unique, so it is on the left).
  if (lane_id > 0) {
    double t = offset;
    for (size_t i = center; i-- > 0;) {
      const Lane& lane = section.lanes[i];
      const double outer = outer_border(lane, ds, t, 1.0);
      if (lane.id == lane_id) {
        out = LaneSpan{lane.id, t, outer};
        return true;
      }
      t = outer;
    }
  }
  const bool has_center = center < n && section.lanes[center].id == 0;
  double t = offset;
  for (size_t i = center + (has_center ? 1 : 0); i < n; ++i) {
    const Lane& lane = section.lanes[i];
    const double outer = outer_border(lane, ds, t, -1.0);
    if (lane.id == lane_id) {
      out = LaneSpan{lane.id, t, outer};
      return true;
    }
    t = outer;
  }
  return false;
}

bool nearest_lane(const LaneSection& section, double s, double offset, double t, bool drivable_only,
                  NearestLane& out) {
  const double ds = s - section.s;
  const size_t n = section.lanes.size();
  const size_t center = center_index(section);
  const bool has_center = center < n && section.lanes[center].id == 0;
  bool found = false;
  const auto consider = [&](const Lane& lane, double inner, double outer) {
    const LaneSpan span{lane.id, inner, outer};
    if (span.width() <= 0.0 || (drivable_only && !is_drivable(lane.type))) {
      return;
    }
    const double gap = t < span.t_min()   ? span.t_min() - t
                       : t > span.t_max() ? t - span.t_max()
                                          : 0.0;
    const double from_center = std::abs(t - span.t_center());
    // Nearest lane; on a shared border the inner lane (smaller |id|) wins; outside every lane,
    // the one whose centre is nearer.
    if (!found || gap < out.gap ||
        (gap == out.gap &&
         (gap > 0.0 ? from_center < out.center_offset : std::abs(lane.id) < std::abs(out.lane)))) {
      out = NearestLane{lane.id, gap, from_center};
      found = true;
    }
  };
  double inner = offset;
  for (size_t i = center; i-- > 0;) {
    const double outer = outer_border(section.lanes[i], ds, inner, 1.0);
    consider(section.lanes[i], inner, outer);
    inner = outer;
  }
  inner = offset;
  for (size_t i = center + (has_center ? 1 : 0); i < n; ++i) {
    const double outer = outer_border(section.lanes[i], ds, inner, -1.0);
    consider(section.lanes[i], inner, outer);
    inner = outer;
  }
  return found;
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
