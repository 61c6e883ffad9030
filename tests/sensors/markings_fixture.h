#pragma once

// A small straight street with the signals and objects a test gives, its world built without
// plants and street lights, and rays straight down to see what paint lies where.

#include <catch2/catch.hpp>
#include <memory>
#include <string>

#include "corsa/xodr/parser.h"
#include "world_fixture.h"

namespace corsa::test {

/// The OpenDRIVE text of a straight 100 m road along +x (so t is y): a sidewalk and one lane on
/// the left, two lanes and a sidewalk on the right, every lane 3.5 m and sidewalks 2 m wide; its
/// signals are `signals` and its objects `objects`. Tests that need another shape edit it.
inline std::string street_text(const std::string& signals, const std::string& objects = "") {
  const std::string lane =
      R"(<lane id="ID" type="TYPE"><width sOffset="0" a="W" b="0" c="0" d="0"/></lane>)";
  auto make = [&](const char* id, const char* type, const char* w) {
    std::string l = lane;
    l.replace(l.find("ID"), 2, id);
    l.replace(l.find("TYPE"), 4, type);
    l.replace(l.find("W\""), 1, w);
    return l;
  };
  return R"(<?xml version="1.0"?><OpenDRIVE><header revMajor="1" revMinor="8"/>
<road id="1" length="100" junction="-1"><planView>
<geometry s="0" x="0" y="0" hdg="0" length="100"><line/></geometry></planView>
<lanes><laneSection s="0"><left>)" +
         make("2", "sidewalk", "2") + make("1", "driving", "3.5") + R"(</left>
<center><lane id="0" type="none"/></center><right>)" +
         make("-1", "driving", "3.5") + make("-2", "driving", "3.5") + make("-3", "sidewalk", "2") +
         R"(</right></laneSection></lanes><objects>)" + objects + R"(</objects><signals>)" +
         signals + R"(</signals></road></OpenDRIVE>)";
}

/// The map of an OpenDRIVE text (such as street_text's).
inline corsa::xodr::Map map_of(const std::string& text) {
  corsa::Diagnostics diagnostics;
  return corsa::xodr::Map::build(corsa::xodr::parse_xodr_text(text, "markings.xodr", diagnostics),
                                 diagnostics);
}

/// The map of street_text(signals, objects).
inline corsa::xodr::Map street_with(const std::string& signals, const std::string& objects = "") {
  return map_of(street_text(signals, objects));
}

/// The world of `map` without plants, street lights and street furniture (nothing over the road
/// but the signals).
inline std::unique_ptr<BuiltWorld> marked_world(const corsa::xodr::Map& map) {
  sensors::WorldOptions options;
  options.seed = 3;
  options.vegetation = false;
  options.street_lights = false;
  options.street_furniture = false;
  return build_world_scene(map, options);
}

/// What a ray straight down at (x, y) hits first.
inline sensors::RayHit down_at(const sensors::Scene& scene, double x, double y) {
  const auto hit = scene.intersect({x, y, 5.0}, {0.0, 0.0, -1.0}, 10.0);
  REQUIRE(hit);
  return *hit;
}

inline bool paint_at(const sensors::Scene& scene, double x, double y) {
  return down_at(scene, x, y).semantic == sensors::SemanticClass::kLaneMarking;
}

}  // namespace corsa::test
