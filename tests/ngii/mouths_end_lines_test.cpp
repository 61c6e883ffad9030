// Road ends on a shared end line: a road after a split, a merge or a skewed stop line starts on
// the end line of the road before it, and a road end turns onto a skewed line over its whole
// reach (mouth_gaps.h; the shared layers in mouth_layers.h).

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/ngii/convert.h"
#include "corsa/xodr/geometry.h"
#include "mouth_layers.h"
#include "reference_line.h"

namespace {

using corsa::ngii::testing::mouth_gaps_of;
using corsa::ngii::testing::MouthLayers;

}  // namespace

TEST_CASE(
    "a road whose second lane splits off its first starts on the end line of the road "
    "before it",
    "[ngii][mouths]") {
  // The lane continuing the one-lane road turns 3 degrees left at the node: a start square to
  // its own course left a wedge beside the joint (7 cm deep at the lane's edge) that the
  // measure sees 5 cm beyond the end as a run of unpaved ground; on the end line of the road
  // before it, none.
  MouthLayers b;
  const double dy = 40.0 * std::tan(3.0 * M_PI / 180.0);
  b.node("A0", 0.0, 0.0);
  b.node("A1", 30.0, 0.0);
  b.node("B1", 70.0, dy);
  b.node("C1", 70.0, dy - 3.5);
  b.link("A2TEST00000A", "6", 1, "A0", "A1");
  b.link("A2TEST00000B", "6", 1, "A1", "B1", "A2TEST00000C", "");
  b.link_through("A2TEST00000C", 2, "A1", "C1",
                 {{30.0, 0.0}, {35.0, -1.0}, {40.0, 0.5 * dy - 3.5}, {70.0, dy - 3.5}}, "",
                 "A2TEST00000B");
  const auto gaps = mouth_gaps_of(b.layers);
  INFO(gaps.worst);
  CHECK(gaps.ends >= 2);
  CHECK(gaps.over == 0);
  CHECK(gaps.max < 0.1);
}

TEST_CASE("two five-lane roads meeting at 0.3 degrees end on their shared line", "[ngii][mouths]") {
  // The lanes of a five-lane road 17.5 m wide end on a line square to neither road: the road
  // after the joint turns 0.3 degrees left, and the line halves the turn, 0.15 degrees off
  // square to each. An end left square to its road (a skew under 0.2 degrees was not bent)
  // put the outer lanes' corners 4-5 cm off the line on either side, a strip of unpaved ground
  // up to 9 cm deep across the outer lanes; the ends now turn onto the line.
  MouthLayers b;
  const double turn = 0.3 * M_PI / 180.0;
  const double half = 0.5 * turn;
  const std::vector<std::string> lanes{"A", "B", "C", "D", "E"};
  for (size_t k = 0; k < lanes.size(); ++k) {
    const double t = -3.5 * static_cast<double>(k);
    const double x = 30.0 - t * std::sin(half), y = t * std::cos(half);
    b.node(lanes[k] + "0", 0.0, t);
    b.node(lanes[k] + "1", x, y);
    b.node(lanes[k] + "2", x + 30.0 * std::cos(turn), y + 30.0 * std::sin(turn));
  }
  for (size_t k = 0; k < lanes.size(); ++k) {
    const std::string right = k + 1 < lanes.size() ? lanes[k + 1] : "";
    const std::string left = k > 0 ? lanes[k - 1] : "";
    const auto id = [](const std::string& lane, const std::string& piece) {
      return lane.empty() ? std::string() : "A2TEST0000" + lane + piece;
    };
    const int lane_no = static_cast<int>(k) + 1;
    b.link(id(lanes[k], "1"), "6", lane_no, lanes[k] + "0", lanes[k] + "1", id(right, "1"),
           id(left, "1"));
    b.link(id(lanes[k], "2"), "6", lane_no, lanes[k] + "1", lanes[k] + "2", id(right, "2"),
           id(left, "2"));
  }
  const auto gaps = mouth_gaps_of(b.layers);
  INFO(gaps.worst);
  CHECK(gaps.ends >= 10);
  CHECK(gaps.over == 0);
  CHECK(gaps.max < 0.1);
}

