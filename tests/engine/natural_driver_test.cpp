// esmini's NaturalDriver controller (controllers/natural_driver.h) on the repository's motorway
// (scenarios/maps/motorway_2km.xodr: road 1 along +x, driving lanes -1, -2, -3 of 3.75 m).
//
// controller_natural_driver_free.xosc: alone on the road, Ego's speed is the Intelligent Driver
// Model's free-road law integrated as esmini integrates it, v += maxAcc (1 - (v / v0)^4) dt per
// step from the speed it had when activated, capped at v0; no lane change pays (the gain is 0)
// and its route is its own lane.
//
// controller_natural_driver.xosc (highway_driver-like): Ego at 25 m/s closes on Slow (8.33 m/s,
// 60 m ahead in its lane). Keeping its lane, the IDM would brake it hard (its desired gap of
// 80 m is more than the 55 m free); in lane -1 or -3 nothing is ahead, so the change pays
// (MOBIL, politeness 0): it changes left (esmini tries the left lane first), passes Slow at its
// desired speed, and goes back to lane -2, its route, once Slow behind it would not have to
// brake harder than maxImposedBraking (8 m/s^2).
//
// controller_natural_driver_two.xosc: two NaturalDrivers want the lane between them at once; the
// one deciding second (entity order) calls its change off while the first changes just ahead.

#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "engine_fixture.h"

using corsa::engine::Semantics;
using corsa::test::engine_fixture;
using corsa::test::FixtureRun;

namespace {

corsa::engine::SimulationOptions natural_reading(Semantics semantics, double dt) {
  corsa::engine::SimulationOptions options;
  options.semantics = semantics;
  options.dt = dt;
  return options;
}

int lane_of(const corsa::engine::EntityState& state) {
  REQUIRE(state.road);
  return state.road->lane;
}

}  // namespace

TEST_CASE("esmini's NaturalDriver speeds up on a free road as the IDM's free-road term gives",
          "[engine][controllers][natural]") {
  const double dt = 0.05;
  FixtureRun run(engine_fixture("controller_natural_driver_free.xosc"),
                 natural_reading(Semantics::kStandard, dt));
  run.run();
  CHECK(run.sim().time() == Approx(10.05));
  // No warning that another controller stands in for it.
  CHECK_THAT(corsa::test::all_text(run.diagnostics()),
             !Catch::Contains("stands in") && !Catch::Contains("is not one of this engine's"));
  double v = 10.0;
  for (int tick = 1; tick <= 200; ++tick) {
    v = std::min(20.0, v + 2.0 * (1.0 - std::pow(v / 20.0, 4)) * dt);
    const auto& ego = run.trace().at(tick, run.entity("Ego"));
    REQUIRE(ego.speed == Approx(v).epsilon(1e-12));
    REQUIRE(lane_of(ego) == -2);
  }
  CHECK(v > 19.0);
  CHECK(v < 20.0);
}

TEST_CASE("esmini's NaturalDriver overtakes a slower car and goes back to its route's lane",
          "[engine][controllers][natural]") {
  for (const Semantics semantics : {Semantics::kStandard, Semantics::kEsmini}) {
    for (const double dt : {0.1, 0.01}) {
      CAPTURE(semantics == Semantics::kEsmini, dt);
      FixtureRun run(engine_fixture("controller_natural_driver.xosc"),
                     natural_reading(semantics, dt));
      run.run();
      const size_t ego = run.entity("Ego");
      const size_t slow = run.entity("Slow");
      // Asked for at time 0 (esmini's initialising frame), the lane change moves Ego from the
      // second step on (esmini starts the action a frame later and steps it from the frame
      // after) and takes laneChangeDuration, 2 s: on lane -1's centre at 2 s + dt.
      CHECK(run.at(dt, "Ego").pose.y == Approx(-5.625));
      CHECK(run.at(2 * dt, "Ego").pose.y > -5.625 + 1e-6);
      CHECK(run.at(2.0, "Ego").pose.y < -1.875 - 1e-6);
      CHECK(run.at(2.0 + dt, "Ego").pose.y == Approx(-1.875));
      CHECK(lane_of(run.at(2.5, "Ego")) == -1);
      CHECK(run.at(2.5, "Ego").pose.y == Approx(-1.875));
      // It passes Slow without slowing down: nothing is ahead of it in lane -1.
      CHECK(run.at(2.5, "Ego").speed == Approx(25.0));
      bool back = false;
      double least_gap = 1e9;
      for (const auto& [tick, states] : run.trace().ticks()) {
        const auto& e = states.at(ego);
        const auto& s = states.at(slow);
        // Boxes 5 m long, centred 1.4 m ahead of the reference point: Ego's rear 1.1 m behind
        // its reference point, Slow's front 3.9 m ahead of its own.
        if (e.road && e.road->lane == -2 && s.pose.x > e.pose.x) {
          least_gap = std::min(least_gap, s.pose.x - 1.1 - (e.pose.x + 3.9));
        }
        if (e.road && e.road->lane == -2 && e.pose.x > s.pose.x && !back) {
          back = true;
          // Back in front of Slow only with room: Slow would brake at most 8 m/s^2 behind it,
          // 6 (5 / gap)^2 <= 8, a gap of at least 4.33 m (the change began before this).
          CHECK(e.pose.x - 1.1 - (s.pose.x + 3.9) > 4.3);
        }
      }
      CHECK(back);
      // Never closer in its lane than when its reference point crossed into lane -1, half way
      // through the change (1 s, 16.7 m closer than the 55 m at the start).
      CHECK(least_gap > 38.0);
      CHECK(lane_of(run.now("Ego")) == -2);
      CHECK(run.now("Ego").pose.y == Approx(-5.625));
      CHECK(run.now("Ego").pose.x > run.now("Slow").pose.x + 200.0);
      CHECK(run.now("Ego").speed == Approx(25.0));
    }
  }
}

