// Roads whose lane borders fold over themselves (mesh_folds.h), on small synthetic layers: each
// case is one cause that folded roads of the sample areas.

#include <catch2/catch.hpp>
#include <cmath>
#include <variant>

#include "border_solver.h"
#include "corsa/ngii/convert.h"
#include "corsa/xodr/map.h"
#include "mesh_folds.h"
#include "polyline.h"
#include "road_reference.h"

namespace {

using corsa::ngii::Layers;
using corsa::ngii::Link;
using corsa::ngii::Node;
using corsa::ngii::Point3;

/// One ordinary lane along `points` (UTM-like coordinates), its two end nodes.
Layers one_lane(std::vector<Point3> points) {
  Layers layers;
  layers.node_file = "A1_NODE.dbf";
  layers.link_file = "A2_LINK.dbf";
  layers.nodes.push_back(
      Node{.id = "N1", .node_type = "99", .position = points.front(), .record = 0});
  layers.nodes.push_back(
      Node{.id = "N2", .node_type = "99", .position = points.back(), .record = 1});
  Link link{.id = "A2TEST000001",
            .link_type = "6",
            .road_rank = "",
            .road_type = "1",
            .road_no = "",
            .lane_no = 1,
            .max_speed = 0,
            .right_id = "",
            .left_id = "",
            .from_node = "N1",
            .to_node = "N2",
            .length_attr = 0.0,
            .points = std::move(points),
            .record = 0};
  for (size_t i = 1; i < link.points.size(); ++i) {
    link.length_attr += std::hypot(link.points[i].x - link.points[i - 1].x,
                                   link.points[i].y - link.points[i - 1].y);
  }
  layers.links.push_back(std::move(link));
  return layers;
}

/// Smallest curvature (1/m, most negative: the tightest right turn) of the road's records.
double tightest_right_turn(const corsa::xodr::Road& road) {
  double k = 0.0;
  for (const auto& g : road.plan_view) {
    if (const auto* arc = std::get_if<corsa::xodr::ArcGeometry>(&g.shape)) {
      k = std::min(k, arc->curvature);
    } else if (const auto* spiral = std::get_if<corsa::xodr::SpiralGeometry>(&g.shape)) {
      k = std::min({k, spiral->curv_start, spiral->curv_end});
    }
  }
  return k;
}

}  // namespace

TEST_CASE("a lane over a survey jog of a few centimetres does not fold its right edge",
          "[ngii][folds]") {
  // A straight lane surveyed every 0.4 m whose vertices step 20 cm to the left between two
  // of them (a digitising jog as in K-City's A219BS010004). The plan-view records that meet
  // the data heading right after the step swing the curvature to -0.5 1/m and back: the
  // right edge of the 3.25 m lane lay beyond the centre of curvature there.
  std::vector<Point3> points;
  const double x0 = 300000.0, y0 = 4100000.0;
  for (int i = 0; i <= 112; ++i) {
    const double u = 0.4 * i;
    points.push_back({x0 + u, y0 + (u > 15.0 ? 0.2 : 0.0), 50.0});
  }
  corsa::Diagnostics diagnostics;
  const auto conversion = corsa::ngii::convert(one_lane(points), {}, diagnostics);
  const auto map = corsa::xodr::Map::build(conversion.map, diagnostics);
  REQUIRE(conversion.map.roads.size() == 1);
  const auto& road = conversion.map.roads.front();
  INFO("tightest right turn " << tightest_right_turn(road));
  CHECK(tightest_right_turn(road) > -1.0 / 3.25);
  CHECK(corsa::test::folded_roads(map) == 0);
  // The lane still follows the survey (the laneOffset takes up the eased reference line).
  CHECK(conversion.summary.max_lane_error <= 0.05);
}

TEST_CASE("a sparse lane that runs straight and then turns right starts along its first segment",
          "[ngii][folds]") {
  // A junction path as surveyed: 2 m straight (no vertex between), then a right turn at a
  // radius of 7 m with a vertex every 30 degrees. The start tangent extrapolated from two
  // chords (exact on a circle) pointed 0.1 rad to the left of the straight part, into the
  // outside of the turn; the plan view had to turn back within a metre and folded the lane's
  // right edge there (K-City's A219BS010543: 0.22 rad).
  std::vector<Point3> points{{0.0, 0.0, 0.0}};
  for (int k = 0; k <= 3; ++k) {
    const double a = k * M_PI / 6.0;
    points.push_back({2.0 + 7.0 * std::sin(a), -7.0 * (1.0 - std::cos(a)), 0.0});
  }
  const corsa::ngii::detail::Polyline lane(points);
  const auto reference = corsa::ngii::detail::shifted_left(lane, std::vector<double>(5, 2.0));
  CHECK(std::abs(reference.start_heading) < 1e-9);
}

