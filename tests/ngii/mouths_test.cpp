// Junction mouths on small synthetic layers: a junction path leaves an approach lane without a
// wedge or sliver of unpaved ground between them (mouth_gaps.h).

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/ngii/convert.h"
#include "corsa/xodr/geometry.h"
#include "corsa/xodr/map.h"
#include "corsa/xodr/parser.h"
#include "corsa/xodr/writer.h"
#include "lane_joints.h"
#include "mouth_fills.h"
#include "mouth_gaps.h"
#include "path_lane_ends.h"
#include "reference_line.h"
#include "synthetic_layers.h"

namespace {

using corsa::ngii::Layers;

constexpr double kX0 = 300000.0, kY0 = 4100000.0;

struct Builder : corsa::ngii::testing::SyntheticLayers {
  Builder() : SyntheticLayers(kX0, kY0, 50.0) {}
};

/// Two eastbound lanes (A left, B 3.5 m to its right) ending at x = 30 (A) and `b_end` (B), a
/// junction path from A's end straight on to a two-lane exit road from x = 50.
Builder mouth(double b_end) {
  Builder b;
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

corsa::test::MouthGapFigures mouth_gaps_of(const Layers& layers) {
  corsa::Diagnostics diagnostics;
  const auto conversion = corsa::ngii::convert(layers, {}, diagnostics);
  CHECK(diagnostics.count(corsa::Severity::kWarning) == 0);
  const auto map = corsa::xodr::Map::build(conversion.map, diagnostics);
  return corsa::test::mouth_gaps(map, [](const corsa::xodr::LaneRef&, bool) { return false; });
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
  Builder b = mouth(30.0);
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
  Builder b = mouth(30.0);
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
  Builder b;
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

/// A one-lane road east from x = 0 to 30 whose marks lie `half_a` either side of it, continued
/// by a road of two lanes from x = 30: its left lane straight on (marks `half_b` either side),
/// its right lane splitting off that one at zero width at x = 30 and lying beside it from
/// x = 40.
Builder lane_count_change(double half_a, double half_b) {
  Builder b;
  b.node("A0", 0.0, 0.0);
  b.node("A1", 30.0, 0.0);
  b.node("B1", 70.0, 0.0);
  b.node("C1", 70.0, -3.5);
  b.link("A2TEST00000A", "6", 1, "A0", "A1");
  b.link("A2TEST00000B", "6", 1, "A1", "B1", "A2TEST00000C", "");
  b.link_through("A2TEST00000C", 2, "A1", "C1",
                 {{30.0, 0.0}, {35.0, -1.0}, {40.0, -3.5}, {55.0, -3.5}, {70.0, -3.5}}, "",
                 "A2TEST00000B");
  b.mark("B2AL", 0.0, 30.0, half_a, "A2TEST00000A", "");
  b.mark("B2AR", 0.0, 30.0, -half_a, "", "A2TEST00000A");
  b.mark("B2BL", 30.0, 70.0, half_b, "A2TEST00000B", "");
  b.mark("B2BR", 30.0, 70.0, -half_b, "A2TEST00000C", "A2TEST00000B");
  b.mark("B2CR", 40.0, 70.0, -3.5 - half_b, "", "A2TEST00000C");
  return b;
}

TEST_CASE("an ordinary lane wider than the lane it continues into meets it edge to edge",
          "[ngii][mouths]") {
  // The one-lane road's marks are 4.0 m apart, the continuing lane's 3.2 m: each road took
  // its own marks' width up to the joint, and the wider lane's end stuck out 0.4 m beyond
  // both sides of the narrower one's start. The narrower lane now widens to the wider one's
  // borders at the joint (its centre stays on its link) and eases back to its own width.
  const Builder b = lane_count_change(2.0, 1.6);
  const auto gaps = mouth_gaps_of(b.layers);
  INFO(gaps.worst);
  CHECK(gaps.ends >= 2);
  CHECK(gaps.over == 0);
  CHECK(gaps.max < 0.1);
  // Its width 5 m on is its own again (3.2 m, measured every metre from the marks).
  corsa::Diagnostics diagnostics;
  const auto conversion = corsa::ngii::convert(b.layers, {}, diagnostics);
  const auto map = corsa::xodr::Map::build(conversion.map, diagnostics);
  bool found = false;
  for (const auto& road : conversion.map.roads) {
    const auto& lanes = road.lane_sections.front().lanes;
    if (std::count_if(lanes.begin(), lanes.end(), [](const auto& l) { return l.id < 0; }) != 2) {
      continue;
    }
    found = true;
    const auto width_at = [&](double s) {
      for (const auto& lane : lanes) {
        if (lane.id == -1) {
          for (size_t i = lane.widths.size(); i-- > 0;) {
            if (lane.widths[i].s <= s) {
              return lane.widths[i].value(s);
            }
          }
        }
      }
      return 0.0;
    };
    CHECK(width_at(0.0) == Approx(4.0).margin(0.05));
    CHECK(width_at(5.0) == Approx(3.2).margin(0.05));
  }
  CHECK(found);
}

TEST_CASE("a lane narrower than the lane it continues into meets it edge to edge",
          "[ngii][mouths]") {
  // The other way round: 3.2 m, then 4.0 m. The one-lane road widens to the wider lane at its
  // end.
  const auto gaps = mouth_gaps_of(lane_count_change(1.6, 2.0).layers);
  INFO(gaps.worst);
  CHECK(gaps.ends >= 2);
  CHECK(gaps.over == 0);
  CHECK(gaps.max < 0.1);
}

TEST_CASE(
    "a lane much wider than the lane it continues into leaves paved shoulders beside the "
    "narrower one",
    "[ngii][mouths]") {
  // 5.0 m, then 3.0 m: 1 m a side is more than a lane's border moves at a joint (a lane at the
  // tip of a painted island), so both lanes keep their widths and centres there, and the wider
  // lane's end stuck out 1 m beyond both sides of the narrower one. The road after the joint
  // now has a shoulder on each side (no road mark, named as a fill), 1 m wide at the joint and
  // narrowing to nothing within a few metres, while its lane stays 3 m wide on its link.
  const Builder b = lane_count_change(2.5, 1.5);
  const auto gaps = mouth_gaps_of(b.layers);
  INFO(gaps.worst);
  CHECK(gaps.ends >= 2);
  CHECK(gaps.over == 0);
  corsa::Diagnostics diagnostics;
  const auto conversion = corsa::ngii::convert(b.layers, {}, diagnostics);
  CHECK(conversion.summary.mouth_fills == 2);
  size_t fills = 0;
  for (const auto& road : conversion.map.roads) {
    for (const auto& lane : road.lane_sections.front().lanes) {
      if (lane.type != corsa::xodr::LaneType::kShoulder) {
        continue;
      }
      ++fills;
      REQUIRE(lane.user_data.size() == 1);
      CHECK(lane.user_data.front().code == "ngii:mouth-fill");
      CHECK(lane.road_marks.empty());
      // About the step at the joint, nothing from 6 m on.
      REQUIRE(!lane.widths.empty());
      CHECK(lane.widths.front().s == 0.0);
      CHECK(lane.widths.front().a == Approx(1.0).margin(0.1));
      const auto width_at = [&](double at) {
        double w = 0.0;
        for (const auto& piece : lane.widths) {
          if (piece.s <= at) {
            w = piece.value(at);
          }
        }
        return w;
      };
      CHECK(width_at(1.0) > 0.5);
      CHECK(width_at(6.0) == Approx(0.0).margin(1e-9));
    }
    for (const auto& lane : road.lane_sections.front().lanes) {
      if (lane.id == -1 && road.lane_sections.front().lanes.size() > 3) {
        CHECK(lane.widths.front().a == Approx(3.0).margin(0.05));
      }
    }
  }
  CHECK(fills == 2);
}

TEST_CASE(
    "a road whose second lane splits off its first starts on the end line of the road "
    "before it",
    "[ngii][mouths]") {
  // The lane continuing the one-lane road turns 3 degrees left at the node: a start square to
  // its own course left a wedge beside the joint (7 cm deep at the lane's edge) that the
  // measure sees 5 cm beyond the end as a run of unpaved ground; on the end line of the road
  // before it, none.
  Builder b;
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

TEST_CASE("two two-lane roads whose lanes continue one to one meet with all their borders",
          "[ngii][mouths]") {
  // Lanes centred 3.5 m apart on both sides of a joint at x = 30: before it 4.1 m and 2.9 m wide,
  // after it 3.5 m each, so that the border between the lanes lies 0.3 m apart across the joint
  // and each road sticks out 0.3 m beyond the other on one side. Meeting lane by lane would
  // move a centre by 0.15 m (the neighbour's border is shared), so the pairs were left alone
  // and both sides kept a 0.3 m sliver of unpaved ground. The road after the joint now takes
  // the road before's borders there, every lane keeping its centre.
  Builder b;
  b.node("A0", 0.0, 0.0);
  b.node("A1", 30.0, 0.0);
  b.node("B0", 0.0, -3.5);
  b.node("B1", 30.0, -3.5);
  b.node("C1", 60.0, 0.0);
  b.node("D1", 60.0, -3.5);
  b.link("A2TEST00000A", "6", 1, "A0", "A1", "A2TEST00000B", "");
  b.link("A2TEST00000B", "6", 2, "B0", "B1", "", "A2TEST00000A");
  b.link("A2TEST00000C", "6", 1, "A1", "C1", "A2TEST00000D", "");
  b.link("A2TEST00000D", "6", 2, "B1", "D1", "", "A2TEST00000C");
  b.mark("B2A", 0.0, 30.0, 2.05, "A2TEST00000A", "");
  b.mark("B2AB", 0.0, 30.0, -2.05, "A2TEST00000B", "A2TEST00000A");
  b.mark("B2B", 0.0, 30.0, -4.95, "", "A2TEST00000B");
  b.mark("B2C", 30.0, 60.0, 1.75, "A2TEST00000C", "");
  b.mark("B2CD", 30.0, 60.0, -1.75, "A2TEST00000D", "A2TEST00000C");
  b.mark("B2D", 30.0, 60.0, -5.25, "", "A2TEST00000D");
  const auto gaps = mouth_gaps_of(b.layers);
  INFO(gaps.worst);
  CHECK(gaps.ends >= 4);
  CHECK(gaps.over == 0);
  CHECK(gaps.max < 0.1);
}

TEST_CASE("a wider lane ending where a narrower one with a neighbour starts narrows to its edges",
          "[ngii][mouths]") {
  // A one-lane road 3.8 m wide ends at x = 30 where the first lane of a two-lane road starts,
  // 3.0 m wide on the same centre line, its second lane beside it on the right. The narrower
  // lane cannot widen to the wider one's edges without moving its centre (its right border is
  // its neighbour's), so the wider lane's left edge stuck out 0.4 m beyond it: unpaved ground
  // just past the joint. The wider lane now narrows to the narrower one's edges at the joint,
  // keeping its own centre.
  Builder b;
  b.node("A0", 0.0, 0.0);
  b.node("A1", 30.0, 0.0);
  b.node("C1", 60.0, 0.0);
  b.node("D0", 30.0, -3.25);
  b.node("D1", 60.0, -3.25);
  b.link("A2TEST00000A", "6", 1, "A0", "A1");
  b.link("A2TEST00000C", "6", 1, "A1", "C1", "A2TEST00000D", "");
  b.link("A2TEST00000D", "6", 2, "D0", "D1", "", "A2TEST00000C");
  b.mark("B2AL", 0.0, 30.0, 1.9, "A2TEST00000A", "");
  b.mark("B2AR", 0.0, 30.0, -1.9, "", "A2TEST00000A");
  b.mark("B2C", 30.0, 60.0, 1.5, "A2TEST00000C", "");
  b.mark("B2CD", 30.0, 60.0, -1.5, "A2TEST00000D", "A2TEST00000C");
  b.mark("B2D", 30.0, 60.0, -5.0, "", "A2TEST00000D");
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
  Builder b;
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

TEST_CASE("a shoulder narrowing along a lane edge that slants steeply at the joint is added",
          "[ngii][mouths]") {
  // Road 1's 3.5 m lane ends where road 2's 3.0 m one starts, both reference lines straight and
  // in line: 0.5 m of road 1's end lies beyond road 2's right edge. Road 2's laneOffset swings
  // its lane left at 2.5 m per metre from its start (a road fitted along its lane's edge
  // through a tight corner slants so), so its right edge, and a shoulder's outer border
  // narrowing beside it from zero slope, slant beyond the 2 m per metre a shoulder may add
  // itself. The shoulder only follows the lane's edge there and is kept.
  const std::string text = R"(<?xml version="1.0" encoding="UTF-8"?>
<OpenDRIVE>
  <header revMajor="1" revMinor="8" name="slanting joint"/>
  <road name="a" length="20" id="1" junction="-1">
    <link><successor elementType="road" elementId="2" contactPoint="start"/></link>
    <planView><geometry s="0" x="0" y="0" hdg="0" length="20"><line/></geometry></planView>
    <lanes>
      <laneSection s="0">
        <center><lane id="0" type="none" level="false"/></center>
        <right><lane id="-1" type="driving" level="false">
          <link><successor id="-1"/></link>
          <width sOffset="0" a="3.5" b="0" c="0" d="0"/>
        </lane></right>
      </laneSection>
    </lanes>
  </road>
  <road name="b" length="20" id="2" junction="-1">
    <link><predecessor elementType="road" elementId="1" contactPoint="end"/></link>
    <planView><geometry s="0" x="20" y="0" hdg="0" length="20"><line/></geometry></planView>
    <lanes>
      <laneOffset s="0" a="0" b="2.5" c="-2.5" d="0"/>
      <laneOffset s="0.5" a="0.625" b="0" c="0" d="0"/>
      <laneSection s="0">
        <center><lane id="0" type="none" level="false"/></center>
        <right><lane id="-1" type="driving" level="false">
          <link><predecessor id="-1"/></link>
          <width sOffset="0" a="3.0" b="0" c="0" d="0"/>
        </lane></right>
      </laneSection>
    </lanes>
  </road>
</OpenDRIVE>
)";
  corsa::Diagnostics diagnostics;
  corsa::xodr::MapData map = corsa::xodr::parse_xodr_text(text, "slanting.xodr", diagnostics);
  REQUIRE(map.roads.size() == 2);
  CHECK(corsa::ngii::detail::fill_lane_mouths(map) == 1);
  const auto& lanes = map.roads[1].lane_sections.front().lanes;
  REQUIRE(lanes.size() == 3);
  CHECK(lanes.back().type == corsa::xodr::LaneType::kShoulder);
  CHECK(lanes.back().id == -2);
  REQUIRE(!lanes.back().widths.empty());
  // As wide as the step (0.5 m) and the 2 cm it reaches under road 1's lane.
  CHECK(lanes.back().widths.front().a == Approx(0.52).margin(0.03));
  const corsa::xodr::Map built = corsa::xodr::Map::build(map, diagnostics);
  const auto gaps =
      corsa::test::mouth_gaps(built, [](const corsa::xodr::LaneRef&, bool) { return false; });
  INFO(gaps.worst);
  CHECK(gaps.over == 0);
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
  Builder b;
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
  Builder b;
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
  Builder b;
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
  Builder b;
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

TEST_CASE("a junction path leaving a stop line at 52 degrees to its square starts on it",
          "[ngii][mouths]") {
  // A two-lane road east whose right lane ends 1.27 m beyond its left one (an end line 20
  // degrees off square), and a junction path from the left lane's end heading 32 degrees south
  // of east onto a road going on that way: the path meets the end line 52 degrees off square,
  // past the 50 degrees a road end was bent to (K-City's path 460 leaves road 322 at 51), so
  // it started square across its own heading, a wedge beside the lane's end.
  Builder b;
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

namespace {

/// A 7 m path leaves a road heading 9 degrees south of east at 26 degrees to its end line,
/// turns left along its length and enters a road E (two vertices, 30 m) heading 38 degrees
/// north of east at a corner of 3 degrees; without `path` the two roads end apart. With `next`
/// a road F continues E straight on for 20 m.
Builder corner_path(bool path, bool next = false) {
  Builder b;
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

TEST_CASE("a road end bent onto a skewed line over sparse vertices turns over its whole reach",
          "[ngii][mouths]") {
  // A one-lane road 4 m wide (L) ends beside another (R) on a line 35 degrees off square, where
  // a two-lane road starts. L's link has a vertex 2 m before its end and none for 28 m before
  // that: the bend onto the line started at that vertex, turning 35 degrees within 2 m (the
  // lane narrowed on the inside of the turn: 4.11 m along the end line for the 4.88 m of its
  // skewed width). It now starts 8 m before the end, on the long segment.
  Builder b;
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
  Builder b;
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
  Builder b;
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

namespace {

/// A one-lane road A east to x = 30, a junction path from its end curving right to heading
/// `arrive` (degrees, negative south of east) at node E0, and a one-lane road E leaving E0 at
/// heading `leave`: the links meet at a corner of leave - arrive at E0. A's and E's marks lie
/// `half` either side of them; the path has none (it takes its lanes' widths).
Builder path_into_corner(double arrive, double leave, double half) {
  Builder b;
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

TEST_CASE("a junction path entering a road at a corner of 30 degrees ends as wide as its lane",
          "[ngii][mouths]") {
  // The path's link arrives 30 degrees off the road it enters (Sangam's four paths into road
  // 196: 29 degrees) and ends on that road's start line, bent to it. Its end width is the
  // lane's times the cosine of the corner (the width across its own link), which the road
  // builder divides by the cosine of the angle between the link and the bent reference line;
  // that link direction was a chord reaching 1.5 m into the road after it (half the corner),
  // so the path ended 0.56 m narrower than the lane, and a shoulder on each side paved the
  // step (Sangam's four stacked paths got none: a 0.20 m gap on each side of road 196's start).
  const Builder b = path_into_corner(-15.0, -45.0, 2.65);
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
  const Builder b = path_into_corner(-5.0, -55.0, 2.9);
  corsa::Diagnostics diagnostics;
  const auto conversion = corsa::ngii::convert(b.layers, {}, diagnostics);
  const LaneEndWidth path = lane_end_width(conversion.map, "A2TEST00000P", true);
  const LaneEndWidth lane = lane_end_width(conversion.map, "A2TEST00000E", false);
  const double corner = std::remainder(path.heading - lane.heading, 2.0 * M_PI);
  CHECK(std::abs(corner) > 0.8);
  CHECK(path.width == Approx(lane.width * std::cos(corner)).margin(0.05));
}
