// Holes that a junction's roads enclose: the small and the narrow are paved as road, islands
// keep the ground.

#include <catch2/catch.hpp>

#include "corsa/sensors/world.h"
#include "corsa/xodr/parser.h"
#include "junction_holes_map.h"
#include "markings_fixture.h"

using namespace corsa::sensors;

using corsa::test::down_at;
using corsa::test::hole_ring;
using corsa::test::hole_ring_xodr;
using corsa::test::hole_rings_document;
using corsa::test::HoleRing;
using corsa::test::marked_world;

TEST_CASE("a small hole between a junction's roads shows road, an island keeps the ground",
          "[sensors][world][holes]") {
  // Rings of connecting roads: 8 m (a 1 m² hole), 30 x 8 m (a 23 x 1 m strip), 20 m (a 13 m
  // island), 8 m with a sidewalk inside its first road (a kerbed island).
  HoleRing kerbed = hole_ring("K", 300);
  kerbed.inner = "sidewalk";
  const std::string text = hole_rings_document(
      hole_ring_xodr(hole_ring("A", 0)) + hole_ring_xodr(hole_ring("B", 100, 30)) +
      hole_ring_xodr(hole_ring("C", 200, 20, 20)) + hole_ring_xodr(kerbed));
  corsa::Diagnostics diagnostics;
  const auto map = corsa::xodr::Map::build(
      corsa::xodr::parse_xodr_text(text, "rings.xodr", diagnostics), diagnostics);
  auto world = marked_world(map);
  CHECK(world->report.junction_holes == 4);
  CHECK(world->report.junction_holes_paved == 2);
  CHECK(world->report.junction_paved_area == Approx(24.0).margin(0.3));
  for (double x : {3.6, 4.0, 4.4}) {
    for (double y : {3.6, 4.0, 4.4}) {
      CAPTURE(x, y);
      const RayHit hit = down_at(world->scene, x, y);
      CHECK(hit.semantic == SemanticClass::kRoad);
      CHECK(hit.point.z == Approx(-0.002).margin(0.001));  // just under the roads around
    }
  }
  CHECK(down_at(world->scene, 3.0, 4.0).point.z == Approx(0.0).margin(1e-4));     // the road above
  CHECK(down_at(world->scene, 115.0, 4.0).semantic == SemanticClass::kRoad);      // the strip
  CHECK(down_at(world->scene, 210.0, 10.0).semantic == SemanticClass::kTerrain);  // the island
  CHECK(down_at(world->scene, 304.0, 4.0).semantic == SemanticClass::kTerrain);   // kerbed
}
