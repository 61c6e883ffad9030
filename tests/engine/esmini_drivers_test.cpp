// esmini's simple vehicle model and the two esmini controllers that drive it
// (controllers/esmini_vehicle.h), on tests/engine/fixtures/controller_esmini_drivers.xosc:
// Coaster (interactiveDriver, no key pressed) starts at 20 m/s at a heading 0.05 rad off the
// straight road's, is asked at 2 s to slow to 5 m/s and is teleported at 20 s; Follower
// (offroadFollower) starts 40 m behind the standing Lead, with 20 m as its target distance.
//
// What to expect, derived from esmini's model: without throttle the speed shrinks by the factor
// 0.999 every step (0.01 s), so over 2 s by 0.999^200, and the car holds its heading (the wheel
// stays straight): its path is the straight line from its start at 0.05 rad, and the slow-down
// does not reach it while the controller is active (esmini's override mode). Off the road
// (y > 10.5 m) its top speed is esmini's 70 km/h. The follower's throttle 0.5 (d - 20) - 0.5 v
// with maxAcceleration 5 m/s^2 (full throttle at first) gives e'' + 2.5 e' + 2.5 e = 0 for
// e = d - 20 once within +-1: damped (roots -1.25 +- 0.97 i), so it comes to rest near 20 m; as
// its speed passes zero the model's brake holds it (it never reverses), a little short of or
// beyond 20 m (the overshoot of that damping, 1.7% of the last metres).

#include <bit>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "../xodr/xodr_test_util.h"
#include "controllers/esmini_vehicle.h"
#include "engine_fixture.h"

using corsa::engine::detail::drive_analog;
using corsa::engine::detail::EsminiVehicle;
using corsa::engine::detail::roll_neutral;
using corsa::test::engine_fixture;
using corsa::test::FixtureRun;

TEST_CASE("esmini's interactiveDriver without input rolls straight on, its speed shrinking",
          "[engine][controllers][esmini]") {
  FixtureRun run(engine_fixture("controller_esmini_drivers.xosc"));
  run.run();
  CHECK(run.sim().controller_substitute(run.entity("Coaster")).empty());
  const auto& start = run.at(0.0, "Coaster");
  REQUIRE(start.speed == Approx(20.0));
  // Engine brake only: 0.999 a step; the SpeedAction at 2 s does not slow it.
  const double v1 = run.at(1.0, "Coaster").speed;
  CHECK(run.at(3.0, "Coaster").speed == Approx(v1 * std::pow(0.999, 200)).epsilon(1e-9));
  CHECK(v1 > 18.0);
  // Straight along its heading, not along the road.
  for (const double t : {1.0, 4.0, 10.0, 20.0}) {
    const auto& now = run.at(t, "Coaster");
    CAPTURE(t);
    CHECK(now.pose.h == Approx(0.05).margin(1e-9));
    CHECK(now.pose.y - start.pose.y ==
          Approx((now.pose.x - start.pose.x) * std::tan(0.05)).margin(1e-6));
  }
  // Off the road (beyond y 10.5 m from about 5 s) its top speed is 70 km/h.
  CHECK(run.at(20.0, "Coaster").pose.y > 10.5);
  CHECK(run.at(20.0, "Coaster").speed <= 70.0 / 3.6 + 1e-9);
  // Teleported at 20 s, it rolls on from there (the model starts again from the entity).
  const auto& end = run.at(30.0, "Coaster");
  CHECK(end.pose.x > 600.0);
  CHECK(end.pose.y - 30.0 == Approx((end.pose.x - 600.0) * std::tan(0.05)).margin(1e-6));
}

TEST_CASE("esmini's offroadFollower closes to its target distance behind the entity it follows",
          "[engine][controllers][esmini]") {
  FixtureRun run(engine_fixture("controller_esmini_drivers.xosc"));
  run.run();
  CHECK(run.sim().controller_substitute(run.entity("Follower")).empty());
  const auto& lead = run.now("Lead");
  double slowest = 0.0, fastest = 0.0;
  for (int tick = 0; tick <= 3000; ++tick) {
    const auto& follower = run.at(tick * 0.01, "Follower");
    slowest = std::min(slowest, follower.speed);
    fastest = std::max(fastest, follower.speed);
    CHECK(follower.pose.y == Approx(lead.pose.y).margin(1e-9));  // straight at it
  }
  CHECK(run.at(0.0, "Follower").pose.x == Approx(60.0));
  CHECK(slowest == 0.0);
  CHECK(fastest > 3.0);
  // Settled at the target distance for the last 10 s.
  CHECK(lead.pose.x - run.at(20.0, "Follower").pose.x == Approx(20.0).margin(0.001));
  CHECK(lead.pose.x - run.now("Follower").pose.x == Approx(20.0).margin(1e-6));
  CHECK(run.now("Follower").speed == Approx(0.0).margin(1e-6));
}

