// The world -> lane index built region by region: a query builds the lane sections near it
// only, the section bounds hold every chunk, and the answers are those of an index whose
// sections were all built before the first query.

#include "spatial_index.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <optional>

#include "corsa/core/random.h"
#include "corsa/xodr/map.h"
#include "xodr_test_util.h"

using namespace corsa::xodr;

namespace {

bool same(const std::optional<LanePosition>& a, const std::optional<LanePosition>& b) {
  if (a.has_value() != b.has_value()) {
    return false;
  }
  return !a ||
         (a->road == b->road && a->section == b->section && a->lane == b->lane && a->s == b->s &&
          a->t == b->t && a->distance == b->distance && a->heading == b->heading);
}

}  // namespace

TEST_CASE("a world -> lane query builds only the lane sections around it", "[xodr][locate]") {
  for (const char* name : {"Town04.xodr", "Town03.xodr"}) {
    INFO(name);
    const Map map = test::load_map(test::shared_map(name));
    detail::SpatialIndex index;
    index.prepare(map);
    CHECK(index.built_sections() == 0);
    const WorldPose on_road = map.world_pose(0, 0.5 * map.road(0).length, 0.0);
    index.locate(map, on_road.x, on_road.y, LocateOptions{});
    CHECK(index.built_sections() > 0);
    CHECK(index.built_sections() * 10 < index.section_count());
  }
}

TEST_CASE("section bounds hold every chunk of every shared map", "[xodr][locate]") {
  for (const auto& path : test::all_shared_maps()) {
    INFO(path.filename().string());
    const Map map = test::load_map(path);
    detail::SpatialIndex index;
    index.prepare(map);
    index.build_all(map);
    CHECK(index.built_sections() == index.section_count());
    CHECK(index.chunks_outside_bounds() == 0);
  }
}

TEST_CASE("the lazily built index answers as one built all at once", "[xodr][locate]") {
  for (const char* name : {"Town04.xodr", "SampleDatabase.xodr", "fabriksgatan.xodr", "e6mini.xodr",
                           "Ex_Line-Spiral-Arc.xodr"}) {
    INFO(name);
    const Map map = test::load_map(test::shared_map(name));
    detail::SpatialIndex lazy, eager;
    lazy.prepare(map);
    eager.prepare(map);
    eager.build_all(map);
    // Points around random reference points, on and off the lanes, at two search distances.
    corsa::RandomStream random(17);
    for (int i = 0; i < 1500; ++i) {
      const auto road = static_cast<uint32_t>(random.uniform_int(0, map.road_count() - 1));
      const RefPoint ref = map.reference(road, random.uniform(0.0, map.road(road).length));
      const double x = ref.x + random.uniform(-40.0, 40.0);
      const double y = ref.y + random.uniform(-40.0, 40.0);
      LocateOptions options;
      options.max_distance = i % 2 == 0 ? 5.0 : 25.0;
      options.drivable_only = i % 5 == 0;
      const auto a = lazy.locate(map, x, y, options);
      const auto b = eager.locate(map, x, y, options);
      INFO("point " << x << ", " << y);
      CHECK(same(a, b));
    }
    CHECK(lazy.built_sections() <= eager.built_sections());
  }
}

TEST_CASE("no locate answers within an off-road point's clearance of every lane",
          "[xodr][locate]") {
  for (const char* name : {"Town04.xodr", "SampleDatabase.xodr", "fabriksgatan.xodr", "e6mini.xodr",
                           "soderleden.xodr"}) {
    INFO(name);
    const Map map = test::load_map(test::shared_map(name));
    corsa::RandomStream random(23);
    int cleared = 0;
    for (int i = 0; i < 600; ++i) {
      const auto road = static_cast<uint32_t>(random.uniform_int(0, map.road_count() - 1));
      const RefPoint ref = map.reference(road, random.uniform(0.0, map.road(road).length));
      const double x = ref.x + random.uniform(-30.0, 30.0);
      const double y = ref.y + random.uniform(-30.0, 30.0);
      const double clear = map.clear_of_lanes(x, y, 0.5, 2.0);
      INFO("point " << x << ", " << y << " clear " << clear);
      REQUIRE(clear >= 0.0);
      REQUIRE(clear <= 2.0);
      LocateOptions options;
      options.max_distance = 0.5;
      if (map.locate(x, y, options)) {
        CHECK(clear == 0.0);
      }
      if (clear == 0.0) {
        continue;
      }
      ++cleared;
      // The square's corners and edges' middles, and random points inside it, at the full and
      // at a smaller search distance.
      for (int k = 0; k < 16; ++k) {
        const double dx = k < 8 ? clear * ((k % 3) - 1.0) : random.uniform(-clear, clear);
        const double dy = k < 8 ? clear * (((k / 3) % 3) - 1.0) : random.uniform(-clear, clear);
        options.max_distance = k % 2 == 0 ? 0.5 : 0.1;
        CHECK_FALSE(map.locate(x + dx, y + dy, options).has_value());
      }
    }
    // Most points 30 m about a reference line are off the road: the bound is not trivially 0.
    CHECK(cleared > 100);
  }
}