TEST_CASE(
    "a one-lane road after a road whose second lane merges into its first starts on that road's "
    "end line",
    "[ngii][mouths]") {
  // The mirror of the split above: a two-lane road's right lane merges into its left one at
  // the node (zero width there), and the one-lane road after it turns 5 degrees left. That road
  // joined only a road of one lane, every lane ending there beside its neighbours, so it started
  // square to its own course: a wedge beside the joint. The merging lane ends on its neighbour's
  // end, so the road before has one line there, which the road after now takes.
  MouthLayers b;
  const double dy = 40.0 * std::tan(5.0 * M_PI / 180.0);
  b.node("A0", 0.0, 0.0);
  b.node("B0", 0.0, -3.5);
  b.node("A1", 30.0, 0.0);
  b.node("C1", 70.0, dy);
  b.link("A2TEST00000A", "6", 1, "A0", "A1", "A2TEST00000B", "");
  b.link_through("A2TEST00000B", 2, "B0", "A1",
                 {{0.0, -3.5}, {20.0, -3.5}, {25.0, -2.5}, {30.0, 0.0}}, "", "A2TEST00000A");
  b.link("A2TEST00000C", "6", 1, "A1", "C1");
  const auto gaps = mouth_gaps_of(b.layers);
  INFO(gaps.worst);
  CHECK(gaps.ends >= 2);
  CHECK(gaps.over == 0);
  CHECK(gaps.max < 0.1);
}

TEST_CASE(
    "a road of two and a half metres surveyed by its two ends turns onto the skewed line it "
    "starts on",
    "[ngii][mouths]") {
  // A two-lane road ends on a stop line skewed by 20 degrees (its right lane ends 1.27 m beyond
  // its left one); the left lane goes on as a one-lane road 2.5 m long whose link has only its
  // two end vertices. Its start did not turn at all (the bend must begin on the link's one
  // segment) and, where it did, a short S back to the line of travel fitted 16 of the 20
  // degrees: a wedge beside the joint, 1.3-1.6 m along the lane's end edge on Sangam's roads.
  MouthLayers b;
  const double beyond = 3.5 * std::tan(20.0 * M_PI / 180.0);
  b.node("A0", 0.0, 0.0);
  b.node("A1", 30.0, 0.0);
  b.node("B0", 0.0, -3.5);
  b.node("B1", 30.0 + beyond, -3.5);
  b.node("C1", 32.5, 0.0);
  b.link("A2TEST00000A", "6", 1, "A0", "A1", "A2TEST00000B", "");
  b.link("A2TEST00000B", "6", 2, "B0", "B1", "", "A2TEST00000A");
  b.link_through("A2TEST00000C", 1, "A1", "C1", {{30.0, 0.0}, {32.5, 0.0}});
  const auto gaps = mouth_gaps_of(b.layers);
  INFO(gaps.worst);
  CHECK(gaps.ends >= 2);
  CHECK(gaps.over == 0);
  CHECK(gaps.max < 0.1);
}

TEST_CASE(
    "a three-lane road whose third lane ends 0.4 m short of the stop line is cut on that line's "
    "parallel",
    "[ngii][mouths]") {
  // Three lanes end on a stop line skewed by 17 degrees, but the survey ends the third lane's
  // link 0.4 m short of it and continues it by a link 0.4 m long; a three-lane road starts on
  // the stop line. Within the 0.25 m an end line allows, the three lane ends lie on a line
  // tilted by about 4 degrees, so the road ended on that line and the road after it on the stop
  // line: the middle lane, between the two, left a wedge (0.5-0.6 m along its end edge on
  // Sangam's road 557). Against the stop line, which the roads after the joint give, the third
  // lane ends short: the other two are cut on its parallel through that lane's end.
  MouthLayers b;
  const double slope = std::tan(17.0 * M_PI / 180.0);
  const std::vector<std::string> lanes{"A", "B", "C"};
  for (size_t k = 0; k < lanes.size(); ++k) {
    const double y = -3.5 * static_cast<double>(k);
    const double x = 30.0 - y * slope;
    b.node(lanes[k] + "0", 0.0, y);
    b.node(lanes[k] + "1", k == 2 ? x - 0.4 : x, y);
    b.node(lanes[k] + "2", x + 30.0, y);
  }
  b.node("C9", 30.0 + 7.0 * slope, -7.0);
  const auto id = [](const std::string& lane, const std::string& piece) {
    return lane.empty() ? std::string() : "A2TEST0000" + lane + piece;
  };
  for (size_t k = 0; k < lanes.size(); ++k) {
    const std::string right = k + 1 < lanes.size() ? lanes[k + 1] : "";
    const std::string left = k > 0 ? lanes[k - 1] : "";
    const int lane_no = static_cast<int>(k) + 1;
    const std::string start = k == 2 ? "C9" : lanes[k] + "1";
    b.link(id(lanes[k], "1"), "6", lane_no, lanes[k] + "0", lanes[k] + "1", id(right, "1"),
           id(left, "1"));
    b.link(id(lanes[k], "2"), "6", lane_no, start, lanes[k] + "2", id(right, "2"), id(left, "2"));
  }
  b.link("A2TEST0000C9", "6", 1, "C1", "C9");
  const auto gaps = mouth_gaps_of(b.layers);
  INFO(gaps.worst);
  CHECK(gaps.ends >= 6);
  CHECK(gaps.over == 0);
  CHECK(gaps.max < 0.1);
}