TEST_CASE("esmini's vehicle model: the wheel returns, rolling back through zero holds the car",
          "[engine][controllers][esmini]") {
  EsminiVehicle car;
  car.wheel = 0.2;
  car.speed = 10.0;
  roll_neutral(car, 0.01);
  CHECK(car.wheel == Approx(0.2 * (1.0 - 4.0 * 0.01)));
  CHECK(car.speed == Approx(10.0 * 0.999));
  CHECK(car.h > 0.0);  // the wheel turned it left
  // Braking through zero stops the car and holds it until the brake is let go.
  EsminiVehicle slow;
  slow.speed = 0.05;
  slow.max_deceleration = 10.0;
  drive_analog(slow, 0.01, -1.0, 0.0);
  CHECK(slow.speed == 0.0);
  CHECK(slow.handbrake);
  drive_analog(slow, 0.01, -1.0, 0.0);
  CHECK(slow.speed == 0.0);
  drive_analog(slow, 0.01, 0.0, 0.0);
  CHECK_FALSE(slow.handbrake);
  // Full throttle adds maxAcceleration x dt, within the top speed.
  EsminiVehicle fast;
  fast.max_acceleration = 4.0;
  fast.max_speed = 10.0;
  fast.speed = 9.99;
  drive_analog(fast, 0.01, 1.0, 0.0);
  CHECK(fast.speed == Approx(10.0));
  fast.speed = 5.0;
  drive_analog(fast, 0.01, 1.0, 0.0);
  CHECK(fast.speed == Approx(5.04));
}

// The single-track step keeps its course's cosine and sine for the next step along the same
// course (CourseTrig). Two cars step through the same inputs, one with the kept values and one
// computing them every step; their places and headings must have the same bits after every step:
// straight runs (the kept values used), a wheel turned and returned to exactly 0 (a new course
// each step, then a new straight one), a heading set from outside (a teleport), a course of -0
// after +0 (the sine's sign differs) and a speed that shrinks toward 0.
TEST_CASE("esmini's single-track step with its course's cosine and sine kept moves as without",
          "[engine][controllers][esmini]") {
  using corsa::engine::detail::CourseTrig;
  using corsa::engine::detail::single_track_step;
  struct Car {
    double x = 3.0, y = -2.0, h = 0.3;
  };
  Car kept, fresh;
  CourseTrig trig;
  int reused = 0;
  int steps = 0;
  const auto step = [&](double speed, double wheel) {
    const bool may_reuse = trig.valid;
    const uint64_t before = trig.course_bits;
    single_track_step(kept.x, kept.y, kept.h, speed, wheel, 4.5, 0.01, &trig);
    single_track_step(fresh.x, fresh.y, fresh.h, speed, wheel, 4.5, 0.01);
    reused += may_reuse && trig.course_bits == before ? 1 : 0;
    ++steps;
    CAPTURE(steps, speed, wheel);
    REQUIRE(std::bit_cast<uint64_t>(kept.x) == std::bit_cast<uint64_t>(fresh.x));
    REQUIRE(std::bit_cast<uint64_t>(kept.y) == std::bit_cast<uint64_t>(fresh.y));
    REQUIRE(std::bit_cast<uint64_t>(kept.h) == std::bit_cast<uint64_t>(fresh.h));
  };
  for (int k = 0; k < 20; ++k) step(12.0, 0.0);  // straight: the same course every step
  for (int k = 0; k < 20; ++k) step(12.0, 0.1 * (20 - k) / 20.0);  // turning
  for (int k = 0; k < 20; ++k) step(8.0, 0.0);  // straight again, on the new heading
  kept.h = fresh.h = 2.0;                       // a teleport's heading
  for (int k = 0; k < 5; ++k) step(8.0, 0.0);
  kept.h = fresh.h = 0.0;
  step(8.0, 0.0);
  kept.h = fresh.h = -0.0;  // the same course but for its sign: the sine's sign differs
  step(8.0, -0.0);
  double speed = 1.0;
  for (int k = 0; k < 50; ++k) {
    speed *= 0.999;
    step(speed, 0.0);
  }
  CHECK(reused > 80);  // the kept values were used on the straight runs
}

