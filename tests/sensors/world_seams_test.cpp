// Cracks between roads that lie side by side (a centre strip split between two opposing roads,
// as the NGII import writes it): the ground must not show through.

#include <catch2/catch.hpp>
#include <string>

#include "corsa/sensors/world.h"
#include "markings_fixture.h"

using namespace corsa::sensors;

using corsa::test::down_at;
using corsa::test::marked_world;

namespace {

/// Two opposing 60 m roads along x, each with a 0.5 m restricted strip on its left and a 3.5 m
/// driving lane on its right: road 1 eastwards with its strip up to y = 0.5, road 2 westwards
/// from y = 0.5 + gap, so `gap` metres of nothing lie between the strips; road 2's surface
/// `rise` metres above road 1's.
corsa::xodr::Map opposing_roads(const std::string& gap, const std::string& rise = "0") {
  const std::string lanes =
      R"(<lanes><laneSection s="0"><left><lane id="1" type="restricted"><width sOffset="0" a="0.5" b="0" c="0" d="0"/></lane></left>
<center><lane id="0" type="none"/></center><right><lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right></laneSection></lanes>)";
  const std::string text =
      R"(<?xml version="1.0"?><OpenDRIVE><header revMajor="1" revMinor="8"/>
<road id="1" length="60" junction="-1"><planView><geometry s="0" x="0" y="0" hdg="0" length="60"><line/></geometry></planView>)" +
      lanes +
      R"(</road><road id="2" length="60" junction="-1"><planView><geometry s="0" x="60" y=")" +
      std::to_string(1.0 + std::stod(gap)) +
      R"(" hdg="3.141592653589793" length="60"><line/></geometry></planView><elevationProfile><elevation s="0" a=")" +
      rise + R"(" b="0" c="0" d="0"/></elevationProfile>)" + lanes + R"(</road></OpenDRIVE>)";
  corsa::Diagnostics diagnostics;
  return corsa::xodr::Map::build(corsa::xodr::parse_xodr_text(text, "seam.xodr", diagnostics),
                                 diagnostics);
}

}  // namespace

TEST_CASE("a crack of millimetres between two roads' centre strips shows road, not ground",
          "[sensors][world][seams]") {
  const auto map = opposing_roads("0.003");
  auto world = marked_world(map);
  // Both roads' strip borders, 60 m each.
  CHECK(world->report.seam_length == Approx(120.0));
  for (double x = 1.0; x < 60.0; x += 7.3) {
    CAPTURE(x);
    const RayHit hit = down_at(world->scene, x, 0.5015);  // in the crack
    CHECK(hit.semantic == SemanticClass::kRoad);
    CHECK(hit.point.z == Approx(0.0).margin(0.002));  // at the road's height, not the ground's
    CHECK(down_at(world->scene, x, 0.3).semantic == SemanticClass::kRoad);
    CHECK(down_at(world->scene, x, 0.7).semantic == SemanticClass::kRoad);
  }
}

TEST_CASE("a road's outer edge with no road beside it keeps the ground beyond it",
          "[sensors][world][seams]") {
  const auto map = opposing_roads("0.5");  // a real 0.5 m gap: ground between the roads
  auto world = marked_world(map);
  CHECK(world->report.seam_length == 0.0);
  CHECK(down_at(world->scene, 30.0, 0.52).semantic == SemanticClass::kTerrain);
  CHECK(down_at(world->scene, 30.0, 0.98).semantic == SemanticClass::kTerrain);
  CHECK(down_at(world->scene, 30.0, -3.52).semantic == SemanticClass::kTerrain);  // outer edge
}

TEST_CASE("a crack where one road lies a few centimetres above the other is closed from below",
          "[sensors][world][seams]") {
  // Road 2 5 cm above road 1: road 2's band would stand over road 1's surface, so only road
  // 1's band is laid, under the crack and under road 2's edge.
  auto world = marked_world(opposing_roads("0.003", "0.05"));
  CHECK(world->report.seam_length == Approx(60.0));
  for (double x = 1.0; x < 60.0; x += 7.3) {
    CAPTURE(x);
    const RayHit hit = down_at(world->scene, x, 0.5015);
    CHECK(hit.semantic == SemanticClass::kRoad);
    CHECK(hit.point.z == Approx(0.0).margin(0.002));  // road 1's band, not above it
  }
}

TEST_CASE("a crack of millimetres where one road ends and the next begins shows road",
          "[sensors][world][seams]") {
  // Two 50 m roads along x, two 3.5 m lanes each: the second begins 5 mm after the first ends
  // (as where a road meets a junction's connecting roads); a third lies 0.5 m beyond the second,
  // a true gap.
  const std::string lanes =
      R"(<lanes><laneSection s="0"><left><lane id="1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></left>
<center><lane id="0" type="none"/></center><right><lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right></laneSection></lanes>)";
  auto road = [&](const char* id, const char* x) {
    return std::string(R"(<road id=")") + id +
           R"(" length="50" junction="-1"><planView><geometry s="0" x=")" + x +
           R"(" y="0" hdg="0" length="50"><line/></geometry></planView>)" + lanes + "</road>";
  };
  const std::string text =
      R"(<?xml version="1.0"?><OpenDRIVE><header revMajor="1" revMinor="8"/>)" + road("1", "0") +
      road("2", "50.005") + road("3", "100.505") + "</OpenDRIVE>";
  corsa::Diagnostics diagnostics;
  const auto map = corsa::xodr::Map::build(
      corsa::xodr::parse_xodr_text(text, "ends.xodr", diagnostics), diagnostics);
  auto world = marked_world(map);
  for (double y = -3.2; y < 3.5; y += 0.9) {
    CAPTURE(y);
    const RayHit hit = down_at(world->scene, 50.0025, y);  // in the crack
    CHECK(hit.semantic == SemanticClass::kRoad);
    CHECK(hit.point.z == Approx(0.0).margin(0.002));
    CHECK(down_at(world->scene, 100.25, y).semantic == SemanticClass::kTerrain);  // the true gap
  }
}
