// Junction mouths where a junction path enters a road: the path ends as wide as the road's lane
// at a corner, and the road after a path that cannot take its start line starts on the path's
// end line (mouth_gaps.h; the shared layers in mouth_layers.h).

#include <catch2/catch.hpp>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/ngii/convert.h"
#include "corsa/xodr/geometry.h"
#include "mouth_layers.h"
#include "reference_line.h"

namespace {

using corsa::ngii::Layers;
using corsa::ngii::testing::mouth_gaps_of;
using corsa::ngii::testing::MouthLayers;

/// A 7 m path leaves a road heading 9 degrees south of east at 26 degrees to its end line,
/// turns left along its length and enters a road E (two vertices, 30 m) heading 38 degrees
/// north of east at a corner of 3 degrees; without `path` the two roads end apart. With `next`
/// a road F continues E straight on for 20 m.
MouthLayers corner_path(bool path, bool next = false) {
  MouthLayers b;
  const double a = -9.4 * M_PI / 180.0;
  const double e = 38.0 * M_PI / 180.0;
  const double ex = 6.69, ey = 4.12;
  const auto along = [](double x, double y, double h, double d, double t) {
    return std::pair<double, double>{x + d * std::cos(h) - t * std::sin(h),
                                     y + d * std::sin(h) + t * std::cos(h)};
  };
  b.node("A0", -30.0 * std::cos(a), -30.0 * std::sin(a));
  b.node("A1", 0.0, 0.0);
  b.node("E0", ex, ey);
  b.node("E1", ex + 30.0 * std::cos(e), ey + 30.0 * std::sin(e));
  b.link("A2TEST00000A", "6", 1, "A0", "A1");
  if (path) {
    b.path_through("A2TEST00000P", "A1", "E0",
                   {{0.0, 0.0}, {1.47, 0.42}, {3.23, 1.43}, {5.29, 2.93}, {ex, ey}});
  }
  b.link("A2TEST00000E", "6", 1, "E0", "E1");
  if (next) {
    b.node("E2", ex + 50.0 * std::cos(e), ey + 50.0 * std::sin(e));
    b.link("A2TEST00000F", "6", 1, "E1", "E2");
  }
  for (const double t : {1.6, -1.6}) {
    const std::string side = t > 0.0 ? "L" : "R";
    const std::string right = t > 0.0 ? "A2TEST00000" : "", left = t > 0.0 ? "" : "A2TEST00000";
    b.mark_through("B2A" + side, {along(0.0, 0.0, a, -30.0, t), along(0.0, 0.0, a, 0.0, t)},
                   right.empty() ? "" : right + "A", left.empty() ? "" : left + "A");
    b.mark_through("B2E" + side, {along(ex, ey, e, 0.0, t), along(ex, ey, e, 30.0, t)},
                   right.empty() ? "" : right + "E", left.empty() ? "" : left + "E");
    if (next) {
      b.mark_through("B2F" + side, {along(ex, ey, e, 30.0, t), along(ex, ey, e, 50.0, t)},
                     right.empty() ? "" : right + "F", left.empty() ? "" : left + "F");
    }
  }
  return b;
}

/// Where the road holding link `link` ends (map frame), and its heading there.
corsa::xodr::RefPoint road_end_of(const Layers& layers, const std::string& link) {
  corsa::Diagnostics diagnostics;
  const auto conversion = corsa::ngii::convert(layers, {}, diagnostics);
  for (const auto& p : conversion.placements) {
    if (p.link_id != link) {
      continue;
    }
    for (const auto& road : conversion.map.roads) {
      if (road.id == p.road_id && !road.plan_view.empty()) {
        const auto& g = road.plan_view.back();
        return corsa::xodr::evaluate_geometry(g, g.length);
      }
    }
  }
  FAIL("no road holds " << link);
  return {};
}

/// A one-lane road A east to x = 30, a junction path from its end curving right to heading
/// `arrive` (degrees, negative south of east) at node E0, and a one-lane road E leaving E0 at
/// heading `leave`: the links meet at a corner of leave - arrive at E0. A's and E's marks lie
/// `half` either side of them; the path has none (it takes its lanes' widths).
MouthLayers path_into_corner(double arrive, double leave, double half) {
  MouthLayers b;
  const double h1 = arrive * M_PI / 180.0;
  const double h2 = leave * M_PI / 180.0;
  // The path: 6 m east, then an arc to `arrive` over 6 m, then 4 m straight (vertices a
  // metre apart on the straights).
  std::vector<std::pair<double, double>> xy;
  for (int i = 0; i <= 6; ++i) {
    xy.push_back({30.0 + i, 0.0});
  }
  const double radius = 6.0 / std::abs(h1);
  for (int i = 1; i <= 6; ++i) {
    const double a = h1 * i / 6.0;
    xy.push_back({36.0 + radius * std::sin(-a), -radius * (1.0 - std::cos(a))});
  }
  const auto [cx, cy] = xy.back();
  for (int i = 1; i <= 4; ++i) {
    xy.push_back({cx + i * std::cos(h1), cy + i * std::sin(h1)});
  }
  const auto [ex, ey] = xy.back();
  b.node("A0", 0.0, 0.0);
  b.node("A1", 30.0, 0.0);
  b.node("E0", ex, ey);
  b.node("E1", ex + 30.0 * std::cos(h2), ey + 30.0 * std::sin(h2));
  b.link("A2TEST00000A", "6", 1, "A0", "A1");
  b.path_through("A2TEST00000P", "A1", "E0", xy);
  b.link("A2TEST00000E", "6", 1, "E0", "E1");
  b.mark("B2AL", 0.0, 30.0, half, "A2TEST00000A", "");
  b.mark("B2AR", 0.0, 30.0, -half, "", "A2TEST00000A");
  const auto side = [&](double t, double d) {
    return std::pair<double, double>{ex + d * std::cos(h2) - t * std::sin(h2),
                                     ey + d * std::sin(h2) + t * std::cos(h2)};
  };
  b.mark_through("B2EL", {side(half, 0.0), side(half, 30.0)}, "A2TEST00000E", "");
  b.mark_through("B2ER", {side(-half, 0.0), side(-half, 30.0)}, "", "A2TEST00000E");
  return b;
}

/// The width of the lane holding link `link` where its road ends (`at_end`) or starts, and the
/// road's heading (rad) there.
struct LaneEndWidth {
  double width = 0.0;
  double heading = 0.0;
};
LaneEndWidth lane_end_width(const corsa::xodr::MapData& map, const std::string& link, bool at_end) {
  for (const auto& road : map.roads) {
    for (const auto& lane : road.lane_sections.front().lanes) {
      if (lane.user_data.empty() || lane.user_data.front().value != link ||
          road.plan_view.empty()) {
        continue;
      }
      const auto& g = at_end ? road.plan_view.back() : road.plan_view.front();
      return {corsa::ngii::detail::piecewise_value(lane.widths, at_end ? road.length : 0.0),
              corsa::xodr::evaluate_geometry(g, at_end ? g.length : 0.0).hdg};
    }
  }
  FAIL("no lane holds " << link);
  return {};
}

size_t shoulders_of(const corsa::xodr::MapData& map) {
  size_t n = 0;
  for (const auto& road : map.roads) {
    for (const auto& lane : road.lane_sections.front().lanes) {
      n += lane.type == corsa::xodr::LaneType::kShoulder;
    }
  }
  return n;
}

}  // namespace