TEST_CASE(
    "a one-lane road where two one-lane roads merge starts on the end line of the one in line",
    "[ngii][mouths]") {
  // Road A comes in 5 degrees off road C's course and road B 32 degrees off, both ending where
  // C starts. C joined no single road there, so it started square to its own course: a wedge
  // beside A's end (0.82 m along C's start edge at K-City's road 317; here two ends over 10 cm,
  // 1.14 m). It now starts on the end line of A, the road in line with it.
  MouthLayers b;
  const double a = 5.0 * M_PI / 180.0, c = 32.0 * M_PI / 180.0;
  b.node("A0", 30.0 - 30.0 * std::cos(a), -30.0 * std::sin(a));
  b.node("B0", 30.0 - 30.0 * std::cos(c), -30.0 * std::sin(c));
  b.node("C0", 30.0, 0.0);
  b.node("C1", 60.0, 0.0);
  b.link("A2TEST00000A", "6", 1, "A0", "C0");
  b.link("A2TEST00000B", "6", 1, "B0", "C0");
  b.link("A2TEST00000C", "6", 1, "C0", "C1");
  b.mark("B2CL", 30.0, 60.0, 1.75, "A2TEST00000C", "");
  b.mark("B2CR", 30.0, 60.0, -1.75, "", "A2TEST00000C");
  const auto gaps = mouth_gaps_of(b.layers);
  INFO(gaps.worst);
  CHECK(gaps.ends >= 3);
  CHECK(gaps.over == 0);
  CHECK(gaps.max < 0.1);
}

TEST_CASE("a road end bent onto a skewed line over sparse vertices turns over its whole reach",
          "[ngii][mouths]") {
  // A one-lane road 4 m wide (L) ends beside another (R) on a line 35 degrees off square, where
  // a two-lane road starts. L's link has a vertex 2 m before its end and none for 28 m before
  // that: the bend onto the line started at that vertex, turning 35 degrees within 2 m (the
  // lane narrowed on the inside of the turn: 4.11 m along the end line for the 4.88 m of its
  // skewed width). It now starts 8 m before the end, on the long segment.
  MouthLayers b;
  const double skew = 35.0 * M_PI / 180.0;
  const double rx = -4.0 * std::tan(skew);
  b.node("L0", -30.0, 0.0);
  b.node("L1", 0.0, 0.0);
  b.node("R0", -12.0, -4.0);
  b.node("R1", rx, -4.0);
  b.node("C1", 30.0, 0.0);
  b.node("D1", 30.0, -4.0);
  b.link_through("A2TEST00000L", 1, "L0", "L1", {{-30.0, 0.0}, {-2.0, 0.0}, {0.0, 0.0}});
  b.link("A2TEST00000R", "6", 1, "R0", "R1");
  b.link("A2TEST00000C", "6", 1, "L1", "C1", "A2TEST00000D", "");
  b.link("A2TEST00000D", "6", 2, "R1", "D1", "", "A2TEST00000C");
  b.mark("B2L", -30.0, 0.0, 2.0, "A2TEST00000L", "");
  b.mark("B2LR", -30.0, 0.0, -2.0, "", "A2TEST00000L");
  const auto gaps = mouth_gaps_of(b.layers);
  INFO(gaps.worst);
  CHECK(gaps.over == 0);
  corsa::Diagnostics diagnostics;
  const auto conversion = corsa::ngii::convert(b.layers, {}, diagnostics);
  bool found = false;
  for (const auto& road : conversion.map.roads) {
    const auto& lanes = road.lane_sections.front().lanes;
    const auto lane = std::find_if(lanes.begin(), lanes.end(), [](const auto& l) {
      return !l.user_data.empty() && l.user_data.front().value == "A2TEST00000L";
    });
    if (lane == lanes.end()) {
      continue;
    }
    found = true;
    // The reference line turns at most 1 / (2 x the lane's width) anywhere (the old bend: 0.18
    // 1/m), and the lane spans its whole width along the skewed end line.
    double sharpest = 0.0;
    for (const auto& g : road.plan_view) {
      for (double u = 0.0; u + 0.05 <= g.length; u += 0.05) {
        const auto p0 = corsa::xodr::evaluate_geometry(g, u);
        const auto p1 = corsa::xodr::evaluate_geometry(g, u + 0.05);
        sharpest = std::max(sharpest, std::abs(std::remainder(p1.hdg - p0.hdg, 2 * M_PI)) / 0.05);
      }
    }
    CHECK(sharpest < 0.125);
    CHECK(corsa::ngii::detail::piecewise_value(lane->widths, road.length) ==
          Approx(4.0 / std::cos(skew)).margin(0.1));
  }
  CHECK(found);
}

