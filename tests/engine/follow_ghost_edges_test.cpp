// esmini's followGhost controller (controllers/follow_ghost.h) where a scenario does odd things
// to the entity or its ghost mid-run, and its position follow mode. The fixtures are
// tests/engine/fixtures/controller_follow_ghost.xosc with one change each (their headers say
// which): the run goes on to its 15 s end with located warnings where the file is odd, and the
// entity never jumps but where its ghost did.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "engine_fixture.h"

using corsa::test::engine_fixture;
using corsa::test::FixtureRun;

namespace {

// The warning whose message holds `text`, with the line it points at (0: none such).
int warning_line(FixtureRun& run, const std::string& text) {
  for (const auto& d : run.diagnostics().all()) {
    if (d.message.find(text) != std::string::npos) return d.line;
  }
  return 0;
}

// The largest distance Ego moved in one step over [from, to] s.
double largest_step(const FixtureRun& run, double from, double to) {
  double worst = 0.0;
  for (double t = from; t < to - 1e-9; t += 0.01) {
    const auto& a = run.at(t, "Ego").pose;
    const auto& b = run.at(t + 0.01, "Ego").pose;
    worst = std::max(worst, std::hypot(b.x - a.x, b.y - a.y));
  }
  return worst;
}

}  // namespace

TEST_CASE("deleting the entity under followGhost takes its ghost with it",
          "[engine][controllers][ghost]") {
  FixtureRun run(engine_fixture("controller_follow_ghost_delete.xosc"));
  run.run();
  CHECK(run.sim().time() == Approx(15.0));
  CHECK(run.at(6.9, "Ego").placed);
  CHECK(run.at(6.9, "Ego_ghost").placed);
  CHECK_FALSE(run.at(7.02, "Ego").placed);
  CHECK_FALSE(run.at(7.02, "Ego_ghost").placed);
  CHECK_FALSE(run.sim().state(run.entity("Ego_ghost")).placed);
}

TEST_CASE("the entity under followGhost jumps where its ghost was teleported, when it gets there",
          "[engine][controllers][ghost]") {
  FixtureRun run(engine_fixture("controller_follow_ghost_teleport.xosc"));
  run.run();
  // The ghost jumps at 7 s (the event's > 9, 2 s earlier), Ego 2 s later.
  CHECK(run.at(7.05, "Ego_ghost").pose.x > 195.0);
  CHECK(run.at(8.9, "Ego").pose.x < 150.0);
  CHECK(run.at(9.1, "Ego").pose.x > 195.0);
  CHECK(run.at(9.1, "Ego").pose.y == Approx(-8.75).margin(0.3));
  CHECK(run.at(15.0, "Ego").road->lane == -3);
  // One jump; before and after it Ego drives.
  CHECK(largest_step(run, 0.0, 8.9) < 0.2);
  CHECK(largest_step(run, 9.2, 15.0) < 0.2);
}

TEST_CASE("followGhost switched off and on again drives on from where the entity is",
          "[engine][controllers][ghost]") {
  FixtureRun run(engine_fixture("controller_follow_ghost_deactivate.xosc"));
  run.run();
  CHECK(warning_line(run, "followGhost of 'Ego' deactivated") > 0);
  // Off from 4 s: the default controller keeps lane -1 where the trail changes lane at 5 s.
  CHECK(run.at(8.9, "Ego").road->lane == -1);
  CHECK(run.at(8.9, "Ego").speed == Approx(10.0).margin(0.5));
  // On at 9 s: no jump back to where the model was at 4 s; it reaches the ghost's lane.
  CHECK(largest_step(run, 0.0, 15.0) < 0.2);
  CHECK(run.at(15.0, "Ego").road->lane == -2);
}

