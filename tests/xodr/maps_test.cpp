// Every real map we have loads; its reference lines are continuous wherever the file is.

#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <numbers>

#include "corsa/xodr/lane_graph.h"
#include "corsa/xodr/map.h"
#include "xodr_test_util.h"

using namespace corsa::xodr;

TEST_CASE("every shared OpenDRIVE map loads", "[xodr][maps]") {
  // Road counts from ../shared/data/xodr/README.md.
  const std::map<std::string, size_t> roads = {
      {"straight_500m.xodr", 1}, {"Ex_Line-Spiral-Arc.xodr", 1},
      {"velodrome.xodr", 1},     {"Ex_Lane-Width.xodr", 1},
      {"two_plus_one.xodr", 1},  {"e6mini.xodr", 1},
      {"soderleden.xodr", 5},    {"Ex_Entry_Exit.xodr", 6},
      {"Ex_Slip_Lane.xodr", 24}, {"Ex_LHT-Complex-X-Junction.xodr", 16},
      {"borregasave.xodr", 39},  {"Town03.xodr", 279},
      {"Town04.xodr", 276},      {"lane_gap_example_issue_119.xodr", 6},
  };
  const auto maps = test::all_shared_maps();
  REQUIRE(maps.size() == 25);
  for (const auto& path : maps) {
    INFO(path.filename().string());
    corsa::Diagnostics diagnostics;
    const Map map = Map::load(path, diagnostics);
    CHECK(diagnostics.count(corsa::Severity::kError) == 0);
    CHECK(map.road_count() > 0);
    CHECK(map.lane_graph().size() > 0);
    const auto expected = roads.find(path.filename().string());
    if (expected != roads.end() && path.parent_path().filename() == "xodr") {
      CHECK(map.road_count() == expected->second);
    }
  }
}

TEST_CASE("map contents match the README's inventory", "[xodr][maps]") {
  const Map town04 = test::load_map(test::shared_map("Town04.xodr"));
  size_t lines = 0;
  size_t arcs = 0;
  size_t in_junction = 0;
  for (const Road& road : town04.data().roads) {
    in_junction += road.in_junction() ? 1 : 0;
    for (const Geometry& g : road.plan_view) {
      lines += std::holds_alternative<LineGeometry>(g.shape) ? 1 : 0;
      arcs += std::holds_alternative<ArcGeometry>(g.shape) ? 1 : 0;
    }
  }
  CHECK(lines == 900);
  CHECK(arcs == 380);
  CHECK(in_junction == 223);
  CHECK(town04.junction_count() == 27);
  CHECK(town04.data().header.geo_reference.find("+proj=tmerc") == 0);

  const Map slip = test::load_map(test::shared_map("Ex_Slip_Lane.xodr"));
  size_t direct = 0;
  for (const Junction& j : slip.data().junctions) {
    direct += j.type == JunctionType::kDirect ? 1 : 0;
  }
  CHECK(slip.junction_count() == 7);
  CHECK(direct == 6);

  const Map lht = test::load_map(test::shared_map("Ex_LHT-Complex-X-Junction.xodr"));
  CHECK(lht.road(0).rule == TrafficRule::kLeftHand);

  // Lane <height> records (raised sidewalks) are kept.
  const Map fabriksgatan = test::load_map(test::shared_map("fabriksgatan.xodr"));
  size_t heights = 0;
  for (const Road& road : fabriksgatan.data().roads) {
    for (const LaneSection& section : road.lane_sections) {
      for (const Lane& lane : section.lanes) {
        heights += lane.heights.size();
      }
    }
  }
  CHECK(heights == 32);

  const Map gap = test::load_map(test::shared_map("lane_gap_example_issue_119.xodr"));
  CHECK(gap.data().header.offset_x != 0.0);
  CHECK(gap.data().header.geo_reference.find("+proj=utm") != std::string::npos);
}

TEST_CASE("geometry joints are continuous or the file's discontinuity is warned about",
          "[xodr][maps][continuity]") {
  size_t joints = 0;
  size_t warned = 0;
  for (const auto& path : test::all_shared_maps()) {
    corsa::Diagnostics diagnostics;
    const Map map = Map::load(path, diagnostics);
    std::string warnings;
    for (const auto& d : diagnostics.all()) {
      warnings += d.message + "\n";
    }
    for (const Road& road : map.data().roads) {
      for (size_t i = 0; i + 1 < road.plan_view.size(); ++i) {
        const Geometry& g = road.plan_view[i];
        const Geometry& next = road.plan_view[i + 1];
        const RefPoint end = evaluate_geometry(g, g.length);
        const double gap = std::hypot(end.x - next.x, end.y - next.y);
        const double jump = std::abs(std::remainder(end.hdg - next.hdg, 2.0 * std::numbers::pi));
        ++joints;
        if (gap >= 0.01 || jump >= 0.01) {
          ++warned;
          // Only the real-world borregasave conversion has kinks (heading jumps up to 0.45 rad).
          CHECK(path.filename() == "borregasave.xodr");
          INFO(path.filename().string()
               << " road " << road.id << " gap " << gap << " jump " << jump);
          CHECK(warnings.find("road '" + road.id + "': planView records do not join") !=
                std::string::npos);
        }
      }
    }
  }
  CHECK(joints > 2000);
  CHECK(warned > 0);
}
