// World -> lane: s,t -> x,y -> s,t round trips within 1 mm, off-road points, distances.

#include <catch2/catch.hpp>
#include <cmath>

#include "corsa/core/random.h"
#include "corsa/xodr/map.h"
#include "xodr_test_util.h"

using namespace corsa::xodr;

namespace {

struct RoundTrip {
  size_t samples = 0;
  size_t same_road = 0;
  size_t located = 0;
};

/// Random points inside random lanes; each is located again. Where lanes of several roads
/// overlap (junctions) another road may be returned: then its (s, t) must still map back to
/// the same world point.
RoundTrip round_trip(const Map& map, size_t samples, uint64_t seed) {
  corsa::RandomStream random(seed);
  RoundTrip result;
  std::vector<LaneSpan> spans;
  for (size_t i = 0; i < samples; ++i) {
    const auto road = static_cast<uint32_t>(random.uniform_int(0, map.road_count() - 1));
    const double s = random.uniform(0.0, map.road(road).length);
    map.lane_spans(road, s, spans);
    std::erase_if(spans, [](const LaneSpan& x) { return x.width() < 0.2; });
    if (spans.empty()) {
      continue;
    }
    const LaneSpan& span = spans[random.uniform_int(0, spans.size() - 1)];
    const double t = span.t_min() + random.uniform(0.05, 0.95) * span.width();
    const WorldPose pose = map.world_pose(road, s, t);
    ++result.samples;
    const auto found = map.locate(pose.x, pose.y);
    INFO("road " << map.road(road).id << " s " << s << " t " << t);
    REQUIRE(found);
    CHECK(found->distance == 0.0);
    ++result.located;
    if (found->road == road) {
      ++result.same_road;
      CHECK(found->s == Approx(s).margin(1e-3));
      CHECK(found->t == Approx(t).margin(1e-3));
      CHECK(found->lane == span.id);
    }
    const WorldPose back = map.world_pose(found->road, found->s, found->t);
    CHECK(std::hypot(back.x - pose.x, back.y - pose.y) < 1e-3);
  }
  return result;
}

}  // namespace

TEST_CASE("s,t -> x,y -> s,t round trips within 1 mm on every geometry kind", "[xodr][locate]") {
  for (const char* name :
       {"straight_500m.xodr", "Ex_Line-Spiral-Arc.xodr", "velodrome.xodr", "e6mini.xodr",
        "road_geometry_param_poly3_length_match_valid.xodr", "Ex_Simple-LaneOffset.xodr",
        "two_plus_one.xodr", "Ex_Line-Spiral-Arc_elevation_and_superelevation.xodr"}) {
    INFO(name);
    const Map map = test::load_map(test::shared_map(name));
    const RoundTrip result = round_trip(map, 300, 7);
    CHECK(result.samples > 200);
    // Single-road maps: always the same road back.
    CHECK(result.same_road == result.samples);
  }
}

TEST_CASE("s,t -> x,y -> s,t round trips on city maps with junctions", "[xodr][locate]") {
  for (const char* name : {"fabriksgatan.xodr", "Ex_LHT-Complex-X-Junction.xodr",
                           "SampleDatabase.xodr", "Town03.xodr", "Town04.xodr"}) {
    INFO(name);
    const Map map = test::load_map(test::shared_map(name));
    const RoundTrip result = round_trip(map, 400, 11);
    CHECK(result.located == result.samples);
    // Overlaps are confined to junction areas.
    CHECK(result.same_road > result.samples / 2);
  }
}

TEST_CASE("points off the road report their distance or nothing", "[xodr][locate]") {
  const Map map = test::load_map(test::shared_map("straight_500m.xodr"));
  std::vector<LaneSpan> spans;
  map.lane_spans(0, 200.0, spans);
  const double edge = spans.front().t_max();
  const WorldPose outside = map.world_pose(0, 200.0, edge + 2.0);
  const auto near = map.locate(outside.x, outside.y);
  REQUIRE(near);
  CHECK(near->distance == Approx(2.0).margin(1e-6));
  CHECK(near->lane == spans.front().id);
  LocateOptions strict;
  strict.max_distance = 1.0;
  CHECK_FALSE(map.locate(outside.x, outside.y, strict).has_value());
  CHECK_FALSE(map.locate(1e6, 1e6).has_value());
  // Beyond the road's end: the distance runs along the road too.
  const WorldPose end = map.world_pose(0, map.road(0).length, spans.back().t_center());
  const RefPoint ref = map.reference(0, map.road(0).length);
  const auto past = map.locate(end.x + 3.0 * std::cos(ref.hdg), end.y + 3.0 * std::sin(ref.hdg));
  REQUIRE(past);
  CHECK(past->distance == Approx(3.0).margin(1e-6));
  CHECK(past->s == Approx(map.road(0).length));
}

TEST_CASE("drivable_only skips sidewalks and shoulders", "[xodr][locate]") {
  const Map map = test::load_map(test::shared_map("Town04.xodr"));
  std::vector<LaneSpan> spans;
  for (uint32_t road = 0; road < map.road_count(); ++road) {
    map.lane_spans(road, 1.0, spans);
    const LaneSection& section = map.road(road).lane_sections[0];
    for (const LaneSpan& span : spans) {
      const Lane* lane = map.lane(LaneRef{road, 0, span.id});
      if (lane->type != LaneType::kSidewalk || span.width() < 1.0) {
        continue;
      }
      const WorldPose pose = map.world_pose(road, 1.0, span.t_center());
      const auto any = map.locate(pose.x, pose.y);
      REQUIRE(any);
      CHECK(map.lane(any->lane_ref())->type == LaneType::kSidewalk);
      LocateOptions drivable;
      drivable.drivable_only = true;
      drivable.max_distance = 50.0;
      const auto car = map.locate(pose.x, pose.y, drivable);
      REQUIRE(car);
      CHECK(is_drivable(map.lane(car->lane_ref())->type));
      CHECK(car->distance > 0.0);
      (void)section;
      return;  // one sidewalk is enough
    }
  }
  FAIL("Town04 has no sidewalk");
}
