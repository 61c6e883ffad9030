// Readings the standard leaves to the simulator, and esmini's where it differs
// (SimulationOptions::semantics, `corsa run --semantics esmini`; docs/openscenario.md,
// "Differences from esmini"), on focused scenarios whose values are derived by hand.

#include <cmath>

#include "engine_fixture.h"

namespace corsa::test {
namespace {

using Catch::Detail::Approx;

engine::SimulationOptions esmini_reading() {
  engine::SimulationOptions options;
  options.semantics = engine::Semantics::kEsmini;
  return options;
}

}  // namespace

TEST_CASE("A step's travel is the exact integral of the speed, or esmini's speed at its end",
          "[engine][semantics]") {
  // From s = 10 the car speeds up linearly from 0 to 10 m/s in 2 s (a = 5 m/s^2), then holds
  // 10 m/s. Exact: s(2) = 10 + 5 * 2^2 / 2 = 20, s(4) = 20 + 10 * 2 = 40; the trapezoid rule
  // integrates a speed that is linear within each step exactly.
  SECTION("standard") {
    FixtureRun run(engine_fixture("semantics_speed_travel.xosc"));
    run.run();
    CHECK(run.at(1.0, "Car").road->s == Approx(12.5).margin(1e-9));
    CHECK(run.at(2.0, "Car").road->s == Approx(20.0).margin(1e-9));
    CHECK(run.at(4.0, "Car").road->s == Approx(40.0).margin(1e-9));
    CHECK(run.at(2.0, "Car").speed == Approx(10.0).margin(1e-12));
  }
  SECTION("esmini") {
    // Each step moves by the speed at its end: sum over k = 1..n of v(k dt) dt, which exceeds
    // the integral by dt/2 times the speed gained, 0.01 / 2 * 5 = 0.025 m after 1 s and
    // 0.01 / 2 * 10 = 0.05 m from 2 s on. The speeds are the same under both readings.
    FixtureRun run(engine_fixture("semantics_speed_travel.xosc"), esmini_reading());
    run.run();
    CHECK(run.at(1.0, "Car").road->s == Approx(12.525).margin(1e-9));
    CHECK(run.at(2.0, "Car").road->s == Approx(20.05).margin(1e-9));
    CHECK(run.at(4.0, "Car").road->s == Approx(40.05).margin(1e-9));
    CHECK(run.at(2.0, "Car").speed == Approx(10.0).margin(1e-12));
  }
}

TEST_CASE("The step in which a step-shaped SpeedAction starts is driven at the new speed",
          "[engine][semantics]") {
  // The car stands at s = 10 until a story's SpeedAction of shape step sets 10 m/s at once. The
  // step that starts the action moves 10 x dt = 0.1 m (averaging 0 and 10 over it would give
  // 0.05 m), and from then on the car covers 10 m each second.
  FixtureRun run(engine_fixture("semantics_speed_jump.xosc"));
  run.run();
  const double dt = run.sim().dt();
  const auto started = run.first("jump", engine::TransitionKind::kStart);
  REQUIRE(started);
  const double t0 = *started;
  CHECK(run.at(t0, "Car").road->s == Approx(10.0).margin(1e-12));
  CHECK(run.at(t0 + dt, "Car").speed == Approx(10.0).margin(1e-12));
  CHECK(run.at(t0 + dt, "Car").road->s == Approx(10.1).margin(1e-9));
  CHECK(run.at(t0 + 1.0, "Car").road->s == Approx(20.0).margin(1e-9));
}

TEST_CASE("During a lane change the lane is followed at the speed, or esmini's path at it",
          "[engine][semantics]") {
  // At 10 m/s the car changes 3.5 m to the right linearly in 1 s: 0.035 m across in each step of
  // 0.1 m. Standard reading: the lane is followed at 10 m/s, s(4) = 10 + 10 * 4 = 50, and the
  // heading turns by atan(0.035 / 0.1) = 0.3366748 rad toward the new lane.
  SECTION("standard") {
    FixtureRun run(engine_fixture("semantics_lateral_travel.xosc"));
    run.run();
    CHECK(run.at(4.0, "Car").road->s == Approx(50.0).margin(1e-9));
    CHECK(run.at(1.5, "Car").pose.h == Approx(-std::atan(0.35)).margin(1e-9));
    CHECK(run.at(4.0, "Car").road->lane == -2);
  }
  SECTION("esmini") {
    // The path is 0.1 m a step, so the lane gets sqrt(0.1^2 - 0.035^2) = 0.0936750 m of it for
    // the 100 steps of the change: s(4) = 50 - 100 * (0.1 - 0.0936750) = 49.3674970, and the
    // heading turns by asin(0.35) = 0.3575711 rad.
    FixtureRun run(engine_fixture("semantics_lateral_travel.xosc"), esmini_reading());
    run.run();
    CHECK(run.at(4.0, "Car").road->s ==
          Approx(50.0 - 100.0 * (0.1 - std::sqrt(0.008775))).margin(1e-6));
    CHECK(run.at(1.5, "Car").pose.h == Approx(-std::asin(0.35)).margin(1e-9));
    CHECK(run.at(4.0, "Car").road->lane == -2);
  }
}

}  // namespace corsa::test
