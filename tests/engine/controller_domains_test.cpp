// Two controllers on one entity's motion domains (controllers.h, settle_domains; docs/engine.md,
// "Controllers per motion domain"), on tests/engine/fixtures/controller_domains.xosc: esmini's
// multi_controller setting (Ego at 15 m/s; sloppyDriver lateral from 1 s to 10 s; interactiveDriver
// assigned at 5 s and active in the longitudinal domain alone until 15 s), at esmini's smoke-test
// step 0.1 s and seed 397860069.
//
// What to expect: until 5.1 s the sloppy driver alone, exactly as without the interactive driver
// (controller_sloppy_driver.xosc); from 5.1 s to 10.1 s the speed is the interactive driver's (no
// key pressed: the engine brake takes 0.1% of it every step) while the sloppy driver goes on
// shifting the entity across its lane; from 10.1 s the offset it made stays. esmini's own rows
// (its smoke test, relative to Ego's start at x 20 m, 3 decimals): 5.2 s x +77.998, y -3.866,
// 14.985 m/s; 10.1 s x +149.618, y -2.853, 14.268 m/s; 15.0 s x +217.812, y -2.853, 13.585 m/s.

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "engine_fixture.h"

using corsa::test::all_text;
using corsa::test::engine_fixture;
using corsa::test::FixtureRun;

namespace {

corsa::engine::SimulationOptions domains_options() {
  corsa::engine::SimulationOptions options;
  options.dt = 0.1;
  options.seed = 397860069;  // esmini's smoke test, test_multi_controller
  return options;
}

double domains_heading_gap(double a, double b) {
  return std::remainder(a - b, 2.0 * std::numbers::pi);
}

}  // namespace

TEST_CASE("a sloppyDriver on the lateral domain and an interactiveDriver on the longitudinal one",
          "[engine][controllers][domains]") {
  FixtureRun run(engine_fixture("controller_domains.xosc"), domains_options());
  run.run();
  FixtureRun alone(engine_fixture("controller_sloppy_driver.xosc"), domains_options());
  alone.run();
  const double x0 = run.at(0.0, "Ego").pose.x;
  const double y0 = run.at(0.0, "Ego").pose.y;
  // The activation by name is of an assigned controller: no warning.
  CHECK(all_text(run.diagnostics()).find("has controller") == std::string::npos);
  // Before the interactive driver: the sloppy driver's motion, bit for bit.
  for (const double t : {1.0, 2.6, 3.2, 4.0, 5.1}) {
    CAPTURE(t);
    CHECK(run.at(t, "Ego").pose.x == alone.at(t, "Ego").pose.x);
    CHECK(run.at(t, "Ego").pose.y == alone.at(t, "Ego").pose.y);
    CHECK(run.at(t, "Ego").speed == 15.0);
  }
  // Both at once: the interactive driver's engine brake on the speed, step by step...
  for (int tick = 52; tick <= 101; ++tick) {
    CAPTURE(tick);
    const double before = run.at(0.1 * (tick - 1), "Ego").speed;
    CHECK(run.at(0.1 * tick, "Ego").speed == Approx(before * (1.0 - 0.001)).epsilon(1e-12));
  }
  // ...and the sloppy driver still steering across the lane.
  CHECK(run.at(7.0, "Ego").pose.y != run.at(6.0, "Ego").pose.y);
  CHECK(run.at(7.0, "Ego").pose.y != alone.at(7.0, "Ego").pose.y);
  // esmini's rows.
  CHECK(run.at(5.2, "Ego").pose.x - x0 == Approx(77.998).margin(0.0015));
  CHECK(run.at(5.2, "Ego").pose.y - y0 == Approx(-3.866).margin(0.0015));
  CHECK(run.at(5.2, "Ego").speed == Approx(14.985).margin(0.0005));
  CHECK(run.at(10.1, "Ego").pose.x - x0 == Approx(149.618).margin(0.0015));
  CHECK(run.at(10.1, "Ego").pose.y - y0 == Approx(-2.853).margin(0.0015));
  CHECK(run.at(10.1, "Ego").speed == Approx(14.268).margin(0.0005));
  CHECK(domains_heading_gap(run.at(10.1, "Ego").pose.h, 0.148) == Approx(0.0).margin(0.0015));
  // The sloppy driver off at 10.1 s: its offset stays, the road's heading, the interactive
  // driver's speed on.
  for (const double t : {10.3, 12.0, 15.0}) {
    CAPTURE(t);
    CHECK(run.at(t, "Ego").pose.y == Approx(run.at(10.2, "Ego").pose.y).margin(1e-9));
    CHECK(domains_heading_gap(run.at(t, "Ego").pose.h, 0.0) == Approx(0.0).margin(1e-12));
  }
  CHECK(run.at(15.0, "Ego").pose.x - x0 == Approx(217.812).margin(0.0015));
  CHECK(run.at(15.0, "Ego").speed == Approx(13.585).margin(0.0005));
}

TEST_CASE("the default controller keeps the speed the entity has when its controller goes off",
          "[engine][controllers][domains]") {
  // The interactive driver (longitudinal) is switched off at 15.1 s: the default controller
  // keeps the 13.57 m/s it leaves, not the 15 m/s the Init's SpeedAction asked for.
  FixtureRun run(engine_fixture("controller_domains.xosc"), domains_options());
  run.run();
  const double left = run.at(15.1, "Ego").speed;
  CHECK(left == Approx(13.572).margin(0.0005));
  for (const double t : {15.5, 16.0, 17.0}) {
    CAPTURE(t);
    CHECK(run.at(t, "Ego").speed == left);
  }
  // esmini's row at 16.0 s.
  CHECK(run.at(16.0, "Ego").pose.x - run.at(0.0, "Ego").pose.x == Approx(231.384).margin(0.0015));
}

TEST_CASE("two controllers on the motion domains whose shared step is not defined",
          "[engine][controllers][domains]") {
  // The sloppy driver longitudinal, the interactive driver then lateral: warned, and the one
  // activated last moves the entity alone (the interactive driver on the lateral domain drives
  // straight at the actions' speed).
  FixtureRun run(engine_fixture("controller_domains_exchanged.xosc"), domains_options());
  run.run();
  const std::string text = all_text(run.diagnostics());
  CHECK(text.find("controllers 'interactive_driver' and 'sloppy_driver' on different motion "
                  "domains") != std::string::npos);
  CHECK(text.find("controller_domains_exchanged.xosc:") != std::string::npos);
  for (const double t : {6.0, 8.0, 10.0}) {
    CAPTURE(t);
    CHECK(run.at(t, "Ego").speed == 15.0);
  }
  CHECK(run.at(5.0, "Ego").speed != 15.0);  // before: the sloppy driver's speed
}
