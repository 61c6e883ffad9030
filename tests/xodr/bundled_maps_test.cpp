// The maps in scenarios/maps/ are exactly what the generator writes, and load cleanly.

#include "bundled_maps.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "corsa/core/atomic_file.h"
#include "corsa/xodr/route.h"
#include "corsa/xodr/writer.h"

using namespace corsa::xodr;

namespace {

std::filesystem::path bundled_file(const char* name) {
  return std::filesystem::path(CORSA_SOURCE_DIR) / "scenarios" / "maps" / name;
}

Map load_clean(const char* name) {
  corsa::Diagnostics diagnostics;
  Map map = Map::load(bundled_file(name), diagnostics);
  for (const auto& d : diagnostics.all()) {
    UNSCOPED_INFO(d.format());
  }
  CHECK(diagnostics.size() == 0);
  return map;
}

}  // namespace

TEST_CASE("bundled maps match their generator byte for byte", "[xodr][bundled]") {
  CHECK(corsa::read_file(bundled_file("motorway_2km.xodr")) ==
        write_xodr_text(bundled::motorway()));
  CHECK(corsa::read_file(bundled_file("intersection_4way.xodr")) ==
        write_xodr_text(bundled::intersection()));
}

TEST_CASE("the bundled motorway is 2 km of three marked lanes each way", "[xodr][bundled]") {
  const Map map = load_clean("motorway_2km.xodr");
  REQUIRE(map.road_count() == 1);
  CHECK(map.road(0).length == 2000.0);
  std::vector<LaneSpan> spans;
  map.lane_spans(0, 1000.0, spans);
  size_t driving = 0;
  for (const LaneSpan& span : spans) {
    driving += map.lane(LaneRef{0, 0, span.id})->type == LaneType::kDriving ? 1 : 0;
  }
  CHECK(driving == 6);
  CHECK(spans.front().t_max() == Approx(3 * 3.75 + 2.5));
  for (const Lane& lane : map.road(0).lane_sections[0].lanes) {
    CHECK(lane.road_marks.size() == 1);
  }
  const auto route = find_route(map, LanePoint{0, -1, 10.0}, LanePoint{0, -3, 1990.0});
  REQUIRE(route);
  CHECK(route->lane_changes == 2);
  CHECK(route->length == Approx(1980.0).margin(1e-6));
}

TEST_CASE("the bundled intersection connects every arm to the three others", "[xodr][bundled]") {
  const Map map = load_clean("intersection_4way.xodr");
  CHECK(map.road_count() == 16);
  REQUIRE(map.junction_count() == 1);
  CHECK(map.junction(0).connections.size() == 12);
  // Connecting roads join their arms exactly (lane centres meet).
  const LaneGraph& graph = map.lane_graph();
  size_t joins = 0;
  for (LaneNode node = 0; node < graph.size(); ++node) {
    for (const bool at_start : {true, false}) {
      for (const LaneEnd& end : graph.ends(node, at_start)) {
        const auto& a = graph.info(node);
        const auto& b = graph.info(end.node);
        const double sa = at_start ? a.s_start : a.s_end;
        const double sb = end.at_start ? b.s_start : b.s_end;
        const auto span_a = map.lane_span_in_section(a.lane.road, a.lane.section, sa, a.lane.lane);
        const auto span_b = map.lane_span_in_section(b.lane.road, b.lane.section, sb, b.lane.lane);
        const WorldPose pa = map.world_pose(a.lane.road, sa, span_a->t_center());
        const WorldPose pb = map.world_pose(b.lane.road, sb, span_b->t_center());
        CHECK(std::hypot(pa.x - pb.x, pa.y - pb.y) < 1e-9);
        ++joins;
      }
    }
  }
  // 12 connecting driving lanes and 4 corner sidewalks, joined at both ends, each join seen
  // from both of its lanes.
  CHECK(joins == 2 * 2 * (12 + 4));
  // From every arm, each other arm is reachable.
  for (uint32_t from = 0; from < 4; ++from) {
    for (uint32_t to = 0; to < 4; ++to) {
      if (from == to) {
        continue;
      }
      const auto route = find_route(map, LanePoint{from, 1, 50.0}, LanePoint{to, -1, 50.0});
      REQUIRE(route);
      CHECK(route->steps.size() == 3);
      CHECK(map.road(route->steps[1].lane.road).in_junction());
    }
  }
  const auto right = find_route(map, LanePoint{0, 1, 50.0}, LanePoint{1, -1, 50.0});
  const auto left = find_route(map, LanePoint{0, 1, 50.0}, LanePoint{3, -1, 50.0});
  const auto straight = find_route(map, LanePoint{0, 1, 50.0}, LanePoint{2, -1, 50.0});
  // 50 m on each arm plus the turn: 24 m straight across, a quarter circle of radius 12 + 1.75
  // for a left turn (the lane runs outside the reference line) and 12 - 1.75 for a right turn.
  CHECK(straight->length == Approx(124.0).margin(1e-6));
  CHECK(left->length == Approx(100.0 + 0.5 * std::numbers::pi * (12.0 + 1.75)).margin(1e-3));
  CHECK(right->length == Approx(100.0 + 0.5 * std::numbers::pi * (12.0 - 1.75)).margin(1e-3));
  // Sidewalks are raised 15 cm.
  CHECK(map.road(0).lane_sections[0].lanes.front().heights.at(0).inner == 0.15);
}
