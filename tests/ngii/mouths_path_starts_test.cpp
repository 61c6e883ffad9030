// Junction mouths where a junction path leaves an approach lane: the path starts on the lane's
// end line (skewed, at a corner) and as wide as the lane, without a wedge or sliver of unpaved
// ground between them (mouth_gaps.h; the shared layers in mouth_layers.h).

#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <utility>

#include "corsa/core/diagnostic.h"
#include "corsa/core/vec.h"
#include "corsa/ngii/convert.h"
#include "lane_joints.h"
#include "mouth_layers.h"
#include "path_lane_ends.h"

namespace {

using corsa::ngii::testing::mouth_gaps_of;
using corsa::ngii::testing::MouthLayers;

/// Two eastbound lanes (A left, B 3.5 m to its right) ending at x = 30 (A) and `b_end` (B), a
/// junction path from A's end straight on to a two-lane exit road from x = 50.
MouthLayers mouth(double b_end) {
  MouthLayers b;
  b.node("A0", 0.0, 0.0);
  b.node("A1", 30.0, 0.0);
  b.node("B0", 0.0, -3.5);
  b.node("B1", b_end, -3.5);
  b.node("E0", 50.0, 0.0);
  b.node("E1", 80.0, 0.0);
  b.node("F0", 50.0, -3.5);
  b.node("F1", 80.0, -3.5);
  b.link("A2TEST00000A", "6", 1, "A0", "A1", "A2TEST00000B", "");
  b.link("A2TEST00000B", "6", 2, "B0", "B1", "", "A2TEST00000A");
  b.link("A2TEST00000P", "1", 1, "A1", "E0");
  b.link("A2TEST00000E", "6", 1, "E0", "E1", "A2TEST00000F", "");
  b.link("A2TEST00000F", "6", 2, "F0", "F1", "", "A2TEST00000E");
  return b;
}

}  // namespace

TEST_CASE("a junction path leaving a skewed stop line starts on it", "[ngii][mouths]") {
  // B ends 1.5 m beyond A: the approach road ends on a line skewed by 23 degrees. A path that
  // started square across its own heading left a wedge beside A's end (1.8 m along its edge).
  const auto gaps = mouth_gaps_of(mouth(31.5).layers);
  INFO(gaps.worst);
  CHECK(gaps.ends >= 4);
  CHECK(gaps.over == 0);
  CHECK(gaps.max < 0.1);
}

TEST_CASE("a junction path narrower than the lane it leaves widens to it at the joint",
          "[ngii][mouths]") {
  // The path's marks are 3.0 m apart, the approach and exit lanes 3.5 m: at its ends it takes
  // their width (easing back over a few metres), so no sliver of 0.25 m opens beside it.
  MouthLayers b = mouth(30.0);
  b.mark("B2L", 30.0, 50.0, 1.5, "A2TEST00000P", "");
  b.mark("B2R", 30.0, 50.0, -1.5, "", "A2TEST00000P");
  const auto gaps = mouth_gaps_of(b.layers);
  INFO(gaps.worst);
  CHECK(gaps.ends >= 4);
  CHECK(gaps.over == 0);
  CHECK(gaps.max < 0.1);
}

TEST_CASE(
    "a junction path whose marks are far apart in its middle starts and ends as wide as "
    "its lanes",
    "[ngii][mouths]") {
  // The path's marks lie 3.5 m either side of it between x = 38 and 42 only (the intersection's
  // edges): the marks give its width there alone, 7 m, which was held flat out to its ends, so
  // it stuck out 1.75 m beyond both sides of the 3.5 m lanes it joins. It now takes their width
  // at its ends (as built) and widens to its own between the ends and x = 38 / 42.
  MouthLayers b = mouth(30.0);
  b.mark("B2L", 38.0, 42.0, 3.5, "A2TEST00000P", "");
  b.mark("B2R", 38.0, 42.0, -3.5, "", "A2TEST00000P");
  const auto gaps = mouth_gaps_of(b.layers);
  INFO(gaps.worst);
  CHECK(gaps.ends >= 4);
  CHECK(gaps.over == 0);
  CHECK(gaps.max < 0.1);
}