TEST_CASE("a lane turning evenly from its first vertex starts along the circle's tangent",
          "[ngii][folds]") {
  // The same turn without the straight part: the corners at the first vertices are equal, so
  // the tangent is extrapolated from the two first chords as before (a circle).
  std::vector<Point3> points;
  for (int k = 0; k <= 30; ++k) {
    const double a = k * M_PI / 60.0;
    points.push_back({7.0 * std::sin(a), -7.0 * (1.0 - std::cos(a)), 0.0});
  }
  const corsa::ngii::detail::Polyline lane(points);
  const auto reference = corsa::ngii::detail::shifted_left(lane, std::vector<double>(31, 2.0));
  CHECK(reference.start_heading == Approx(0.0).margin(0.01));
  CHECK(reference.end_heading == Approx(-M_PI / 2.0).margin(0.01));
}

TEST_CASE("the outermost lane narrows on the inside of a turn tighter than it is wide",
          "[ngii][folds]") {
  using corsa::ngii::detail::LaneTarget;
  // One lane 3.5 m wide whose centre is 1.75 m right of the reference line, which turns right
  // at a radius of 2.5 m: its right border (t = -3.5) would lie 1 m beyond the centre of
  // curvature (t = -2.5), where the normals cross and the border folds back.
  std::vector<LaneTarget> lanes{{-1.75, 3.5, true}};
  corsa::ngii::detail::narrow_inside_of_turn(lanes, -0.4, 0.5, 0.2);
  const auto borders = corsa::ngii::detail::solve_borders(lanes, 0);
  CHECK(0.5 * (borders[0] + borders[1]) == Approx(-1.75).margin(0.02));
  CHECK(borders[1] >= -2.5 + 0.5 - 0.02);  // the solver keeps centres within 2 cm
  CHECK(borders[1] < -1.75);
  // Not narrower than asked for.
  lanes = {{-1.75, 3.5, true}};
  corsa::ngii::detail::narrow_inside_of_turn(lanes, -0.4, 0.5, 1.5);
  CHECK(lanes[0].width == Approx(1.5));
  // A left turn narrows the leftmost lane only, a gentle turn nothing.
  lanes = {{0.5, 3.5, true}, {-3.0, 3.5, true}};
  corsa::ngii::detail::narrow_inside_of_turn(lanes, 0.5, 0.5, 0.2);
  CHECK(lanes[0].width == Approx(2.0));
  CHECK(lanes[1].width == 3.5);
  lanes = {{-1.75, 3.5, true}};
  corsa::ngii::detail::narrow_inside_of_turn(lanes, -0.1, 0.5, 0.2);
  CHECK(lanes[0].width == 3.5);
}

TEST_CASE("a junction path turning right tightly after its node does not fold", "[ngii][folds]") {
  // A one-lane path surveyed every 0.25 m that leaves its node turning right at a radius of
  // 2 m (lane centre) by a quarter turn, then runs 8 m straight. Along its left edge, the
  // reference line keeps the data's course over its first metres (its end point and heading),
  // and the lane's 3.25 m width put its right edge beyond the centre of curvature there (it
  // folded with or without narrowing). Along its right edge, the inside of the turn, no
  // border lies on the inside.
  const double x0 = 300000.0, y0 = 4100000.0, r = 2.0;
  std::vector<Point3> points;
  const int steps = static_cast<int>(std::ceil(0.5 * M_PI * r / 0.25));
  for (int k = 0; k <= steps; ++k) {
    const double a = 0.5 * M_PI * k / steps;
    points.push_back({x0 + r * std::sin(a), y0 - r * (1.0 - std::cos(a)), 50.0});
  }
  for (int i = 1; i <= 32; ++i) {
    points.push_back({x0 + r, y0 - r - 0.25 * i, 50.0});
  }
  corsa::Diagnostics diagnostics;
  const auto conversion = corsa::ngii::convert(one_lane(points), {}, diagnostics);
  const auto map = corsa::xodr::Map::build(conversion.map, diagnostics);
  REQUIRE(conversion.map.roads.size() == 1);
  // The lane lies left of the reference line (positive laneOffset at the start).
  const auto& road = conversion.map.roads.front();
  REQUIRE(!road.lane_offsets.empty());
  CHECK(road.lane_offsets.front().a > 1.0);
  CHECK(corsa::test::folded_roads(map) == 0);
  CHECK(conversion.summary.max_lane_error <= 0.06);
}

TEST_CASE("only one-lane roads turning right without sharp corners follow their right edge",
          "[ngii][folds]") {
  using corsa::ngii::detail::along_right_edge;
  using corsa::ngii::detail::Polyline;
  const auto turn = [](double radius, double sign) {
    std::vector<Point3> points;
    for (int k = 0; k <= 40; ++k) {
      const double a = 0.5 * M_PI * k / 40;
      points.push_back({radius * std::sin(a), sign * radius * (1.0 - std::cos(a)), 0.0});
    }
    return Polyline(std::span<const Point3>(points));
  };
  CHECK(along_right_edge(turn(4.0, -1.0)));
  CHECK_FALSE(along_right_edge(turn(4.0, 1.0)));   // a left turn
  CHECK_FALSE(along_right_edge(turn(1.0, -1.0)));  // the right edge could not follow
  const std::vector<Point3> straight{{0.0, 0.0, 0.0}, {20.0, 0.0, 0.0}};
  CHECK_FALSE(along_right_edge(Polyline(std::span<const Point3>(straight))));
}

