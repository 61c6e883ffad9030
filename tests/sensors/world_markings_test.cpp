// OpenDRIVE signals that stand for road markings (German and Korean numbers) and roadMark
// objects: painted on the road, labelled, never drawn as a sign on a post.

#include <catch2/catch.hpp>
#include <string>

#include "corsa/sensors/labels.h"
#include "corsa/sensors/world.h"
#include "markings_fixture.h"

using namespace corsa::sensors;

using corsa::test::down_at;
using corsa::test::marked_world;
using corsa::test::paint_at;
using corsa::test::street_with;

TEST_CASE("a stop line signal is painted across the lanes its orientation serves",
          "[sensors][world][signals][markings]") {
  // StVO 294, for traffic towards +s: the right lanes (-1, -2) of right-hand traffic.
  const auto map = street_with(
      R"(<signal id="stop" s="30" t="-7" orientation="+" dynamic="no" country="DE" type="294" subtype="-1"/>)");
  auto world = marked_world(map);
  CHECK(world->report.markings == 1);
  CHECK(world->report.signs == 0);  // no post with a generic sign
  CHECK(world->warnings.empty());
  CHECK(paint_at(world->scene, 30.0, -1.0));  // lane -1
  CHECK(paint_at(world->scene, 30.0, -6.0));  // lane -2
  CHECK(paint_at(world->scene, 30.2, -3.5));  // 0.5 m wide, centred on s
  CHECK_FALSE(paint_at(world->scene, 30.4, -3.5));
  CHECK_FALSE(paint_at(world->scene, 30.0, 1.75));  // the oncoming lane
  CHECK(down_at(world->scene, 30.0, -8.0).semantic == SemanticClass::kSidewalk);
  // Labelled as one object with the signal's id and type.
  const RayHit hit = down_at(world->scene, 30.0, -1.0);
  REQUIRE(hit.instance_id >= kStaticInstanceBase);
  const std::vector<uint32_t> instance = {hit.instance_id};
  const std::vector<uint8_t> semantic = {static_cast<uint8_t>(SemanticClass::kLaneMarking)};
  const auto labels = static_object_labels(world->scene, instance, 1, semantic);
  REQUIRE(labels.size() == 1);
  CHECK(labels[0].info.kind == "stop_line");
  CHECK(labels[0].info.signal_id == "stop");
  CHECK(labels[0].info.type == "294");
}

TEST_CASE("a crosswalk signal is zebra bars across every drivable lane",
          "[sensors][world][signals][markings]") {
  // StVO 293 in CARLA's country code; bars 0.5 m wide every metre from the right lanes' edge
  // at t = -7, 4 m along the road.
  const auto map = street_with(
      R"(<signal id="zebra" s="60" t="0" orientation="none" dynamic="no" country="OpenDRIVE" type="293" subtype="-1"/>)");
  auto world = marked_world(map);
  CHECK(world->report.markings == 1);
  CHECK(world->report.signs == 0);
  CHECK(paint_at(world->scene, 60.0, -6.75));
  CHECK_FALSE(paint_at(world->scene, 60.0, -6.25));  // the gap between bars
  CHECK(paint_at(world->scene, 61.9, -0.75));
  CHECK(paint_at(world->scene, 60.0, 1.25));  // the oncoming lane too
  CHECK(paint_at(world->scene, 60.0, 3.25));
  CHECK_FALSE(paint_at(world->scene, 62.2, -0.75));  // 4 m along the road
  CHECK(down_at(world->scene, 60.0, 4.5).semantic == SemanticClass::kSidewalk);
}