TEST_CASE("a junction path leaving a lane at a corner starts on that lane's end line",
          "[ngii][mouths]") {
  // One-lane roads east, a junction path between them heading 15 degrees north of east: the
  // links meet at a corner of 15 degrees at both of its ends. A path ending square to its own
  // course left a wedge of unpaved ground on the outside of each corner, about half the lane
  // wide (1.5 m); on the end lines of the roads it joins, none.
  MouthLayers b;
  const double px = 30.0 + 15.0 * std::cos(15.0 * M_PI / 180.0);
  const double py = 15.0 * std::sin(15.0 * M_PI / 180.0);
  b.node("A0", 0.0, 0.0);
  b.node("A1", 30.0, 0.0);
  b.node("E0", px, py);
  b.node("E1", px + 30.0, py);
  b.link("A2TEST00000A", "6", 1, "A0", "A1");
  b.link("A2TEST00000P", "1", 1, "A1", "E0");
  b.link("A2TEST00000E", "6", 1, "E0", "E1");
  b.mark("B2AL", 0.0, 30.0, 1.75, "A2TEST00000A", "");
  b.mark("B2AR", 0.0, 30.0, -1.75, "", "A2TEST00000A");
  b.mark("B2EL", px, px + 30.0, py + 1.75, "A2TEST00000E", "");
  b.mark("B2ER", px, px + 30.0, py - 1.75, "", "A2TEST00000E");
  const auto gaps = mouth_gaps_of(b.layers);
  INFO(gaps.worst);
  CHECK(gaps.ends >= 4);
  CHECK(gaps.over == 0);
  CHECK(gaps.max < 0.1);
}

TEST_CASE("a junction path leaving a stop line at 52 degrees to its square starts on it",
          "[ngii][mouths]") {
  // A two-lane road east whose right lane ends 1.27 m beyond its left one (an end line 20
  // degrees off square), and a junction path from the left lane's end heading 32 degrees south
  // of east onto a road going on that way: the path meets the end line 52 degrees off square,
  // past the 50 degrees a road end was bent to (K-City's path 460 leaves road 322 at 51), so
  // it started square across its own heading, a wedge beside the lane's end.
  MouthLayers b;
  const double h = -32.0 * M_PI / 180.0;
  const double ex = 30.0 + 20.0 * std::cos(h), ey = 20.0 * std::sin(h);
  b.node("A0", 0.0, 0.0);
  b.node("A1", 30.0, 0.0);
  b.node("B0", 0.0, -3.5);
  b.node("B1", 30.0 + 3.5 * std::tan(20.0 * M_PI / 180.0), -3.5);
  b.node("E0", ex, ey);
  b.node("E1", ex + 30.0 * std::cos(h), ey + 30.0 * std::sin(h));
  b.link("A2TEST00000A", "6", 1, "A0", "A1", "A2TEST00000B", "");
  b.link("A2TEST00000B", "6", 2, "B0", "B1", "", "A2TEST00000A");
  b.link("A2TEST00000P", "1", 1, "A1", "E0");
  b.link("A2TEST00000E", "6", 1, "E0", "E1");
  b.mark_through("B2EL",
                 {{ex - 1.75 * std::sin(h), ey + 1.75 * std::cos(h)},
                  {ex + 30.0 * std::cos(h) - 1.75 * std::sin(h),
                   ey + 30.0 * std::sin(h) + 1.75 * std::cos(h)}},
                 "A2TEST00000E", "");
  b.mark_through("B2ER",
                 {{ex + 1.75 * std::sin(h), ey - 1.75 * std::cos(h)},
                  {ex + 30.0 * std::cos(h) + 1.75 * std::sin(h),
                   ey + 30.0 * std::sin(h) - 1.75 * std::cos(h)}},
                 "", "A2TEST00000E");
  const auto gaps = mouth_gaps_of(b.layers);
  INFO(gaps.worst);
  CHECK(gaps.ends >= 3);
  CHECK(gaps.over == 0);
  CHECK(gaps.max < 0.1);
}