TEST_CASE(
    "a one-lane road of two metres whose turn onto a skewed line is cut short runs on past it",
    "[ngii][mouths]") {
  // A lane 1.8 m wide, surveyed by its two ends 2.25 m apart, comes in 37 degrees off the
  // course of the two-lane road D and ends on D's start line, where D's right lane F starts
  // 0.7 m wide and widens: Sangam's road 365 before road 366. It can turn only 28 degrees onto
  // the line before its lane would fold, which leaves a triangle up to 0.14 m deep short of the
  // line at one corner; it now runs on 9 cm along its end heading past the line. Without that,
  // the road built here ended 1.37 m of its end edge away from pavement (it kept its own
  // course: the curve to a target on the line itself was not kept); with it, no gap.
  MouthLayers b;
  const double a = 37.0 * M_PI / 180.0;
  const double length = 2.25, half = 0.9, f_width = 0.7;
  const double fy = -1.75 - 0.5 * f_width;
  const double ex = 30.0 - length * std::cos(a), ey = fy + length * std::sin(a);
  b.node("D0", 30.0, 0.0);
  b.node("D1", 60.0, 0.0);
  b.node("F0", 30.0, fy);
  b.node("F1", 60.0, -3.5);
  b.node("E0", ex, ey);
  b.link("A2TEST00000D", "6", 1, "D0", "D1", "A2TEST00000F", "");
  b.link_through("A2TEST00000F", 2, "F0", "F1", {{30.0, fy}, {50.0, -3.5}, {60.0, -3.5}}, "",
                 "A2TEST00000D");
  b.link_through("A2TEST00000E", 1, "E0", "F0", {{ex, ey}, {30.0, fy}});
  b.mark("B2DL", 30.0, 60.0, 1.75, "A2TEST00000D", "");
  b.mark("B2DF", 30.0, 60.0, -1.75, "A2TEST00000F", "A2TEST00000D");
  b.layers.marks.push_back(corsa::ngii::SurfaceMark{
      .id = "B2FR",
      .type = "211",
      .kind = "503",
      .right_link = "",
      .left_link = "A2TEST00000F",
      .points = {b.at(30.0, -1.75 - f_width), b.at(50.0, -5.25), b.at(60.0, -5.25)},
      .record = static_cast<int64_t>(b.layers.marks.size())});
  // The marks either side of the short lane give its width.
  const double nx = std::sin(a) * half, ny = std::cos(a) * half;  // to its left
  const double ux = std::cos(a), uy = -std::sin(a);               // along it
  for (const double side : {1.0, -1.0}) {
    b.layers.marks.push_back(corsa::ngii::SurfaceMark{
        .id = side > 0.0 ? "B2EL" : "B2ER",
        .type = "211",
        .kind = "503",
        .right_link = side > 0.0 ? "A2TEST00000E" : "",
        .left_link = side > 0.0 ? "" : "A2TEST00000E",
        .points = {b.at(ex - 0.5 * ux + side * nx, ey - 0.5 * uy + side * ny),
                   b.at(30.0 + 0.5 * ux + side * nx, fy + 0.5 * uy + side * ny)},
        .record = static_cast<int64_t>(b.layers.marks.size())});
  }
  const auto gaps = mouth_gaps_of(b.layers);
  INFO(gaps.worst);
  CHECK(gaps.ends >= 2);
  CHECK(gaps.over == 0);
  CHECK(gaps.max < 0.1);
}