TEST_CASE("a give-way line signal covers only its validity lanes, in dashes",
          "[sensors][world][signals][markings]") {
  // StVO 341 with <validity> lane -1 only; a length of 0.3 m from the signal (OpenDRIVE 1.8).
  const auto map = street_with(
      R"(<signal id="wait" s="90" t="-3.5" orientation="+" dynamic="no" country="DE" type="341" subtype="-1" length="0.3"><validity fromLane="-1" toLane="-1"/></signal>)");
  auto world = marked_world(map);
  CHECK(world->report.markings == 1);
  CHECK(paint_at(world->scene, 90.0, -3.25));        // a dash from the lane's edge at t = -3.5
  CHECK_FALSE(paint_at(world->scene, 90.0, -2.9));   // the gap after it
  CHECK(paint_at(world->scene, 90.0, -2.5));         // the next dash
  CHECK_FALSE(paint_at(world->scene, 90.2, -3.25));  // 0.3 m along the road
  CHECK_FALSE(paint_at(world->scene, 90.0, -5.0));   // lane -2 is not in the validity
}

TEST_CASE("road marking signals Corsa does not paint are left out with one located warning",
          "[sensors][world][signals][markings]") {
  // StVO 297 (arrows) twice: no sign post in the road, one warning at the first signal.
  const auto map = street_with(
      R"(<signal id="a1" s="20" t="-1.75" orientation="+" dynamic="no" country="DE" type="297" subtype="10"/>
         <signal id="a2" s="25" t="-5.25" orientation="+" dynamic="no" country="DE" type="297" subtype="10"/>)");
  auto world = marked_world(map);
  CHECK(world->report.signs == 0);
  CHECK(world->report.markings == 0);
  REQUIRE(world->warnings.size() == 1);
  CHECK(world->warnings[0].line > 0);
  CHECK_THAT(world->warnings[0].message, Catch::Contains("road marking Corsa does not paint"));
  CHECK(down_at(world->scene, 20.0, -1.75).semantic == SemanticClass::kRoad);
}

TEST_CASE("Korean stop line and crosswalk signals are painted as their German counterparts",
          "[sensors][world][signals][markings][korea]") {
  // 530 stop line (0.45 m wide) for traffic towards +s, 532 crosswalk over every lane.
  const auto map = street_with(
      R"(<signal id="k-stop" s="30" t="-3.5" orientation="+" dynamic="no" country="KR" type="530" subtype="-1"/>
         <signal id="k-zebra" s="60" t="0" orientation="none" dynamic="no" country="KOR" type="532" subtype="-1"/>)");
  auto world = marked_world(map);
  CHECK(world->report.markings == 2);
  CHECK(world->report.signs == 0);
  CHECK(world->warnings.empty());
  CHECK(paint_at(world->scene, 30.0, -1.0));
  CHECK(paint_at(world->scene, 30.0, -6.0));
  CHECK(paint_at(world->scene, 30.2, -3.5));
  CHECK_FALSE(paint_at(world->scene, 30.25, -3.5));  // 0.45 m wide, centred on s
  CHECK_FALSE(paint_at(world->scene, 30.0, 1.75));
  CHECK(paint_at(world->scene, 60.0, -6.75));
  CHECK_FALSE(paint_at(world->scene, 60.0, -6.25));
  CHECK(paint_at(world->scene, 60.0, 1.25));
  const RayHit hit = down_at(world->scene, 60.0, -6.75);
  const std::vector<uint32_t> instance = {hit.instance_id};
  const std::vector<uint8_t> semantic = {static_cast<uint8_t>(SemanticClass::kLaneMarking)};
  const auto labels = static_object_labels(world->scene, instance, 1, semantic);
  REQUIRE(labels.size() == 1);
  CHECK(labels[0].info.kind == "crosswalk");
  CHECK(labels[0].info.country == "KOR");
  CHECK(labels[0].info.type == "532");
}