TEST_CASE(
    "a junction path leaving a wide lane's skewed end 50 degrees off its link meets that lane "
    "edge to edge",
    "[ngii][mouths]") {
  // K-City's roads 321/322 and path 460 (links A219BS010453/454/455 and 579, the path 577
  // merging at 579's end and the road before it, the marks beside them), in map metres: the
  // right lane R of a two-lane road heading west ends about 6.6 m wide along a line skewed by
  // 29 degrees, and the path P from its end turns right, its first segment 50 degrees off the
  // road's end heading and its next ones 10-20 degrees further. P took R's width across its
  // first segment (x cos 50 degrees), and the road builder widened it back across its smoothed
  // lane's slant at its start (/ cos 40 degrees), so it started 0.67 / 0.59 m inside R's end
  // (K-City: 5.41 m wide on a 6.58 m end, 0.62 / 0.55 m). With the lane's direction taken from
  // P's own stretch of its smoothed line it still starts 0.45 / 0.37 m inside (K-City 0.20 /
  // 0.12 m). It now meets R's borders there.
  // (Here P's start ends up 2 degrees off R's end line, K-City's 0.5, and mouth_gaps finds a
  // sliver behind it; the borders along the joint are what this case holds.)
  MouthLayers b;
  b.node("C0", 33.08, 890.05);
  b.node("C1", 5.12, 889.34);
  b.node("R1", -10.08, 891.24);
  b.node("L1", -8.81, 886.28);
  b.node("P1", -17.02, 899.97);
  b.node("E1", -19.44, 920.95);
  b.node("S0", -4.63, 866.56);
  b.node("S1", -9.58, 876.94);
  b.link("A2TEST00000C", "6", 1, "C0", "C1");
  b.link_through("A2TEST00000L", 1, "C1", "L1",
                 {{5.12, 889.34},
                  {3.5, 888.99},
                  {1.79, 888.61},
                  {-0.88, 888.02},
                  {-3.96, 887.34},
                  {-5.9, 886.92},
                  {-8.81, 886.28}},
                 "A2TEST00000R", "");
  b.link_through("A2TEST00000R", 2, "C1", "R1",
                 {{5.12, 889.34},
                  {1.78, 889.45},
                  {-1.78, 889.54},
                  {-4.83, 889.97},
                  {-7.28, 890.49},
                  {-10.08, 891.24}},
                 "", "A2TEST00000L");
  b.path_through("A2TEST00000P", "R1", "P1",
                 {{-10.08, 891.24},
                  {-12.15, 892.74},
                  {-13.97, 895.11},
                  {-15.16, 896.65},
                  {-16.63, 899.26},
                  {-17.02, 899.97}});
  b.link_through("A2TEST00000S", 1, "S0", "S1",
                 {{-4.63, 866.56},
                  {-5.59, 868.52},
                  {-6.39, 870.15},
                  {-7.27, 871.97},
                  {-8.28, 874.02},
                  {-9.58, 876.94}});
  b.path_through("A2TEST00000Q", "S1", "P1",
                 {{-9.58, 876.94},
                  {-10.59, 879.76},
                  {-11.61, 882.57},
                  {-12.63, 885.39},
                  {-13.65, 888.21},
                  {-14.58, 890.77},
                  {-15.35, 893.66},
                  {-16.12, 896.55},
                  {-16.88, 899.45},
                  {-17.02, 899.97}});
  b.link_through("A2TEST00000E", 1, "P1", "E1",
                 {{-17.02, 899.97},
                  {-17.58, 902.87},
                  {-18.09, 906.03},
                  {-18.55, 909.37},
                  {-18.98, 913.1},
                  {-19.26, 917.02},
                  {-19.44, 920.95}});
  b.mark_through("B2CS",
                 {{33.45, 888.18},
                  {13.81, 887.98},
                  {5.95, 887.33},
                  {-1.8, 886.17},
                  {-5.86, 885.31},
                  {-8.77, 884.6}},
                 "A2TEST00000C", "");
  b.mark_through("B2CN",
                 {{33.43, 894.36},
                  {29.63, 892.38},
                  {25.9, 891.63},
                  {12.86, 891.47},
                  {2.22, 891.5},
                  {-1.65, 891.75},
                  {-5.57, 892.36},
                  {-6.49, 892.57}},
                 "", "A2TEST00000C");
  b.mark_through("B2RN", {{-6.49, 892.57}, {-7.32, 892.75}, {-9.02, 893.4}, {-10.83, 894.77}}, "",
                 "A2TEST00000R");
  b.mark_through("B2RS", {{-7.82, 888.08}, {-9.92, 888.8}, {-12.52, 890.13}}, "A2TEST00000R", "");
  b.mark_through("B2RL", {{-7.82, 888.08}, {-9.17, 887.75}}, "A2TEST00000R", "A2TEST00000L");
  b.mark_through("B2SQ", {{-8.43, 884.69}, {-8.81, 886.28}, {-9.17, 887.75}}, "", "A2TEST00000Q");
  b.mark_through("B2Q", {{-11.52, 887.18}, {-12.02, 888.65}, {-12.52, 890.13}}, "", "A2TEST00000Q");
  for (const double side : {1.0, -1.0}) {
    b.mark_through(side > 0.0 ? "B2EL" : "B2ER",
                   {{-17.02 - side * 1.75, 899.97},
                    {-17.58 - side * 1.75, 902.87},
                    {-18.55 - side * 1.75, 909.37},
                    {-19.44 - side * 1.75, 920.95}},
                   side > 0.0 ? "A2TEST00000E" : "", side > 0.0 ? "" : "A2TEST00000E");
    b.mark_through(
        side > 0.0 ? "B2SL" : "B2SR",
        {{-4.63 - side * 1.6, 866.56 - side * 0.7}, {-9.58 - side * 1.6, 876.94 - side * 0.7}},
        side > 0.0 ? "A2TEST00000S" : "", side > 0.0 ? "" : "A2TEST00000S");
  }
  corsa::Diagnostics diagnostics;
  const auto conversion = corsa::ngii::convert(b.layers, {}, diagnostics);
  CHECK(diagnostics.count(corsa::Severity::kWarning) == 0);
  // The lane's borders where it ends and the path's where it starts, as map points (left,
  // right), and where each lies along the lane's end edge and across it.
  const auto borders_of = [&](const std::string& link, bool at_end) {
    for (const auto& road : conversion.map.roads) {
      // The lane section built_border_points reads at that end.
      const auto& lanes = (at_end ? road.lane_sections.back() : road.lane_sections.front()).lanes;
      int index = 0;
      for (const auto& lane : lanes) {
        if (lane.id >= 0) {
          continue;
        }
        if (!lane.user_data.empty() && lane.user_data.front().value == link) {
          const auto points = corsa::ngii::detail::built_border_points(road, at_end);
          return std::pair{points[static_cast<size_t>(index)],
                           points[static_cast<size_t>(index) + 1]};
        }
        ++index;
      }
    }
    FAIL("no lane holds " << link);
    return std::pair<corsa::Vec2, corsa::Vec2>{};
  };
  const auto [lane_left, lane_right] = borders_of("A2TEST00000R", true);
  const auto [path_left, path_right] = borders_of("A2TEST00000P", false);
  const corsa::Vec2 edge = lane_right - lane_left;
  const double width = corsa::norm(edge);
  const corsa::Vec2 along = edge * (1.0 / width);
  INFO("lane end " << width << " m wide; path from " << dot(path_left - lane_left, along) << " to "
                   << dot(path_right - lane_left, along) << " along it, "
                   << cross(along, path_left - lane_left) << " / "
                   << cross(along, path_right - lane_right) << " m across it");
  CHECK(width > 6.0);
  CHECK(std::abs(dot(path_left - lane_left, along)) < 0.05);
  CHECK(std::abs(dot(path_right - lane_right, along)) < 0.05);
  // Across the edge the path's end centre lies on it; its borders lie about 0.12 m either side,
  // as its end line is turned 2 degrees off the lane's (3.3 m x sin 2 degrees: the fit of the
  // joined line, see above), not by the borders' move.
  CHECK(std::abs(cross(along, (path_left + path_right) * 0.5 - (lane_left + lane_right) * 0.5)) <
        0.05);
  CHECK(std::abs(cross(along, path_left - lane_left)) < 0.15);
  CHECK(std::abs(cross(along, path_right - lane_right)) < 0.15);
}

