// Holes in junctions: which uncovered places a junction's roads enclose, how large they are and
// which of them are paved (the small and the narrow), on rings of connecting roads.

#include "corsa/xodr/junction_holes.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "corsa/xodr/map.h"
#include "corsa/xodr/parser.h"
#include "corsa/xodr/writer.h"
#include "junction_holes_map.h"

using namespace corsa::xodr;
using corsa::test::hole_ring;
using corsa::test::hole_ring_xodr;
using corsa::test::hole_rings_document;
using corsa::test::HoleRing;

namespace {

Map rings_map(const std::string& rings) {
  corsa::Diagnostics diagnostics;
  Map map = Map::build(parse_xodr_text(hole_rings_document(rings), "rings.xodr", diagnostics),
                       diagnostics);
  CHECK(diagnostics.count(corsa::Severity::kWarning) == 0);
  return map;
}

std::vector<JunctionHole> holes_of(const Map& map) {
  return find_junction_holes(map, build_road_mesh(map, MeshOptions{.road_marks = false}));
}

}  // namespace

TEST_CASE("a junction's roads that enclose a small uncovered patch make a hole to pave",
          "[xodr][holes]") {
  // The 8 m ring leaves 1 x 1 m inside its lanes; the 30 x 8 m ring a 23 x 1 m strip (large
  // but narrow); the 20 m ring 13 x 13 m, room for an island.
  const Map map =
      rings_map(hole_ring_xodr(hole_ring("A", 0)) + hole_ring_xodr(hole_ring("B", 100, 30)) +
                hole_ring_xodr(hole_ring("C", 200, 20, 20)));
  const auto holes = holes_of(map);
  REQUIRE(holes.size() == 3);
  CHECK(map.junction(holes[0].junction).id == "A");
  CHECK(holes[0].kind == HoleKind::kPaved);
  CHECK(holes[0].area == Approx(1.0).margin(0.03));
  CHECK(holes[0].width == Approx(1.0).margin(0.11));
  CHECK(holes[0].centre.x == Approx(4.0).margin(0.05));
  CHECK(holes[0].centre.y == Approx(4.0).margin(0.05));
  CHECK(holes[0].centre.z == Approx(0.0).margin(1e-6));
  CHECK(holes[1].kind == HoleKind::kPaved);
  CHECK(holes[1].area == Approx(23.0).margin(0.3));
  CHECK(holes[1].width < 1.2);
  CHECK(holes[2].kind == HoleKind::kLarge);
  CHECK(holes[2].area == Approx(169.0).margin(1.5));
  CHECK(holes[2].width == Approx(13.0).margin(0.2));
  // The paving covers the hole and a rim of one cell under the roads, 2 mm down.
  CHECK(holes[0].triangles.size() == 2 * (12 * 12));
  for (const auto& v : holes[0].vertices) {
    CHECK(v.z == Approx(-0.002).margin(1e-9));
    CHECK(v.x >= 3.4 - 1e-9);
    CHECK(v.x <= 4.6 + 1e-9);
  }
  CHECK(holes[2].triangles.empty());  // kept as ground
}

TEST_CASE("a hole bordered by a sidewalk or with a pole in it is an island, not paved",
          "[xodr][holes]") {
  HoleRing kerbed = hole_ring("K", 0);
  kerbed.inner = "sidewalk";
  HoleRing pole = hole_ring("P", 100);
  pole.pole = true;
  const Map map = rings_map(hole_ring_xodr(kerbed) + hole_ring_xodr(pole));
  const auto holes = holes_of(map);
  REQUIRE(holes.size() == 2);
  CHECK(holes[0].kind == HoleKind::kKerbed);
  CHECK(holes[1].kind == HoleKind::kOccupied);
  CHECK(holes[0].triangles.empty());
  CHECK(holes[1].triangles.empty());
}

TEST_CASE("a junction's <boundary> is its area: a hole outside it is none of its own",
          "[xodr][holes]") {
  // Ring O's boundary goes round the ring's outer borders (its roads' right lanes), so the hole
  // is inside; ring S's boundary is its first road's strip alone, so the hole lies outside.
  std::string around;
  for (const char* road : {"O1", "O2", "O3", "O4"}) {
    around += std::string(R"(<segment type="lane" roadId=")") + road +
              R"(" boundaryLane="-1" sStart="begin" sEnd="end"/>)";
  }
  HoleRing around_ring = hole_ring("O", 0);
  around_ring.boundary = around;
  HoleRing strip_ring = hole_ring("S", 100);
  strip_ring.boundary =
      R"(<segment type="lane" roadId="S1" boundaryLane="-1" sStart="begin" sEnd="end"/>
         <segment type="joint" roadId="S1" contactPoint="end" jointLaneStart="-1" jointLaneEnd="1"/>
         <segment type="lane" roadId="S1" boundaryLane="1" sStart="end" sEnd="0"/>)";
  const Map map = rings_map(hole_ring_xodr(around_ring) + hole_ring_xodr(strip_ring));
  REQUIRE(map.junction(0).boundary.size() == 4);
  CHECK(map.junction(1).boundary[1].joint);
  CHECK(map.junction(1).boundary[1].contact_point == ContactPoint::kEnd);
  CHECK(map.junction(1).boundary[1].joint_lane_end == 1);
  const auto holes = holes_of(map);
  REQUIRE(holes.size() == 1);
  CHECK(map.junction(holes[0].junction).id == "O");
  // Written back as it was read.
  corsa::Diagnostics diagnostics;
  const MapData again = parse_xodr_text(write_xodr_text(map.data()), "again.xodr", diagnostics);
  REQUIRE(again.junctions[1].boundary.size() == 3);
  CHECK(again.junctions[0].boundary[2].road_id == "O3");
  CHECK(std::isinf(again.junctions[0].boundary[2].s_end));
  CHECK(again.junctions[1].boundary[1].joint_lane_start == -1);
  CHECK(std::isinf(again.junctions[1].boundary[2].s_start));  // "end"
  CHECK(again.junctions[1].boundary[2].s_end == 0.0);
  CHECK(holes[0].kind == HoleKind::kPaved);
}

TEST_CASE("a junction boundary segment of an unknown type is a located error",
          "[xodr][holes][errors]") {
  HoleRing ring = hole_ring("E", 0);
  ring.boundary = R"(<segment type="curve" roadId="E1"/>)";
  const std::string text = hole_rings_document(hole_ring_xodr(ring));
  corsa::Diagnostics diagnostics;
  try {
    (void)parse_xodr_text(text, "bad.xodr", diagnostics);
    FAIL("no error");
  } catch (const corsa::InputError& e) {
    CHECK(e.diagnostic().format().rfind("bad.xodr:", 0) == 0);
    CHECK_THAT(e.diagnostic().format(), Catch::Contains("'lane' or 'joint'"));
  }
}

TEST_CASE("a junction boundary segment naming a missing road is a located error",
          "[xodr][holes][errors]") {
  HoleRing ring = hole_ring("M", 0);
  ring.boundary =
      R"(<segment type="lane" roadId="nowhere" boundaryLane="-1" sStart="0" sEnd="end"/>)";
  corsa::Diagnostics diagnostics;
  try {
    (void)Map::build(
        parse_xodr_text(hole_rings_document(hole_ring_xodr(ring)), "bad.xodr", diagnostics),
        diagnostics);
    FAIL("no error");
  } catch (const corsa::InputError& e) {
    CHECK(e.diagnostic().format().rfind("bad.xodr:", 0) == 0);
    CHECK_THAT(e.diagnostic().format(), Catch::Contains("road 'nowhere', which does not exist"));
  }
}