TEST_CASE(
    "a road after a junction path that cannot take its start line starts on the path's end line",
    "[ngii][mouths]") {
  // Bent square to both joined lines within its length, the path's reference line needed a
  // corner tighter than the fit allows (a kink), so it keeps its own square end, and the road
  // after it started square to its own course: a sliver of unpaved ground on one side of the
  // joint. That road now starts on the path's end line.
  const auto gaps = mouth_gaps_of(corner_path(true).layers);
  INFO(gaps.worst);
  CHECK(gaps.ends >= 4);
  CHECK(gaps.over == 0);
  CHECK(gaps.max < 0.1);
}

TEST_CASE("a road rebuilt onto a junction path's end line keeps its other end",
          "[ngii][mouths][!shouldfail]") {
  // Road E is built again once the path is built, bent to the path's end line at its start.
  // Its end should stay where road F was built on it, as it is without the path; the refit
  // moves it by 1.1 mm and 1.8 mrad (the fit runs from E's start). Kept for now (shouldfail):
  // not rebuilding such roads reopened a wedge of 0.75 m at K-City's road 187.
  const auto joined = road_end_of(corner_path(true, true).layers, "A2TEST00000E");
  const auto alone = road_end_of(corner_path(false, true).layers, "A2TEST00000E");
  CHECK(joined.x == Approx(alone.x).margin(1e-9));
  CHECK(joined.y == Approx(alone.y).margin(1e-9));
  CHECK(joined.hdg == Approx(alone.hdg).margin(1e-9));
}

