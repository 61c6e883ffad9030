// Readings the standard leaves to the simulator, and esmini's where it differs
// (SimulationOptions::semantics, `corsa run --semantics esmini`; docs/openscenario.md,
// "Differences from esmini"), on focused scenarios whose values are derived by hand.

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

}  // namespace corsa::test