TEST_CASE(
    "a junction path far narrower than a flared lane end moves each border at most a metre "
    "towards the lane's",
    "[ngii][mouths]") {
  using corsa::Vec2;
  using corsa::ngii::detail::path_end_shortfall;
  using corsa::ngii::detail::path_end_targets;
  // A lane ending 9 m wide across x = 0 (flared where lanes split off), a path 3 m wide
  // starting 5 cm beyond it: each border lies 3 m inside the lane's.
  const Vec2 lane_left{0.0, 4.5}, lane_right{0.0, -4.5};
  const Vec2 path_left{0.05, 1.5}, path_right{0.05, -1.5};
  const auto before = path_end_shortfall(lane_left, lane_right, path_left, path_right);
  REQUIRE(before);
  CHECK(before->left == Approx(3.0));
  CHECK(before->right == Approx(3.0));
  SECTION("a long path keeps about its own width: a metre more a side") {
    const auto to = path_end_targets(lane_left, lane_right, path_left, path_right, 20.0);
    CHECK(norm(to.left - path_left) == Approx(1.0));
    CHECK(norm(to.right - path_right) == Approx(1.0));
    const auto after = path_end_shortfall(lane_left, lane_right, to.left, to.right);
    REQUIRE(after);
    CHECK(after->left == Approx(2.0).margin(0.01));
    CHECK(after->right == Approx(2.0).margin(0.01));
  }
  SECTION("a path a metre long moves no further than its ease slants at 2 m per metre") {
    const double length = 1.0;
    const auto to = path_end_targets(lane_left, lane_right, path_left, path_right, length);
    const double moved = norm(to.left - path_left);
    CHECK(moved < 1.0);
    // A smoothstep's steepest slant: 1.5 times the move over the ease.
    CHECK(1.5 * moved / corsa::ngii::detail::end_border_ramp(moved, length) <= 2.0 + 1e-9);
  }
  SECTION("a border a few decimetres short moves onto the lane's") {
    const Vec2 near_left{0.05, 4.3}, near_right{0.05, -4.2};
    const auto to = path_end_targets(lane_left, lane_right, near_left, near_right, 20.0);
    CHECK(norm(to.left - lane_left) < 1e-12);
    CHECK(norm(to.right - lane_right) < 1e-12);
  }
}
