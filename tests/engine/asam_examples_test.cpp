// The ASAM OpenSCENARIO 1.3 examples (../shared/conformance/asam-osc-1.3) run to their stop
// trigger; key facts: who changes lane when, where everybody ends, final speeds. Times follow
// from the scenarios' numbers (distances and speeds), worked out in the comments.

#include "engine_fixture.h"

namespace corsa::test {
namespace {

using Catch::Detail::Approx;
using engine::TransitionKind;

TEST_CASE("ASAM CutIn: A2 overtakes Ego and cuts into its lane", "[engine][asam]") {
  FixtureRun run(asam("CutIn.xosc"));
  run.run();
  CHECK(run.sim().end_reason() == engine::EndReason::kStopTrigger);
  // A2 (30.556 m/s) starts 100 m behind Ego (27.778 m/s) one lane left; the cut-in starts on
  // the rising edge of "more than 20 m from Ego" (road coordinates), i.e. once A2 is ahead.
  const auto cut = run.first("Event1::Action1", TransitionKind::kStart);
  REQUIRE(cut);
  CHECK(*cut == Approx(43.1).margin(0.05));
  CHECK(run.at(*cut, "A2").road->lane == -2);
  CHECK(run.at(*cut, "A2").pose.x > run.at(*cut, "Ego").pose.x + 19.0);
  // Cubic over 54.83 m at 30.556 m/s: 1.79 s; then A2 is in Ego's lane (-3).
  CHECK(run.first("Event1::Action1", TransitionKind::kEnd) == Approx(*cut + 1.79).margin(0.02));
  CHECK(run.now("A2").road->lane == -3);
  CHECK(run.now("Ego").road->lane == -3);
  CHECK(run.now("A1").road->lane == -3);
  // The stop trigger waits 10 s after Act1 completes.
  CHECK(run.sim().time() == Approx(*run.first("MyStory::Act1", TransitionKind::kEnd) + 10.0));
  CHECK(run.now("A2").speed == Approx(30.556));
  CHECK(run.now("Ego").speed == Approx(27.778));
  CHECK(run.sim().collisions().empty());
}

TEST_CASE("ASAM DoubleLaneChanger: A1 cuts in front of Ego and back out", "[engine][asam]") {
  FixtureRun run(asam("DoubleLaneChanger.xosc"));
  run.run();
  // A1 (47.22 m/s) starts 13.24 m behind Ego (36.11 m/s) one lane left; once 5 m ahead
  // (18.24 m at 11.11 m/s: 1.64 s) it changes right for 2 s, then left again for 2 s.
  const auto right = run.first("MyLaneChangeRightAction", TransitionKind::kStart);
  REQUIRE(right);
  CHECK(*right == Approx(1.65).margin(0.02));
  const auto& after_right = run.at(*right + 2.0, "A1");
  CHECK(after_right.road->lane == run.at(*right + 2.0, "Ego").road->lane);
  CHECK(run.first("MyLaneChangeLeftAction", TransitionKind::kStart) == Approx(*right + 2.0));
  CHECK(run.first("MyLaneChangeLeftAction", TransitionKind::kEnd) == Approx(*right + 4.0));
  CHECK(run.now("A1").road->lane == run.at(0.0, "A1").road->lane);
  // Stop: A1 50 m ahead of A2, which started 83.24 m ahead of A1: 133.24 / 11.11 = 12.0 s.
  CHECK(run.sim().time() == Approx(12.0).margin(0.02));
  CHECK(run.now("A1").speed == Approx(47.2222));
}

TEST_CASE("ASAM Overtaker: A1 passes Ego on the left and returns", "[engine][asam]") {
  FixtureRun run(asam("Overtaker.xosc"));
  run.run();
  // A1 (41.67 m/s) is 79.04 m behind Ego (36.11 m/s) in the same lane: within 30 m after
  // 49.04 / 5.556 = 8.83 s it moves left (5 s); 5 m ahead (15.1 s) it moves back right.
  CHECK(run.first("MyLaneChangeLeftAction", TransitionKind::kStart) == Approx(8.83).margin(0.02));
  const auto back = run.first("MyLaneChangeRightAction", TransitionKind::kStart);
  REQUIRE(back);
  CHECK(*back == Approx(15.13).margin(0.02));
  const int own_lane = run.at(0.0, "A1").road->lane;
  CHECK(run.at(14.0, "A1").road->lane != own_lane);
  CHECK(run.now("A1").road->lane == own_lane);
  // The stop trigger fires 10 s after A1 is back in line: less than 0.5 m lateral distance is
  // reached toward the end of the 5 s sinusoidal change.
  CHECK(run.sim().time() > *back + 10.0 + 4.0);
  CHECK(run.sim().time() < *back + 10.0 + 5.0);
  CHECK(run.now("A1").pose.y > run.now("Ego").pose.y);  // ahead (the road runs along +y)
}

TEST_CASE("ASAM SimpleOvertake: Vehicle 1 overtakes Vehicle 2 on lane -3 and returns to -4",
          "[engine][asam]") {
  FixtureRun run(asam("SimpleOvertake.xosc"));
  run.run();
  // 58 m behind, 5.556 m/s faster: within 30 m after 5.04 s; lane change over 200 m (4.8 s).
  CHECK(run.first("Turn left::Lane Change", TransitionKind::kStart) == Approx(5.05).margin(0.02));
  CHECK(run.at(10.0, "Vehicle 1").road->lane == -3);
  // Vehicle 2 sees Vehicle 1 10 m ahead after 68 / 5.556 = 12.24 s: back to lane -4 in 4 s.
  CHECK(run.first("Turn right::Lane Change", TransitionKind::kStart) == Approx(12.25).margin(0.02));
  CHECK(run.now("Vehicle 1").road->lane == -4);
  CHECK(run.now("Vehicle 2").road->lane == -4);
  CHECK(run.sim().time() == Approx(20.01));
  CHECK(run.now("Vehicle 1").speed == Approx(41.6666666667));
}

TEST_CASE("ASAM SequentialEvents: 0-100-0 km/h, events ordered by states or by speed",
          "[engine][asam]") {
  for (const char* name :
       {"SequentialEvents_0-100-0kph_Explicit.xosc", "SequentialEvents_0-100-0kph_Implicit.xosc"}) {
    FixtureRun run(asam(name));
    run.run();
    INFO(name);
    // 4 m/s^2 up to 100 km/h (6.95 s), then 4 m/s^2 down to a stop; the run stops 3 s later.
    const auto brake = run.first("BrakeEvent", TransitionKind::kStart);
    REQUIRE(brake);
    CHECK(*brake == Approx(6.96).margin(0.011));
    CHECK(run.at(*brake, "Ego").speed == Approx(27.78).margin(0.05));
    const auto stopped = run.first("BrakeEvent", TransitionKind::kEnd);
    REQUIRE(stopped);
    CHECK(*stopped == Approx(13.91).margin(0.011));
    CHECK(run.sim().time() == Approx(*stopped + 3.0));
    CHECK(run.now("Ego").speed == 0.0);
    CHECK(run.now("Ego").road->lane == -3);
    // 0-100-0 at 4 m/s^2: about 27.8^2 / 4 = 193 m.
    CHECK(run.now("Ego").odometer == Approx(193.0).margin(1.0));
  }
  // Implicit: the brake event overrides the still running acceleration.
  FixtureRun implicit(asam("SequentialEvents_0-100-0kph_Implicit.xosc"));
  implicit.run();
  CHECK(implicit.first("AccelerateEvent", TransitionKind::kStop) == Approx(6.96));
}

TEST_CASE("ASAM SlowPrecedingVehicle: Ego closes on A1 until the time to collision is 0.5 s",
          "[engine][asam]") {
  FixtureRun run(asam("SlowPrecedingVehicle.xosc"));
  run.run();
  // 200 m apart, 5.556 m/s closing; free space 195.55 m; TTC < 0.5 s at a gap of 2.78 m.
  CHECK(run.sim().end_reason() == engine::EndReason::kStopTrigger);
  CHECK(run.sim().time() == Approx(34.71).margin(0.02));
  CHECK(run.now("Ego").speed == Approx(27.778));
  CHECK(run.now("A1").speed == Approx(22.222));
  CHECK(run.now("Ego").road->lane == -3);
  CHECK(run.now("A1").road->s - run.now("Ego").road->s == Approx(7.15).margin(0.05));
  CHECK(run.sim().collisions().empty());
}

TEST_CASE("ASAM examples with routes, trajectories and synchronization reach their stop trigger",
          "[engine][asam]") {
  for (const char* name : {"SynchronizedArrivalToIntersection.xosc", "CloseVehicleCrossing.xosc",
                           "TrailerConnect.xosc"}) {
    FixtureRun run(asam(name), with_duration(120.0));
    run.run();
    INFO(name);
    CHECK(run.sim().end_reason() == engine::EndReason::kStopTrigger);
    for (const auto& [tick, states] : run.trace().ticks()) {
      for (const auto& state : states) {
        CHECK(std::isfinite(state.pose.x));
        CHECK(std::abs(state.speed) < 70.0);
      }
    }
  }
}

TEST_CASE(
    "ASAM FastOvertakeWithReInitialization: Ego runs into A1 because the scenario drives it so",
    "[engine][asam][collision]") {
  FixtureRun run(asam("FastOvertakeWithReInitialization.xosc"));
  run.run();
  CHECK(run.sim().end_reason() == engine::EndReason::kStopTrigger);
  // One contact, Ego with A1, when Ego's front bumper reaches A1's rear bumper: Ego (car1, 5 m
  // box from 1.1 m behind its reference point) holds its Init speed of 130 km/h in lane -4 of
  // road 9; A1 (car2) starts 119.9 m ahead in the same lane at 90 km/h and slows to 60 km/h.
  // Nothing in the scenario changes Ego's speed or lane: the bumpers meet at 9.08 s.
  REQUIRE(run.sim().collisions().size() == 1);
  const auto& contact = run.sim().collisions().front();
  CHECK(contact.time == Approx(9.09).margin(0.02));
  CHECK(contact.first == run.entity("Ego"));
  CHECK(contact.second == run.entity("A1"));
  const auto& ego = run.at(contact.time, "Ego");
  const auto& a1 = run.at(contact.time, "A1");
  CHECK(ego.speed == Approx(130.0 / 3.6));
  REQUIRE(ego.road);
  REQUIRE(a1.road);
  CHECK(ego.road->road == a1.road->road);
  CHECK(ego.road->lane == -4);
  CHECK(a1.road->lane == -4);
  CHECK(std::abs(ego.pose.x - a1.pose.x) < 0.01);  // one lane, the same line
  CHECK(ego.pose.h == Approx(a1.pose.h));
  // Bumper to bumper along the road: Ego's front (3.9 m ahead) meets A1's rear (0.95 m behind).
  const double gap = (a1.pose.y - 0.95) - (ego.pose.y + 3.9);
  CHECK(gap < 0.0);
  CHECK(gap > -36.2 * run.sim().dt() - 1e-9);  // touching since this step only
  // The re-initialisation teleports A2 into the lane to A1's left (-3), 200 m behind it, where
  // it passes both without touching them.
  CHECK(run.now("A2").road->lane == -3);
  CHECK(run.now("Ego").speed == Approx(130.0 / 3.6));
}

}  // namespace
}  // namespace corsa::test