TEST_CASE("a lane turning right tightly within a metre or two of its end does not fold",
          "[ngii][folds]") {
  // A one-lane path surveyed every 0.25 m that runs 12 m straight and turns right by 0.6 rad
  // at a radius of 2.5 m in its last 1.5 m (K-City's A219BS010733 and A219BS010805 end so).
  // The last record must meet the end's point and heading, and turns within 2 m of a road end
  // were never eased: that record turned right at -0.5 1/m, and the right edge of the 3.25 m
  // lane lay beyond its centre of curvature.
  const double x0 = 300000.0, y0 = 4100000.0;
  const double r = 2.5, turn = 0.6;
  std::vector<Point3> points;
  for (int i = 0; i <= 48; ++i) {
    points.push_back({x0 + 0.25 * i, y0, 50.0});
  }
  const int steps = static_cast<int>(std::ceil(turn * r / 0.25));
  for (int k = 1; k <= steps; ++k) {
    const double a = turn * k / steps;
    points.push_back({x0 + 12.0 + r * std::sin(a), y0 - r * (1.0 - std::cos(a)), 50.0});
  }
  corsa::Diagnostics diagnostics;
  const auto conversion = corsa::ngii::convert(one_lane(points), {}, diagnostics);
  const auto map = corsa::xodr::Map::build(conversion.map, diagnostics);
  REQUIRE(conversion.map.roads.size() == 1);
  const auto& road = conversion.map.roads.front();
  INFO("tightest right turn " << tightest_right_turn(road));
  CHECK(corsa::test::folded_roads(map) == 0);
  CHECK(conversion.summary.max_lane_error <= 0.06);
}

namespace {

/// A straight two-vertex reference along +x, `length` metres, its end lines (left to right)
/// turned by `skew` from square where asked.
corsa::ngii::detail::ReferencePolyline straight_reference(double length) {
  corsa::ngii::detail::ReferencePolyline reference;
  reference.points = {{0.0, 0.0}, {length, 0.0}};
  return reference;
}
corsa::ngii::detail::EndLine skewed_line(corsa::Vec2 point, double skew) {
  return corsa::ngii::detail::EndLine{point, {std::sin(skew), -std::cos(skew)}};
}

}  // namespace

TEST_CASE("a two-vertex road longer than twice the reach bends over the reach alone",
          "[ngii][folds]") {
  // The last segment of 100 m is longer than the reach (8 m for 20 degrees at 3.5 m): the bend
  // starts on it 8 m before the end, and the road runs straight up to there.
  const double skew = 20.0 * M_PI / 180.0;
  const auto reference = corsa::ngii::detail::align_ends(straight_reference(100.0), std::nullopt,
                                                         skewed_line({100.0, 0.0}, skew),
                                                         {0.0, 0.0}, {100.0, 0.0}, 3.5);
  const auto& p = reference.points;
  REQUIRE(p.size() > 3);
  double bend_start = 0.0;  // the last vertex still on the line of travel
  for (const auto& q : p) {
    if (std::abs(q.y) < 1e-12) {
      bend_start = std::max(bend_start, q.x);
    }
  }
  CHECK(bend_start == Approx(92.0).margin(1e-9));
  CHECK(std::abs(p[2].y) > 1e-6);  // the bend itself leaves the line of travel
  CHECK(std::abs(reference.end_heading) == Approx(skew).margin(1e-9));
}

TEST_CASE("both bends of a short two-vertex road stay within their rooms", "[ngii][folds]") {
  // Skewed at both ends by 20 degrees, 3.5 m wide: each end bends over its reach of 8 m within
  // its room (0.45 of the length), and the middle stays on the line of travel.
  const double skew = 20.0 * M_PI / 180.0;
  for (const double length : {20.0, 25.0, 30.0}) {
    INFO("length " << length);
    const auto reference = corsa::ngii::detail::align_ends(
        straight_reference(length), skewed_line({0.0, 0.0}, skew),
        skewed_line({length, 0.0}, -skew), {0.0, 0.0}, {length, 0.0}, 3.5);
    const double room = 0.45 * length;
    int bent = 0;
    for (const auto& q : reference.points) {
      if (std::abs(q.y) > 1e-12) {
        ++bent;
        INFO("bent vertex at x = " << q.x);
        CHECK((q.x <= room || q.x >= length - room));
      }
    }
    CHECK(bent > 4);  // both ends did bend
    CHECK(std::abs(reference.start_heading) == Approx(skew).margin(1e-9));
    CHECK(std::abs(reference.end_heading) == Approx(skew).margin(1e-9));
  }
}
