// Joints between lanes of different widths: a narrower lane widens to the wider one's borders
// at the joint, a step too large for that is paved by shoulders (mouth fills), and roads of
// several lanes meet with all their borders (mouth_gaps.h; the shared layers in mouth_layers.h).

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstddef>
#include <string>

#include "corsa/core/diagnostic.h"
#include "corsa/ngii/convert.h"
#include "corsa/xodr/map.h"
#include "corsa/xodr/parser.h"
#include "mouth_fills.h"
#include "mouth_gaps.h"
#include "mouth_layers.h"

namespace {

using corsa::ngii::testing::mouth_gaps_of;
using corsa::ngii::testing::MouthLayers;

/// A one-lane road east from x = 0 to 30 whose marks lie `half_a` either side of it, continued
/// by a road of two lanes from x = 30: its left lane straight on (marks `half_b` either side),
/// its right lane splitting off that one at zero width at x = 30 and lying beside it from
/// x = 40.
MouthLayers lane_count_change(double half_a, double half_b) {
  MouthLayers b;
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

}  // namespace

TEST_CASE("an ordinary lane wider than the lane it continues into meets it edge to edge",
          "[ngii][mouths]") {
  // The one-lane road's marks are 4.0 m apart, the continuing lane's 3.2 m: each road took
  // its own marks' width up to the joint, and the wider lane's end stuck out 0.4 m beyond
  // both sides of the narrower one's start. The narrower lane now widens to the wider one's
  // borders at the joint (its centre stays on its link) and eases back to its own width.
  const MouthLayers b = lane_count_change(2.0, 1.6);
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
  const MouthLayers b = lane_count_change(2.5, 1.5);
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

TEST_CASE("two two-lane roads whose lanes continue one to one meet with all their borders",
          "[ngii][mouths]") {
  // Lanes centred 3.5 m apart on both sides of a joint at x = 30: before it 4.1 m and 2.9 m wide,
  // after it 3.5 m each, so that the border between the lanes lies 0.3 m apart across the joint
  // and each road sticks out 0.3 m beyond the other on one side. Meeting lane by lane would
  // move a centre by 0.15 m (the neighbour's border is shared), so the pairs were left alone
  // and both sides kept a 0.3 m sliver of unpaved ground. The road after the joint now takes
  // the road before's borders there, every lane keeping its centre.
  MouthLayers b;
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
  MouthLayers b;
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