TEST_CASE("another controller assigned to the entity under followGhost warns",
          "[engine][controllers][ghost]") {
  FixtureRun run(engine_fixture("controller_follow_ghost_assign.xosc"));
  run.run();
  CHECK(warning_line(run, "its motion actions go on to the ghost") > 0);
  // The default controller keeps Ego's speed and lane; the ghost changes lane and speeds up.
  CHECK(run.at(15.0, "Ego").road->lane == -1);
  CHECK(run.at(15.0, "Ego").speed == Approx(10.0).margin(0.5));
  CHECK(run.at(13.0, "Ego_ghost").speed == Approx(15.0));
  CHECK(largest_step(run, 0.0, 15.0) < 0.2);
}

TEST_CASE("followGhost in position mode follows the trail by the point nearest the entity",
          "[engine][controllers][ghost]") {
  FixtureRun run(engine_fixture("controller_follow_ghost_position.xosc"));
  run.run();
  CHECK(warning_line(run, "followMode") == 0);
  // Ego's distance to the ghost's path (its positions over the run) at every step.
  double worst = 0.0;
  for (int tick = 0; tick <= 1500; ++tick) {
    const auto& ego = run.at(tick * 0.01, "Ego").pose;
    double nearest = 1e9;
    for (int g = -200; g <= 1500; g += 2) {
      const auto& ghost = run.at(g * 0.01, "Ego_ghost").pose;
      nearest = std::min(nearest, std::hypot(ego.x - ghost.x, ego.y - ghost.y));
    }
    worst = std::max(worst, nearest);
  }
  CHECK(worst < 0.5);
  CHECK(run.at(15.0, "Ego").road->lane == -2);
  CHECK(run.at(15.0, "Ego").speed == Approx(15.0).margin(0.2));
}

TEST_CASE("an entity that stands during the ghost's head start begins its actions at time 0",
          "[engine][controllers][ghost]") {
  // The Other car's 4 s linear brake from 10 m/s starts with the Act at -2 s; the car stands
  // until 0 and brakes from there (before: the brake's clock ran from -2 s, so the car stopped
  // at 2 s after 5 m). Each step travels its end speed, dt / 2 times the speed lost short of
  // the exact integral: 0.005 x 5 m/s by 2 s, 0.005 x 10 m/s once stopped.
  FixtureRun run(engine_fixture("controller_follow_ghost_other_brakes.xosc"));
  run.run();
  CHECK(run.at(0.0, "Other").road->s == Approx(20.0));
  CHECK(run.at(0.0, "Other").speed == Approx(10.0));
  CHECK(run.at(2.0, "Other").speed == Approx(5.0).margin(1e-9));
  CHECK(run.at(2.0, "Other").road->s == Approx(35.0 - 0.025).margin(1e-6));
  CHECK(run.at(4.0, "Other").speed == Approx(0.0).margin(1e-9));
  CHECK(run.at(6.0, "Other").road->s == Approx(40.0 - 0.05).margin(1e-6));
  // The ghost's own run is unchanged: it left at -2 s.
  CHECK(run.at(0.0, "Ego_ghost").road->s == Approx(40.0).margin(1e-6));
}

namespace {

// The run's time and Ego's and the ghost's s at every step, in the order of the steps (a ghost
// restart runs times again, which a map by tick would fold).
class StepTimes final : public corsa::engine::SimulationObserver {
 public:
  struct Step {
    double time, ego_s, ghost_s;
  };
  StepTimes(size_t ego, size_t ghost) : ego_(ego), ghost_(ghost) {}
  void on_step(const corsa::engine::Simulation& sim) override {
    steps.push_back({sim.time(), sim.state(ego_).road->s, sim.state(ghost_).road->s});
  }
  std::vector<Step> steps;

 private:
  size_t ego_, ghost_;
};

}  // namespace