TEST_CASE("a Korean crosswalk-ahead signal is a hollow diamond in each lane it serves",
          "[sensors][world][signals][markings][korea]") {
  // 529 for traffic towards +s: lanes -1 (t -3.5..0) and -2 (t -7..-3.5); the diamond is
  // 4.8 m along the road and 1.35 m across, with a 0.15 m stroke.
  const auto map = street_with(
      R"(<signal id="ahead" s="40" t="-3.5" orientation="+" dynamic="no" country="KR" type="529" subtype="-1"/>)");
  auto world = marked_world(map);
  CHECK(world->report.markings == 1);
  CHECK(world->warnings.empty());
  CHECK(paint_at(world->scene, 42.3, -1.75));        // near the forward tip, lane -1
  CHECK(paint_at(world->scene, 40.0, -1.1));         // the left corner's stroke
  CHECK(paint_at(world->scene, 40.0, -2.4));         // the right corner's stroke
  CHECK_FALSE(paint_at(world->scene, 40.0, -1.75));  // hollow inside
  CHECK_FALSE(paint_at(world->scene, 40.0, -0.9));   // 1.35 m wide
  CHECK(paint_at(world->scene, 37.7, -5.25));        // the second lane's diamond
  CHECK_FALSE(paint_at(world->scene, 40.0, 1.75));   // not the oncoming lane
}

TEST_CASE("Korean marking numbers Corsa does not paint warn once and are never signs",
          "[sensors][world][signals][markings][korea]") {
  // 520 (the second slow marking, whose drawing was not confirmed) twice and 542 (unprotected
  // left turn) once.
  const auto map = street_with(
      R"(<signal id="t1" s="20" t="-1.75" orientation="+" dynamic="no" country="KR" type="520" subtype="-1"/>
         <signal id="t2" s="25" t="-5.25" orientation="+" dynamic="no" country="KR" type="520" subtype="-1"/>
         <signal id="u1" s="45" t="-1.75" orientation="+" dynamic="no" country="KR" type="542" subtype="-1"/>)");
  auto world = marked_world(map);
  CHECK(world->report.signs == 0);
  CHECK(world->report.markings == 0);
  REQUIRE(world->warnings.size() == 2);
  CHECK(world->warnings[0].line > 0);
  CHECK_THAT(world->warnings[0].message, Catch::Contains("'520' (country 'KR', slow)"));
  CHECK_THAT(world->warnings[1].message,
             Catch::Contains("'542' (country 'KR', unprotected left turn)"));
  CHECK(down_at(world->scene, 20.0, -1.75).semantic == SemanticClass::kRoad);
}

TEST_CASE("roadMark objects are painted in their outline, arrows included",
          "[sensors][world][objects][markings]") {
  // An NGII-style stop line (a closed outline 0.4 m wide in road coordinates) and an arrow
  // (a non-convex outline in local u, v), as `corsa convert ngii` writes B2 and B3 marks.
  const auto map = street_with(
      "",
      R"(<object id="sl" type="roadMark" subtype="stopLine" name="stop line" s="30" t="-3.5" zOffset="0">
            <outlines><outline id="0" closed="true">
              <cornerRoad s="29.8" t="-7" dz="0" height="0"/><cornerRoad s="30.2" t="-7" dz="0" height="0"/>
              <cornerRoad s="30.2" t="0" dz="0" height="0"/><cornerRoad s="29.8" t="0" dz="0" height="0"/>
            </outline></outlines></object>
          <object id="arrow" type="roadMark" subtype="5371" name="arrow" s="50" t="-1.75" zOffset="0" hdg="0">
            <outlines><outline id="0" closed="true">
              <cornerLocal u="-2" v="-0.15" z="0" height="0"/><cornerLocal u="1" v="-0.15" z="0" height="0"/>
              <cornerLocal u="1" v="-0.6" z="0" height="0"/><cornerLocal u="2.5" v="0" z="0" height="0"/>
              <cornerLocal u="1" v="0.6" z="0" height="0"/><cornerLocal u="1" v="0.15" z="0" height="0"/>
              <cornerLocal u="-2" v="0.15" z="0" height="0"/>
            </outline></outlines></object>)");
  auto world = marked_world(map);
  CHECK(world->warnings.empty());
  CHECK(paint_at(world->scene, 30.0, -1.0));
  CHECK(paint_at(world->scene, 30.0, -6.5));
  CHECK_FALSE(paint_at(world->scene, 30.3, -3.5));
  CHECK(paint_at(world->scene, 49.0, -1.75));        // the shaft
  CHECK_FALSE(paint_at(world->scene, 49.0, -2.1));   // beside the shaft: not its bounding box
  CHECK(paint_at(world->scene, 51.2, -2.2));         // the head is wider than the shaft
  CHECK_FALSE(paint_at(world->scene, 52.7, -1.75));  // beyond the tip
  const RayHit hit = down_at(world->scene, 49.0, -1.75);
  const std::vector<uint32_t> instance = {hit.instance_id};
  const std::vector<uint8_t> semantic = {static_cast<uint8_t>(SemanticClass::kLaneMarking)};
  const auto labels = static_object_labels(world->scene, instance, 1, semantic);
  REQUIRE(labels.size() == 1);
  CHECK(labels[0].info.kind == "road_mark");
  CHECK(labels[0].info.type == "5371");
}