TEST_CASE("a junction path entering a road at a corner of 30 degrees ends as wide as its lane",
          "[ngii][mouths]") {
  // The path's link arrives 30 degrees off the road it enters (Sangam's four paths into road
  // 196: 29 degrees) and ends on that road's start line, bent to it. Its end width is the
  // lane's times the cosine of the corner (the width across its own link), which the road
  // builder divides by the cosine of the angle between the link and the bent reference line;
  // that link direction was a chord reaching 1.5 m into the road after it (half the corner),
  // so the path ended 0.56 m narrower than the lane, and a shoulder on each side paved the
  // step (Sangam's four stacked paths got none: a 0.20 m gap on each side of road 196's start).
  const MouthLayers b = path_into_corner(-15.0, -45.0, 2.65);
  const auto gaps = mouth_gaps_of(b.layers);
  INFO(gaps.worst);
  CHECK(gaps.ends >= 4);
  CHECK(gaps.over == 0);
  CHECK(gaps.max < 0.1);
  corsa::Diagnostics diagnostics;
  const auto conversion = corsa::ngii::convert(b.layers, {}, diagnostics);
  const LaneEndWidth path = lane_end_width(conversion.map, "A2TEST00000P", true);
  const LaneEndWidth lane = lane_end_width(conversion.map, "A2TEST00000E", false);
  CHECK(std::abs(std::remainder(path.heading - lane.heading, 2.0 * M_PI)) < 0.01);
  CHECK(path.width == Approx(lane.width).margin(0.15));
  CHECK(shoulders_of(conversion.map) == 0);
}

TEST_CASE(
    "a junction path keeping its own end line at 50 degrees to the road it enters spans that "
    "road's lane",
    "[ngii][mouths]") {
  // The path cannot turn 50 degrees onto the road's start line (Sangam's paths 1017, 1019 and
  // 1024 into road 504: 46-52 degrees), so it ends square to its own course, as wide as the
  // road's lane spans across it (the lane's width times the cosine of the corner). The road
  // builder divided that by the cosine of half the corner (the chord into the road after it),
  // so the path stuck out 0.2 m beyond the lane on each side (a 0.15 m sliver beside road 504).
  const MouthLayers b = path_into_corner(-5.0, -55.0, 2.9);
  corsa::Diagnostics diagnostics;
  const auto conversion = corsa::ngii::convert(b.layers, {}, diagnostics);
  const LaneEndWidth path = lane_end_width(conversion.map, "A2TEST00000P", true);
  const LaneEndWidth lane = lane_end_width(conversion.map, "A2TEST00000E", false);
  const double corner = std::remainder(path.heading - lane.heading, 2.0 * M_PI);
  CHECK(std::abs(corner) > 0.8);
  CHECK(path.width == Approx(lane.width * std::cos(corner)).margin(0.05));
}
