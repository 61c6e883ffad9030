// A junction's area for the holes search (junction_area.h).

#include "junction_area.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace corsa::xodr::detail {
namespace {

constexpr double kOutlineStep = 0.5;  // m between samples along a boundary lane segment

double hull_turn(const Vec2d& o, const Vec2d& a, const Vec2d& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

/// The outer border of `lane` on road r at s, in the map frame; nothing where the lane is absent.
std::optional<Vec2d> lane_border(const Map& map, size_t r, double s, int lane) {
  const auto span = map.lane_span(r, s, lane);
  if (!span) {
    return std::nullopt;
  }
  const WorldPose p = map.world_pose(r, s, span->t_outer);
  return Vec2d{p.x, p.y};
}

/// A joint segment's two ends: the outer borders of its lanes (the outermost lanes on both sides
/// when it names none), ordered from the start lane, or nearest the outline so far first.
void add_joint(const Map& map, size_t r, const JunctionBoundarySegment& segment,
               std::vector<Vec2d>& outline) {
  const double s = segment.contact_point == ContactPoint::kEnd ? map.road(r).length : 0.0;
  std::vector<LaneSpan> spans;
  map.lane_spans(r, s, spans);
  if (spans.empty()) {
    return;
  }
  auto border_of = [&](std::optional<int> lane, bool left) -> std::optional<Vec2d> {
    if (lane) {
      return lane_border(map, r, s, *lane);
    }
    // Spans run left to right.
    const WorldPose p = map.world_pose(r, s, left ? spans.front().t_max() : spans.back().t_min());
    return Vec2d{p.x, p.y};
  };
  std::optional<Vec2d> a = border_of(segment.joint_lane_start, true);
  std::optional<Vec2d> b = border_of(segment.joint_lane_end, false);
  if (!a || !b) {
    return;
  }
  if (!segment.joint_lane_start && !segment.joint_lane_end && !outline.empty()) {
    const Vec2d& last = outline.back();
    if (std::hypot(b->x - last.x, b->y - last.y) < std::hypot(a->x - last.x, a->y - last.y)) {
      std::swap(a, b);
    }
  }
  outline.push_back(*a);
  outline.push_back(*b);
}

}  // namespace

std::vector<Vec2d> convex_hull(std::vector<Vec2d> points) {
  std::sort(points.begin(), points.end(),
            [](const Vec2d& a, const Vec2d& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  if (points.size() < 3) {
    return points;
  }
  std::vector<Vec2d> hull(2 * points.size());
  size_t k = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && hull_turn(hull[k - 2], hull[k - 1], points[i]) <= 0.0) {
      --k;
    }
    hull[k++] = points[i];
  }
  for (size_t i = points.size() - 1, lower = k + 1; i > 0; --i) {
    while (k >= lower && hull_turn(hull[k - 2], hull[k - 1], points[i - 1]) <= 0.0) {
      --k;
    }
    hull[k++] = points[i - 1];
  }
  hull.resize(k - 1);
  return hull;
}

void fill_row(const std::vector<Vec2d>& polygon, double y, double x0, double cell,
              std::vector<double>& crossings, uint8_t* row, int nx) {
  crossings.clear();
  for (size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Vec2d& a = polygon[i];
    const Vec2d& b = polygon[j];
    if ((a.y > y) != (b.y > y)) {
      crossings.push_back(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
    }
  }
  std::sort(crossings.begin(), crossings.end());
  for (size_t k = 0; k + 1 < crossings.size(); k += 2) {
    // Cells whose centre x lies in (crossings[k], crossings[k + 1]).
    const int first = std::max(0, static_cast<int>(std::floor((crossings[k] - x0) / cell + 0.5)));
    const int last =
        std::min(nx - 1, static_cast<int>(std::ceil((crossings[k + 1] - x0) / cell - 0.5)) - 1);
    for (int ix = first; ix <= last; ++ix) {
      row[ix] = 1;
    }
  }
}

std::vector<Vec2d> boundary_outline(const Map& map, const Junction& junction) {
  std::vector<Vec2d> outline;
  for (const JunctionBoundarySegment& segment : junction.boundary) {
    const auto r = map.find_road(segment.road_id);
    if (!r) {
      return {};
    }
    if (segment.joint) {
      add_joint(map, *r, segment, outline);
      continue;
    }
    const double length = map.road(*r).length;
    const double s0 = std::min(segment.s_start, length), s1 = std::min(segment.s_end, length);
    const int n = std::max(1, static_cast<int>(std::ceil(std::abs(s1 - s0) / kOutlineStep)));
    for (int i = 0; i <= n; ++i) {
      if (const auto p = lane_border(map, *r, s0 + (s1 - s0) * i / n, segment.boundary_lane)) {
        outline.push_back(*p);
      }
    }
  }
  return outline.size() >= 3 ? outline : std::vector<Vec2d>{};
}

}  // namespace corsa::xodr::detail