// esmini's speed limit, kept by its driver over the stretch of road where it is the same
// (SpeedLimitMemo): a road whose types give no speed, 50 km/h from 100 m and no speed again from
// 200 m, with two driving lanes a side up to 150 m and one beyond; and a road of one lane a side
// without types. Walked along both roads, off the road and back, the kept limit must be the one
// read afresh (speed_limit_of) everywhere, and it must be read again exactly where the stretch
// ends: at a type's start, a lane section's, on another road and on the other side.
TEST_CASE("esmini's speed limit is kept over a stretch of road and read again beyond it",
          "[engine][controllers][esmini][memo]") {
  using corsa::engine::RoadCoordinates;
  using corsa::engine::detail::speed_limit_at;
  using corsa::engine::detail::speed_limit_of;
  using corsa::engine::detail::SpeedLimitMemo;
  corsa::xodr::MapData data;
  data.roads.push_back(corsa::xodr::test::make_road("1", corsa::xodr::LineGeometry{}, 300.0, 2));
  data.roads.push_back(corsa::xodr::test::make_road("2", corsa::xodr::LineGeometry{}, 100.0, 1));
  corsa::xodr::Road& road = data.roads[0];
  corsa::xodr::LaneSection narrow = road.lane_sections[0];
  std::erase_if(narrow.lanes, [](const corsa::xodr::Lane& lane) { return std::abs(lane.id) > 1; });
  narrow.s = 150.0;
  road.lane_sections.push_back(narrow);
  road.types = {{0.0, "town", "", std::nullopt},
                {100.0, "town", "", 50.0 / 3.6},
                {200.0, "rural", "", std::nullopt}};
  corsa::Diagnostics diagnostics;
  const corsa::xodr::Map map = corsa::xodr::Map::build(std::move(data), diagnostics);
  REQUIRE(map.road_count() == 2);
  REQUIRE(map.road(0).lane_sections.size() == 2);

  SpeedLimitMemo memo;
  int reads = 0;
  const auto limit_at = [&](const std::optional<RoadCoordinates>& at) {
    const SpeedLimitMemo before = memo;
    const double limit = speed_limit_at(&map, at, memo);
    const bool read =
        std::bit_cast<uint64_t>(before.s_from) != std::bit_cast<uint64_t>(memo.s_from) ||
        std::bit_cast<uint64_t>(before.s_to) != std::bit_cast<uint64_t>(memo.s_to) ||
        before.valid != memo.valid || before.road != memo.road || before.section != memo.section ||
        before.side != memo.side;
    reads += read ? 1 : 0;
    if (at) {
      CAPTURE(at->road, at->section, at->lane, at->s);
      CHECK(std::bit_cast<uint64_t>(limit) ==
            std::bit_cast<uint64_t>(speed_limit_of(map, *at).limit));
    }
    return limit;
  };
  const auto on = [](uint32_t road_index, int lane, double s) {
    const uint32_t section = road_index == 0 && s >= 150.0 ? 1 : 0;
    return std::optional<RoadCoordinates>(RoadCoordinates{road_index, section, lane, s, 0.0});
  };
  // Along the first road on the right: 120 km/h (two lanes), 50 from 100 m, and from 200 m the
  // one lane's 60. Four stretches: [0, 100), [100, 150), [150, 200) in the next section, [200,
  // 300).
  for (double s = 0.0; s < 300.0; s += 0.5) {
    const double expected = s < 100.0 ? 120.0 : s < 200.0 ? 50.0 : 60.0;
    CHECK(limit_at(on(0, -1, s)) == Approx(expected / 3.6));
  }
  CHECK(reads == 4);
  CHECK(memo.road == 0);
  CHECK(memo.section == 1);
  CHECK(memo.s_from == 200.0);
  // Onto the other road: read again there.
  CHECK(limit_at(on(1, -1, 20.0)) == Approx(60.0 / 3.6));
  CHECK(reads == 5);
  CHECK(memo.road == 1);
  CHECK(limit_at(on(1, -1, 80.0)) == Approx(60.0 / 3.6));
  CHECK(reads == 5);
  // Off the road: esmini's 70 km/h, the memo kept; back on the first road, on its left side.
  CHECK(limit_at(std::nullopt) == Approx(70.0 / 3.6));
  CHECK(speed_limit_at(nullptr, on(1, -1, 20.0), memo) == Approx(70.0 / 3.6));
  CHECK(reads == 5);
  CHECK(limit_at(on(0, 1, 50.0)) == Approx(120.0 / 3.6));
  CHECK(memo.side == 1);
  CHECK(limit_at(on(0, -1, 50.0)) == Approx(120.0 / 3.6));
  CHECK(memo.side == -1);
  CHECK(reads == 7);
  // Backwards over the first road's type starts: read again at each, from the stretch's end.
  CHECK(limit_at(on(0, -1, 99.5)) == Approx(120.0 / 3.6));
  CHECK(limit_at(on(0, -1, 100.0)) == Approx(50.0 / 3.6));
  CHECK(limit_at(on(0, -1, 99.75)) == Approx(120.0 / 3.6));
  CHECK(reads == 9);
  // A NaN s lies in no stretch: read afresh (every type counts, none with a speed; two lanes).
  CHECK(limit_at(on(0, -1, std::nan(""))) == Approx(120.0 / 3.6));
  CHECK(reads == 10);
  CHECK(memo.s_from == 200.0);
}