TEST_CASE("traffic lights from the NGII import get Korean horizontal heads",
          "[sensors][world][signals][korea]") {
  // The same light twice: written by `corsa convert ngii` (German catalogue number, country
  // "OpenDRIVE", the NGII layer in userData) at s 30, and a plain one at s 70. Both stand at
  // t = -8 facing traffic towards +s, heads 5 m up.
  const auto map = street_with(
      R"(<signal id="ngii" s="30" t="-8" zOffset="5" orientation="+" dynamic="yes" country="OpenDRIVE" type="1000001" subtype="-1"><userData code="ngii:C1_TRAFFICLIGHT.Type" value="1"/></signal>
         <signal id="plain" s="70" t="-8" zOffset="5" orientation="+" dynamic="yes" country="OpenDRIVE" type="1000001" subtype="-1"/>)");
  auto world = marked_world(map);
  CHECK(world->report.traffic_lights == 2);
  // A horizontal head reaches 0.8 m to either side of the signal; a vertical one 0.18 m.
  const auto head_at = [&](double s, double t) {
    const auto hit = world->scene.intersect({s - 10.0, t, 5.2}, {1.0, 0.0, 0.0}, 12.0);
    return hit && hit->semantic == SemanticClass::kTrafficLight;
  };
  CHECK(head_at(30.0, -7.4));
  CHECK(head_at(30.0, -8.6));
  CHECK_FALSE(head_at(70.0, -7.4));
  CHECK(head_at(70.0, -8.0));
}

TEST_CASE("marking signals with wild sizes are capped at 50 m with a located warning and end",
          "[sensors][world][signals][markings][robustness]") {
  // A crosswalk and a give-way line covering no lane fall back to their width around t: 1e300
  // m (where a += 1 m no longer moves) and 1e9 m (1e9 bars) are capped; so are the hatched
  // areas' sizes (1e300 m would overflow their stripe count) and a word's length.
  const auto map = street_with(
      R"(<signal id="zebra" s="20" t="0" orientation="none" dynamic="no" country="DE" type="293" subtype="-1" width="1e300">
           <validity fromLane="7" toLane="7"/></signal>
         <signal id="yield" s="35" t="0" orientation="none" dynamic="no" country="DE" type="341" subtype="-1" width="1e9">
           <validity fromLane="7" toLane="7"/></signal>
         <signal id="island" s="60" t="0" orientation="none" dynamic="no" country="KR" type="531" subtype="-1" length="1e300" width="1e300"/>
         <signal id="box" s="80" t="-3.5" orientation="none" dynamic="no" country="KR" type="524" subtype="-1" length="8" width="1e300"/>
         <signal id="slow" s="50" t="-1.75" orientation="+" dynamic="no" country="KR" type="519" subtype="-1" length="1e300"/>)");
  auto world = marked_world(map);
  CHECK(world->report.markings == 5);
  int capped = 0;
  for (const auto& warning : world->warnings) {
    CHECK(warning.line > 0);
    if (warning.message.find("is more than 50 m; painted 50 m") != std::string::npos) {
      ++capped;
    }
  }
  CHECK(capped == 6);  // the two widths, 531's length and width, 524's width, 519's length
  CHECK(paint_at(world->scene, 20.0, 0.25));  // the zebra's bars from t -25, every 1 m
  CHECK_FALSE(paint_at(world->scene, 20.0, 0.75));
}