TEST_CASE("esmini's NaturalDriver calls off a change to the lane another one is changing to ahead",
          "[engine][controllers][natural]") {
  const double dt = 0.1;
  FixtureRun run(engine_fixture("controller_natural_driver_two.xosc"),
                 natural_reading(Semantics::kStandard, dt));
  run.run();
  // A changes from the second step on; B, which decided after A in the same frame, stays.
  CHECK(run.at(dt, "A").pose.y == Approx(-1.875));
  CHECK(run.at(2 * dt, "A").pose.y < -1.875 - 1e-6);
  CHECK(lane_of(run.at(2.5, "A")) == -2);
  for (double t = 0.0; t <= 2.0 + 1e-9; t += dt) {
    CAPTURE(t);
    REQUIRE(run.at(t, "B").pose.y == Approx(-9.375));
  }
  // Kept behind its slow car meanwhile, B brakes (the IDM's gap term) ...
  CHECK(run.at(1.0, "B").speed < 24.0);
  // ... and once A no longer asks for lane -2, B follows it there, behind it.
  CHECK(lane_of(run.now("B")) == -2);
  CHECK(run.now("B").pose.y == Approx(-5.625));
  CHECK(run.now("A").pose.x - 1.1 - (run.now("B").pose.x + 3.9) > 20.0);
}

TEST_CASE("esmini's NaturalDriver refuses property values out of their range, each at its line",
          "[engine][controllers][natural]") {
  const double dt = 0.05;
  FixtureRun run(engine_fixture("controller_natural_driver_bad_values.xosc"),
                 natural_reading(Semantics::kStandard, dt));
  run.run();
  const std::string text = corsa::test::all_text(run.diagnostics());
  CHECK_THAT(text, Catch::Contains(":24: warning: NaturalDriver property 'desiredSpeed' must be "
                                   "above 0: esmini's default is used"));
  CHECK_THAT(text,
             Catch::Contains(":25: warning: NaturalDriver property 'maxAcc' must be above 0"));
  CHECK_THAT(text,
             Catch::Contains(":26: warning: NaturalDriver property 'maxDec' must be below 0"));
  CHECK_THAT(text,
             Catch::Contains(":27: warning: NaturalDriver property 'thw' must be at least 0"));
  CHECK_THAT(text, Catch::Contains(":28: warning: NaturalDriver property 'laneChangeDuration' "
                                   "must be at least 0 and within a float's range"));
  CHECK_THAT(text, Catch::Contains(":29: warning: NaturalDriver property 'laneChangeDelay' must "
                                   "be at least 0"));
  CHECK_THAT(text, Catch::Contains(":30: warning: NaturalDriver property 'route' must be within "
                                   "an int's range"));
  // esmini's defaults: desiredSpeed 15 m/s, and route -1, so Ego changes to lane -1 first
  // (holding its speed) and then speeds up toward 15 m/s.
  double last = 10.0;
  for (int tick = 1; tick <= 200; ++tick) {
    const auto& ego = run.trace().at(tick, run.entity("Ego"));
    REQUIRE(std::isfinite(ego.pose.x));
    REQUIRE(std::isfinite(ego.pose.y));
    REQUIRE(ego.speed >= last);
    REQUIRE(ego.speed < 15.0);
    last = ego.speed;
  }
  CHECK(last > 14.9);
  CHECK(lane_of(run.now("Ego")) == -1);
}
