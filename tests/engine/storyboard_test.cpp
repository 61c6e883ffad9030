// The storyboard state machine (OpenSCENARIO 1.3 §8.4): priorities, execution counts, act
// triggers, edges and delays, how runs end.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "engine_fixture.h"

namespace corsa::test {
namespace {

using Catch::Detail::Approx;
using engine::ElementState;
using engine::TransitionKind;

TEST_CASE("Event priorities override, skip and parallel", "[engine][storyboard][priority]") {
  FixtureRun run(engine_fixture("storyboard_priorities.xosc"));
  run.run();
  SECTION("override stops the running event of the same maneuver") {
    CHECK(run.first("OverrideGroup::M::Long", TransitionKind::kStop) == Approx(2.01));
    CHECK(run.first("OverrideGroup::M::Long::Ramp", TransitionKind::kStop) == Approx(2.01));
    CHECK(run.count("OverrideGroup::M::Long", TransitionKind::kEnd) == 0);
    CHECK(run.now("Overridden").speed == 5.0);
  }
  SECTION("skip does not start while another event runs, and counts as an execution") {
    CHECK(run.first("SkipGroup::M::Skipped", TransitionKind::kSkip) == Approx(1.01));
    CHECK(run.count("SkipGroup::M::Skipped", TransitionKind::kStart) == 0);
    CHECK(run.state_of("SkipGroup::M::Skipped") == ElementState::kComplete);
    CHECK(run.count("SkipGroup::M::SkippedTwice", TransitionKind::kSkip) == 2);
    CHECK(run.first("SkipGroup::M::Later", TransitionKind::kStart) == Approx(5.01));
    CHECK(run.now("Skipper").speed == 10.0);
  }
  SECTION("parallel runs alongside the running event") {
    CHECK(run.first("ParallelGroup::M::Swerve", TransitionKind::kStart) == Approx(1.01));
    CHECK(run.first("ParallelGroup::M::Accelerate", TransitionKind::kEnd) == Approx(4.51));
    CHECK(run.count("ParallelGroup::M::Accelerate", TransitionKind::kStop) == 0);
    CHECK(run.now("Parallel").road->lane == -2);
    CHECK(run.now("Parallel").speed == 20.0);
  }
  // The story is complete at 5.01 s, but a storyboard with a stop trigger runs until it fires.
  CHECK(run.first("S", TransitionKind::kEnd) == Approx(5.01));
  CHECK(run.sim().end_reason() == engine::EndReason::kStopTrigger);
  CHECK(run.sim().time() == Approx(6.01));
}

TEST_CASE("maximumExecutionCount re-runs events and maneuver groups",
          "[engine][storyboard][count]") {
  FixtureRun run(engine_fixture("storyboard_execution_count.xosc"));
  run.run();
  CHECK(run.sim().variable("Executions")->text() == "3");
  CHECK(run.count("Events::M::Thrice", TransitionKind::kStart) == 3);
  CHECK(run.count("Events::M::Thrice", TransitionKind::kEnd) == 3);
  CHECK(run.state_of("Events::M::Thrice") == ElementState::kComplete);
  CHECK(run.sim().variable("Rounds")->text() == "2");
  CHECK(run.count("S::A::Twice", TransitionKind::kStart) == 2);
  CHECK(run.first("Twice::M::Round", TransitionKind::kStart) == Approx(2.01));
  CHECK(run.sim().element_state("S::A::Twice") == ElementState::kComplete);
}

TEST_CASE("Act start and stop triggers", "[engine][storyboard][act]") {
  FixtureRun run(engine_fixture("storyboard_act_triggers.xosc"));
  run.run();
  CHECK(run.first("S::Later", TransitionKind::kStart) == Approx(1.01));
  CHECK(run.first("S::Later", TransitionKind::kStop) == Approx(3.01));
  CHECK(run.first("Later::G::M::Ramp::Accelerate", TransitionKind::kStop) == Approx(3.01));
  CHECK(run.now("Car").speed == Approx(4.0));  // the ramp stopped a fifth of the way
  CHECK(run.count("S::Never", TransitionKind::kStart) == 0);
  CHECK(run.first("S::Never", TransitionKind::kStop) == Approx(4.01));
  CHECK(run.sim().end_reason() == engine::EndReason::kStopTrigger);
  CHECK(run.sim().time() == Approx(4.01));
}

TEST_CASE("Condition edges and delays", "[engine][storyboard][trigger]") {
  FixtureRun run(engine_fixture("storyboard_edges.xosc"));
  run.run();
  // Speed > 10 m/s from 2.01 s (accelerating at 5 m/s^2) until 8.01 s (braking from 6.01 s).
  const auto start = [&](const std::string& event) {
    return run.first("Marks::M::" + event, TransitionKind::kStart);
  };
  CHECK(start("Rising") == Approx(2.01));
  CHECK(start("Falling") == Approx(8.01));
  CHECK(run.count("Marks::M::Both", TransitionKind::kStart) == 2);
  CHECK(start("Delayed") == Approx(3.51));
  CHECK(start("RisingDelayed") == Approx(2.51));
  // True from the first check: no rising edge is ever seen.
  CHECK(run.count("Marks::M::NeverRises", TransitionKind::kStart) == 0);
  CHECK(run.first("Marks::M::NeverRises", TransitionKind::kStop) == Approx(11.01));
}

TEST_CASE("A run ends with its stories, its stop trigger or the duration cap",
          "[engine][storyboard][end]") {
  SECTION("every story complete without a stop trigger") {
    FixtureRun run(engine_fixture("storyboard_stories_complete.xosc"));
    run.run();
    CHECK(run.sim().end_reason() == engine::EndReason::kStoriesComplete);
    CHECK(run.sim().time() == Approx(3.01));
    CHECK(run.sim().element_state("") == ElementState::kComplete);
    CHECK(run.sim().transitions().back().transition == TransitionKind::kEnd);
  }
  SECTION("the duration cap") {
    engine::SimulationOptions options;
    options.duration = 2.0;
    FixtureRun run(engine_fixture("storyboard_stories_complete.xosc"), options);
    run.run();
    CHECK(run.sim().end_reason() == engine::EndReason::kDuration);
    CHECK(run.sim().tick() == 200);
    CHECK(!run.sim().step());
    CHECK(run.sim().tick() == 200);
  }
  SECTION("another step size keeps the times on its grid") {
    engine::SimulationOptions options;
    options.dt = 0.05;
    FixtureRun run(engine_fixture("storyboard_stories_complete.xosc"), options);
    run.run();
    CHECK(run.sim().time() == Approx(3.05));
    CHECK(run.first("G::M::Go", TransitionKind::kStart) == Approx(1.05));
  }
}

TEST_CASE("A maneuver group run again starts its events' conditions afresh",
          "[engine][storyboard][execution]") {
  // "slow" starts 1 s after "fast" is complete and takes 0.5 s; the group then runs again. Its
  // second "slow" waits for the second "fast" (the condition's value of 1 s before the restart,
  // from the first execution, does not start it at once).
  engine::SimulationOptions options;
  options.dt = 0.1;
  FixtureRun run(engine_fixture("group_restart_delay.xosc"), options);
  run.run();
  std::vector<double> fast;
  std::vector<double> slow;
  for (const auto& record : run.sim().transitions()) {
    if (record.transition != TransitionKind::kStart) continue;
    if (record.path == "S::A::G::M::fast") fast.push_back(record.time);
    if (record.path == "S::A::G::M::slow") slow.push_back(record.time);
  }
  REQUIRE(fast.size() == 2);
  REQUIRE(slow.size() == 2);
  CHECK(slow[0] == Approx(fast[0] + 1.0).margin(1e-9));
  CHECK(fast[1] == Approx(slow[0] + 0.5 + 1.0).margin(1e-9));  // 1 s after the group restarts
  CHECK(slow[1] == Approx(fast[1] + 1.0).margin(1e-9));
}

TEST_CASE("An act's walk reaches every event a transition of the same walk makes ready",
          "[engine][storyboard][walk]") {
  // Most steps change no element state and the walk visits only the events in standby it found
  // before; a transition made during the walk sends the rest of it over every group again.
  FixtureRun run(engine_fixture("storyboard_walk.xosc"));
  run.run();
  const auto start = [&](const std::string& event) {
    return run.first(event, TransitionKind::kStart);
  };
  // First's start is seen by Second, later in its maneuver, and Second's by Third, in the next
  // group, in the same walk; Late, before them in the document, sees Third's at the next step.
  CHECK(start("One::OneM::First") == Approx(1.01));
  CHECK(start("One::OneM::Second") == Approx(1.01));
  CHECK(start("Two::TwoM::Third") == Approx(1.01));
  CHECK(start("One::OneM::Late") == Approx(1.02));
  // A group that ends with executions left starts again at the next step (the walk's stop at a
  // group in standby), and its first end starts an event of a later group in the same walk.
  CHECK(run.count("S::A::Rounds", TransitionKind::kStart) == 3);
  CHECK(run.count("Rounds::RoundsM::Round", TransitionKind::kStart) == 3);
  CHECK(run.first("S::A::Rounds", TransitionKind::kEnd) == Approx(2.01));
  CHECK(start("Four::FourM::AfterRounds") == Approx(2.01));
  CHECK(run.state_of("S::A::Rounds") == ElementState::kComplete);
  // After three seconds of steps that changed no element state, Waiter's trigger still fires
  // on the first step its time condition holds.
  CHECK(start("Two::TwoM::Waiter") == Approx(5.01));
  CHECK(run.first("S::A", TransitionKind::kEnd) == Approx(5.01));
  CHECK(run.now("Car").speed == 5.0);
}

TEST_CASE("Conditions whose inputs stood for long fire on the step they change",
          "[engine][storyboard][trigger]") {
  // For 20 s no element state is written and Car stands (its state's count of writes stays):
  // the triggers read none of their inputs again, and take the values those gave. Go then
  // accelerates Car at 5 m/s^2 from 20.01 s; each condition must fire on the step its value
  // changes, with its own edge and delay.
  FixtureRun run(engine_fixture("storyboard_standing_inputs.xosc"));
  engine::Simulation& sim = run.sim();
  const size_t car = run.entity("Car");
  while (sim.tick() < 100) REQUIRE(sim.step());
  const uint32_t standing = sim.state_changes()[car];
  const size_t transitions = sim.transitions().size();
  while (sim.tick() < 2000) REQUIRE(sim.step());
  REQUIRE(sim.state_changes()[car] == standing);
  REQUIRE(sim.transitions().size() == transitions);
  run.run();
  const double dt = sim.dt();
  const auto start = [&](const std::string& event) {
    return run.first("M::" + event, TransitionKind::kStart);
  };
  // The first step at which `holds` holds for Car's recorded state (its conditions read it).
  const auto first_step = [&](const auto& holds) -> std::optional<double> {
    for (const auto& [tick, states] : run.trace().ticks()) {
      if (holds(states.at(car))) return static_cast<double>(tick) * dt;
    }
    return std::nullopt;
  };
  CHECK(start("Go") == Approx(20.01));
  const auto fast = first_step([](const engine::EntityState& s) { return s.speed > 10.0; });
  REQUIRE(fast);
  CHECK(*fast > 22.0);
  CHECK(start("Faster") == Approx(*fast));
  CHECK(start("FasterLater") == Approx(*fast + 0.5));
  const auto moves = first_step([](const engine::EntityState& s) { return s.speed >= 0.001; });
  REQUIRE(moves);
  CHECK(start("Moves") == Approx(*moves));
  // Within 1 m of s = 50 (x = 50 on the straight road, in Car's lane).
  const auto near = first_step([](const engine::EntityState& s) { return s.pose.x >= 49.0; });
  REQUIRE(near);
  CHECK(start("Reached") == Approx(*near));
  // Element states: Go's start is seen once (the evaluation after it has the time condition of
  // the group, and no second sight of the start); its running state rises at its start, seen 1 s
  // later; its end (20 m/s after 4 s) is seen on its step. The stop trigger, checked before the
  // acts, sees SeesGoEnd complete one step later, and fires 3 s after that.
  CHECK(run.count("M::GoSeenOnce", TransitionKind::kStart) == 0);
  CHECK(start("GoRunningLater") == Approx(21.01));
  const auto end = run.first("M::Go", TransitionKind::kEnd);
  REQUIRE(end);
  CHECK(*end == Approx(24.01));
  CHECK(start("SeesGoEnd") == Approx(*end));
  CHECK(sim.end_reason() == engine::EndReason::kStopTrigger);
  CHECK(sim.time() == Approx(*end + 3.01));
}

}  // namespace
}  // namespace corsa::test