TEST_CASE("an event on a condition the ghost cannot meet ahead restarts the ghost from the entity",
          "[engine][controllers][ghost]") {
  // Ego brakes on a parameter set at 5 s: the ghost is put back onto Ego at 5.01 s, the time goes
  // back 2 s and the ghost alone runs to 5.01 s again, braking; Ego brakes 2 s behind it, from
  // about 5 s (without the restart it would brake from 7 s, 20 m further on).
  FixtureRun run(engine_fixture("controller_follow_ghost_restart.xosc"));
  StepTimes times(run.entity("Ego"), run.entity("Ego_ghost"));
  run.sim().add_observer(times);
  run.run();
  CHECK(run.sim().time() == Approx(15.0));
  // 1700 steps from -2 s to 15 s and the 200 run again.
  CHECK(run.sim().steps() == 1900);
  // The one step back: from 5.01 s to 3.02 s; meanwhile Ego stands at 70.1 m and the ghost, put
  // back there, drives on ahead of it.
  size_t back = 0, at = 0;
  for (size_t i = 1; i < times.steps.size(); ++i) {
    if (times.steps[i].time < times.steps[i - 1].time) {
      ++back;
      at = i;
    }
  }
  REQUIRE(back == 1);
  CHECK(times.steps[at - 1].time == Approx(5.01));
  CHECK(times.steps[at].time == Approx(3.02));
  CHECK(times.steps[at].ego_s == Approx(70.1).margin(1e-6));
  CHECK(times.steps[at].ghost_s == Approx(70.2).margin(1e-6));
  CHECK(times.steps[at + 198].time == Approx(5.0));
  CHECK(times.steps[at + 198].ego_s == Approx(70.1).margin(1e-6));
  CHECK(times.steps[at + 198].ghost_s == Approx(85.0).margin(0.2));
  // Ego brakes after the new trail: 5 m/s at 7 s, at rest about 20 m after 70 m.
  CHECK(run.at(7.0, "Ego").speed == Approx(5.0).margin(0.2));
  CHECK(run.at(15.0, "Ego").speed == Approx(0.0).margin(0.01));
  CHECK(run.at(15.0, "Ego").road->s == Approx(90.0).margin(0.5));
  // Ego never jumps, the step back in time included (it stands through the replay).
  double worst = 0.0;
  for (size_t i = 1; i < times.steps.size(); ++i) {
    worst = std::max(worst, std::abs(times.steps[i].ego_s - times.steps[i - 1].ego_s));
  }
  CHECK(worst < 0.2);
}

TEST_CASE("a ghost restart counts neither the jump back nor the ticks run again as travelled",
          "[engine][controllers][ghost][condition]") {
  // esmini's ghost_restart.xosc with TraveledDistanceConditions on Ego, which read the ghost
  // (0.5 s ahead, 10 m/s): at 1 s the lane change restarts the ghost from Ego, which has
  // travelled 10 m, and the time goes back to 0.5 s; the ghost carries those 10 m over. So its
  // distance stays 10 m/s * (t + 0.5 s) at the ghost's time t (plus under 0.1 m of the lane
  // change's sideways steps): 16 m at 1.1 s, 20 m at 1.5 s and 30 m at 2.5 s. Counting the jump
  // back and the replayed ticks, the 16 m and 20 m events started at 0.52 s.
  FixtureRun run(engine_fixture("controller_follow_ghost_restart_traveled.xosc"));
  StepTimes times(run.entity("Ego"), run.entity("Ego_ghost"));
  run.sim().add_observer(times);
  run.run();
  size_t back = 0;
  for (size_t i = 1; i < times.steps.size(); ++i) {
    back += times.steps[i].time < times.steps[i - 1].time ? 1 : 0;
  }
  REQUIRE(back == 1);
  const auto started = [&](const std::string& event) -> std::optional<double> {
    for (const auto& record : run.sim().transitions()) {
      if (record.transition == corsa::engine::TransitionKind::kStart &&
          record.path == "S::A::G::M::" + event) {
        return record.time;
      }
    }
    return std::nullopt;
  };
  CHECK(started("Travel16") == Approx(1.1).margin(1e-9));
  CHECK(started("Travel20") == Approx(1.5).margin(1e-9));
  CHECK(started("Travel30") == Approx(2.5).margin(1e-9));
}
