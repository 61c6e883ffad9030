// esmini's followGhost controller (controllers/follow_ghost.h) on tests/engine/fixtures/
// controller_follow_ghost.xosc: Ego's ghost starts 2 s early, changes lane at 3 s of simulation
// time (its event's SimulationTimeCondition > 5 comes 2 s earlier) and speeds up from 6 s
// (> 8); Ego drives after it along its trail.
//
// What to expect, derived: the ghost performs Ego's actions from -2 s, so at every time t the
// ghost is where Ego would be at t + 2 had Ego performed them itself; Ego, steering toward the
// trail 1 s ahead of (t - 2) and taking the trail's speed 0.1 s ahead of it, drives the ghost's
// path 2 s later. On the straight it is there exactly (same start, same speed); through the
// lane change its 1 s look-ahead cuts the S-bend (0.35 m at most, measured), so Ego stays
// within 0.5 m of the ghost's position of 2 s before. Its speed loop (10 m/s^2 per m/s) lags
// the 2 m/s^2 ramp by 0.2 m/s and looks 0.1 s ahead (another 0.2 m/s): within 0.4 m/s.

#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "corsa/engine/outputs.h"
#include "corsa/engine/world_snapshot.h"
#include "engine_fixture.h"

using corsa::engine::Semantics;
using corsa::engine::TransitionKind;
using corsa::test::engine_fixture;
using corsa::test::FixtureRun;

namespace {

corsa::engine::SimulationOptions reading(Semantics semantics) {
  corsa::engine::SimulationOptions options;
  options.semantics = semantics;
  return options;
}

}  // namespace

TEST_CASE("followGhost makes a ghost that starts the run its head start earlier",
          "[engine][controllers][ghost]") {
  FixtureRun run(engine_fixture("controller_follow_ghost.xosc"));
  REQUIRE(run.sim().entity_count() == 3);
  CHECK(run.sim().entity(2).name == "Ego_ghost");
  CHECK(run.sim().tick() == -200);
  CHECK(run.sim().time() == Approx(-2.0));
  run.run();
  CHECK(run.sim().time() == Approx(15.0));
  // The ghost's lane change and speed-up come 2 s before their SimulationTimeConditions.
  CHECK(run.first("ChangeLane", TransitionKind::kStart) == Approx(3.01));
  CHECK(run.first("SpeedUp", TransitionKind::kStart) == Approx(6.01));
  // Until time 0 only the ghost moves.
  CHECK(run.at(0.0, "Ego").pose.x == Approx(20.0));
  CHECK(run.at(0.0, "Other").pose.x == Approx(20.0));
  CHECK(run.at(0.0, "Ego_ghost").pose.x == Approx(40.0));
  CHECK(run.at(0.0, "Ego_ghost").pose.y == Approx(-1.75));
}

TEST_CASE("the entity under followGhost drives its ghost's trail 2 s behind it",
          "[engine][controllers][ghost]") {
  for (const Semantics semantics : {Semantics::kStandard, Semantics::kEsmini}) {
    FixtureRun run(engine_fixture("controller_follow_ghost.xosc"), reading(semantics));
    run.run();
    double worst = 0.0, worst_speed = 0.0;
    for (int tick = 0; tick <= 1500; ++tick) {
      const double t = tick * 0.01;
      const auto& ego = run.at(t, "Ego");
      const auto& ghost = run.at(t - 2.0, "Ego_ghost");
      worst = std::max(worst, std::hypot(ego.pose.x - ghost.pose.x, ego.pose.y - ghost.pose.y));
      worst_speed = std::max(worst_speed, std::abs(ego.speed - ghost.speed));
    }
    CAPTURE(static_cast<int>(semantics));
    CHECK(worst < 0.5);
    CHECK(worst_speed < 0.2 + 0.1 * 2.0);
    // Ego ends in the ghost's lane at the ghost's speed.
    CHECK(run.at(15.0, "Ego").pose.y == Approx(-5.25).margin(0.05));
    CHECK(run.at(15.0, "Ego").speed == Approx(15.0).margin(0.01));
    CHECK(run.at(15.0, "Ego").road->lane == -2);
  }
}

TEST_CASE("the ghost is seen by no one: no collisions, invisible to sensors",
          "[engine][controllers][ghost]") {
  FixtureRun run(engine_fixture("controller_follow_ghost.xosc"));
  // Ego and its ghost stand on each other at -2 s and until the ghost drives off.
  run.sim().step();
  corsa::engine::WorldSnapshot world;
  run.sim().fill_snapshot(world);
  REQUIRE(world.entities.size() == 3);
  CHECK(world.entities[0].visible);
  CHECK_FALSE(world.entities[2].visible);
  CHECK_FALSE(run.sim().colliding(0, 2));
  run.run();
  CHECK(run.sim().collisions().empty());
}

TEST_CASE("without controllers followGhost makes no ghost and the entity performs its actions",
          "[engine][controllers][ghost]") {
  corsa::engine::SimulationOptions options;
  options.disable_controllers = true;
  FixtureRun run(engine_fixture("controller_follow_ghost.xosc"), options);
  CHECK(run.sim().entity_count() == 2);
  CHECK(run.sim().tick() == 0);
  run.run();
  CHECK(run.first("ChangeLane", TransitionKind::kStart) == Approx(5.01));
  CHECK(run.at(15.0, "Ego").road->lane == -2);
}

TEST_CASE("a ghost run counts the steps taken from its negative start, not the final tick",
          "[engine][controllers][ghost]") {
  FixtureRun run(engine_fixture("controller_follow_ghost.xosc"));
  CHECK(run.sim().start_tick() == -200);
  CHECK(run.sim().steps() == 0);
  run.run();
  // From -2 s to 15 s at 0.01 s: 1700 steps, though the final tick is 1500.
  CHECK(run.sim().tick() == 1500);
  CHECK(run.sim().steps() == 1700);
  const std::string summary = corsa::engine::summary_json(run.sim(), 1.0);
  CHECK(summary.find("\"steps\": 1700") != std::string::npos);
  CHECK(summary.find("\"start_time\": -2") != std::string::npos);
}
