// Motion: the default controller along lanes, sections, road links and junctions, bad
// placements and two simulations side by side; SynchronizeAction (also within Performance
// limits), FollowTrajectoryAction, LongitudinalDistanceAction, LateralDistanceAction and
// SpeedProfileAction on the focused scenarios of fixtures/, the bundled scenarios and the ASAM
// examples that use them.

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <string>

#include "engine_fixture.h"
#include "motion/jerk_profile.h"

namespace corsa::test {
namespace {

using Catch::Detail::Approx;
using engine::TransitionKind;

/// The time (s, interpolated between ticks) at which `name` first passes road s `s` on the road
/// with id `road`, driving in direction `dir` (+1: toward +s); nothing when it never does.
std::optional<double> passing_time(FixtureRun& run, const std::string& name,
                                   const std::string& road, double s, int dir) {
  const size_t index = run.entity(name);
  std::optional<std::pair<double, double>> previous;  // (time, s) on that road
  for (const auto& [tick, states] : run.trace().ticks()) {
    const auto& at = states[index].road;
    if (!at || run.sim().road_id(at->road) != road) {
      previous.reset();
      continue;
    }
    const double time = run.sim().time_of(tick);
    if (previous && dir * (previous->second - s) < 0.0 && dir * (at->s - s) >= 0.0) {
      const double w = (s - previous->second) / (at->s - previous->second);
      return previous->first + w * (time - previous->first);
    }
    previous = std::make_pair(time, at->s);
  }
  return std::nullopt;
}

TEST_CASE("The default controller follows lanes through sections, road links and junctions",
          "[engine][motion]") {
  FixtureRun run(engine_fixture("motion_lane_links.xosc"));
  run.run();
  const size_t driver = run.entity("Driver");
  std::vector<std::pair<std::string, int>> visited;
  const engine::EntityState* previous = nullptr;
  double largest_step = 0.0;
  for (const auto& [tick, states] : run.trace().ticks()) {
    const engine::EntityState& s = states[driver];
    REQUIRE(s.road);
    const std::pair<std::string, int> where{run.sim().road_id(s.road->road), s.road->lane};
    if (visited.empty() || visited.back() != where) {
      visited.push_back(where);
    }
    CHECK(std::abs(s.pose.h) < 1e-9);  // every road here runs along +x for the driver
    CHECK(s.pose.y == Approx(-1.75));
    if (previous != nullptr) {
      largest_step = std::max(largest_step,
                              std::hypot(s.pose.x - previous->pose.x, s.pose.y - previous->pose.y));
    }
    previous = &s;
  }
  // Road 2 runs the other way round: its lane 1 continues lane -1; the junction's straight
  // connection (road 10) wins over the right turn (road 11).
  const std::vector<std::pair<std::string, int>> expected{
      {"1", -1}, {"2", 1}, {"10", -1}, {"3", -1}};
  CHECK(visited == expected);
  CHECK(largest_step <= 20.0 * 0.01 + 1e-9);  // no jump anywhere
  // 300 + 300 + 20 + 200 m at 20 m/s: at the end of road 3 after 41 s, stopped there.
  CHECK(run.now("Driver").pose.x == Approx(1020.0));
  CHECK(run.now("Driver").speed == 0.0);
  CHECK(run.now("Driver").odometer == Approx(820.0));
  CHECK(run.sim().time() == Approx(41.01));
  CHECK(run.sim().end_reason() == engine::EndReason::kStopTrigger);
}

TEST_CASE("An entity stopped at the end of the road drives on at its speed once put elsewhere",
          "[engine][motion]") {
  FixtureRun run(engine_fixture("motion_end_of_road_teleport.xosc"));
  run.run();
  // 40 m at 20 m/s to the end at 2 s, where it stands; the EndOfRoadCondition (0.5 s) holds at
  // 2.5 s and teleports it back to s = 100.
  CHECK(run.at(2.0, "Runner").pose.x == Approx(1000.0));
  CHECK(run.at(2.3, "Runner").speed == 0.0);
  CHECK(run.at(2.3, "Runner").pose.x == Approx(1000.0));
  const auto back = run.first("S::A::G::M::Back::Back", TransitionKind::kStart);
  REQUIRE(back);
  CHECK(*back == Approx(2.5));
  // The teleport takes its step; from there at the 20 m/s the SpeedAction asked for (a step
  // travels its end speed).
  CHECK(run.now("Runner").speed == Approx(20.0));
  CHECK(run.now("Runner").pose.x == Approx(100.0 + 20.0 * (run.sim().time() - 2.51)));
}

TEST_CASE("Entities placed on a missing road or lane, or off the map, fail before the run",
          "[engine][motion][errors]") {
  const auto message = [](const std::string& fixture) -> std::string {
    try {
      FixtureRun run(engine_fixture(fixture));
    } catch (const InputError& error) {
      CHECK(error.diagnostic().file.find(fixture) != std::string::npos);
      CHECK(error.diagnostic().line == 27);
      return error.diagnostic().message;
    }
    FAIL("no error for " << fixture);
    return {};
  };
  CHECK(message("error_missing_road.xosc") == "road '7' does not exist in the road network");
  CHECK(message("error_missing_lane.xosc") == "road '1' has no lane -9 at s = 10");
  CHECK(message("error_off_map.xosc").find("placed off the map") != std::string::npos);
}

TEST_CASE("Two simulations of one scenario in one process do not interact",
          "[engine][motion][determinism]") {
  FixtureRun first(engine_fixture("action_lane_change.xosc"));
  FixtureRun second(engine_fixture("action_lane_change.xosc"));
  // Interleaved steps, one simulation ahead of the other.
  for (int i = 0; i < 50; ++i) {
    first.sim().step();
  }
  while (first.sim().step()) {
    second.sim().step();
  }
  second.run();
  REQUIRE(first.sim().tick() == second.sim().tick());
  for (const auto& [tick, states] : first.trace().ticks()) {
    for (size_t i = 0; i < states.size(); ++i) {
      CHECK(states[i].pose.x == second.trace().at(tick, i).pose.x);
      CHECK(states[i].pose.y == second.trace().at(tick, i).pose.y);
    }
  }
}

TEST_CASE("SynchronizeAction brings the follower to its point when the master reaches its own",
          "[engine][synchronize]") {
  FixtureRun run(engine_fixture("action_synchronize.xosc"));
  run.run();
  // Master drives -s on road 1 lane 1; Follower -s on road 4 lane 1: both toward the junction.
  const auto master = passing_time(run, "Master", "1", 5.0, -1);
  const auto follower = passing_time(run, "Follower", "4", 5.0, -1);
  REQUIRE(master);
  REQUIRE(follower);
  // 85 m at 10 m/s.
  CHECK(*master == Approx(8.5).margin(0.02));
  CHECK(std::abs(*master - *follower) <= run.sim().dt());
  // The final speed (6 m/s) is held over the last 10 m and after the action.
  CHECK(run.at(*follower - 1.0, "Follower").speed == Approx(6.0).margin(0.05));
  CHECK(run.now("Follower").speed == Approx(6.0));
  CHECK(run.first("S0::Act0::G::M::E::A", TransitionKind::kEnd));
  // Plausible motion: never backwards, never faster than it needs.
  for (const auto& [tick, states] : run.trace().ticks()) {
    CHECK(states[run.entity("Follower")].speed >= 0.0);
    CHECK(states[run.entity("Follower")].speed < 15.0);
  }
}

TEST_CASE("SynchronizeAction with a relative final speed held for a steady-state time",
          "[engine][synchronize]") {
  FixtureRun run(engine_fixture("action_synchronize.xosc"));
  run.run();
  const auto master = passing_time(run, "Master", "1", 5.0, -1);
  const auto follower = passing_time(run, "Follower2", "2", 5.0, -1);
  REQUIRE(master);
  REQUIRE(follower);
  CHECK(std::abs(*master - *follower) <= run.sim().dt());
  // Half the master's speed (factor 0.5 of 10 m/s), held for the last 2 s.
  CHECK(run.at(*follower, "Follower2").speed == Approx(5.0).margin(0.05));
  CHECK(run.at(*follower - 1.5, "Follower2").speed == Approx(5.0).margin(0.05));
}

TEST_CASE(
    "SynchronizeAction keeps the appointment beyond the actors' Performance, under both "
    "readings",
    "[engine][synchronize][semantics]") {
  // Master covers 85 m at 10 m/s in 8.5 s. Slow (maxSpeed 8 m/s, maxAcceleration 2 m/s^2) needs
  // 90 m from standstill (lane 1 of road 4, s = 95 down to s = 5): a constant acceleration of
  // 2 x 90 / 8.5^2 = 2.49 m/s^2 up to 21.2 m/s. Early (12 m/s, maxDeceleration 1 m/s^2) needs
  // 40 m ending at 4 m/s: two ramps through (4 x 40 / 8.5 - 12 - 4) / 2 = 1.41 m/s, braking at
  // 2.5 m/s^2. The action has no DynamicConstraints and the standard does not bound it by the
  // Performance: both arrive with the master, and nothing warns.
  FixtureRun run(engine_fixture("sync_beyond_performance.xosc"));
  run.run();
  CHECK(run.diagnostics().count(Severity::kWarning) == 0);
  const auto slow = passing_time(run, "Slow", "4", 5.0, -1);
  const auto early = passing_time(run, "Early", "2", 5.0, -1);
  const auto master = passing_time(run, "Master", "1", 5.0, -1);
  REQUIRE(slow);
  REQUIRE(early);
  REQUIRE(master);
  CHECK(std::abs(*slow - *master) <= run.sim().dt() + 1e-9);
  CHECK(std::abs(*early - *master) <= run.sim().dt() + 1e-9);
  CHECK(run.at(*master, "Slow").speed > 8.0);
  double slow_peak_acceleration = 0.0;
  double early_peak_deceleration = 0.0;
  for (const auto& [tick, states] : run.trace().ticks()) {
    slow_peak_acceleration =
        std::max(slow_peak_acceleration, states[run.entity("Slow")].acceleration);
    early_peak_deceleration =
        std::max(early_peak_deceleration, -states[run.entity("Early")].acceleration);
  }
  CHECK(slow_peak_acceleration > 2.0);
  CHECK(early_peak_deceleration > 1.0);
  CHECK(run.now("Early").speed == Approx(4.0));
  SECTION("esmini's reading keeps the appointment too") {
    // (Its steps travel by the speed at their end, so the trajectories differ by a few cm.)
    engine::SimulationOptions options;
    options.semantics = engine::Semantics::kEsmini;
    FixtureRun esmini(engine_fixture("sync_beyond_performance.xosc"), options);
    esmini.run();
    CHECK(esmini.diagnostics().count(Severity::kWarning) == 0);
    const auto esmini_master = passing_time(esmini, "Master", "1", 5.0, -1);
    const auto esmini_slow = passing_time(esmini, "Slow", "4", 5.0, -1);
    const auto esmini_early = passing_time(esmini, "Early", "2", 5.0, -1);
    REQUIRE(esmini_master);
    REQUIRE(esmini_slow);
    REQUIRE(esmini_early);
    CHECK(std::abs(*esmini_slow - *esmini_master) <= esmini.sim().dt() + 1e-9);
    CHECK(std::abs(*esmini_early - *esmini_master) <= esmini.sim().dt() + 1e-9);
  }
}

TEST_CASE("ASAM SynchronizedArrivalToIntersection: the two arrive within 0.01 s",
          "[engine][asam][synchronize]") {
  FixtureRun run(asam("SynchronizedArrivalToIntersection.xosc"), with_duration(60.0));
  run.run();
  const auto start = run.first("SyncActionNPC", TransitionKind::kStart);
  REQUIRE(start);
  // Ego's target: road 0 lane 1 (driven toward -s) s = 6; the NPC's: road 3 lane -1 s = 114.
  const auto ego = passing_time(run, "Ego", "0", 6.0, -1);
  const auto npc = passing_time(run, "NPC", "3", 114.0, 1);
  REQUIRE(ego);
  REQUIRE(npc);
  CHECK(std::abs(*ego - *npc) < 0.01);  // 0.0074 s: 5.7025 and 5.7098 s
  CHECK(run.first("SyncActionNPC", TransitionKind::kEnd));
  // Final speed: the master's (10 m/s) minus 3.
  CHECK(run.at(*npc, "NPC").speed == Approx(7.0).margin(0.05));
}

TEST_CASE("scenarios/intersection_sync.xosc: both vehicles enter the junction in the same step",
          "[engine][synchronize][scenarios]") {
  FixtureRun run(std::filesystem::path(CORSA_SOURCE_DIR) / "scenarios/intersection_sync.xosc");
  run.run();
  std::map<std::string, double> entered;
  for (const auto& [tick, states] : run.trace().ticks()) {
    for (const std::string name : {"Ego", "Npc"}) {
      const auto& road = states[run.entity(name)].road;
      if (road && run.sim().road_id(road->road).size() == 3 && !entered.count(name)) {
        entered[name] = run.sim().time_of(tick);  // connecting roads have ids 101..112
      }
    }
  }
  REQUIRE(entered.size() == 2);
  CHECK(std::abs(entered["Ego"] - entered["Npc"]) <= run.sim().dt() + 1e-9);
  // They meet in the junction: the stop trigger is their collision.
  CHECK(run.sim().end_reason() == engine::EndReason::kStopTrigger);
  CHECK(run.sim().collisions().size() == 1);
  CHECK(run.now("Npc").speed == Approx(8.0));
}

TEST_CASE("FollowTrajectoryAction drives polylines, clothoids and NURBS by their timing",
          "[engine][trajectory]") {
  FixtureRun run(engine_fixture("action_follow_trajectory.xosc"));
  run.run();
  CHECK(run.diagnostics().count(Severity::kWarning) == 0);
  const auto start = run.first("S0::Act0::G::M::E::A", TransitionKind::kStart);
  REQUIRE(start);
  // Timed polyline, relative timing with scale 2: the vertex at trajectory time 5 s (x = 60) is
  // reached 10 s after the start; half way there, x = 35 at 5 m/s.
  CHECK(run.at(*start + 10.0, "Timed").pose.x == Approx(60.0).margin(1e-6));
  CHECK(run.at(*start + 10.0, "Timed").pose.y == Approx(-1.75).margin(1e-6));
  CHECK(run.at(*start + 5.0, "Timed").pose.x == Approx(35.0).margin(1e-6));
  CHECK(run.at(*start + 5.0, "Timed").speed == Approx(5.0).margin(1e-6));
  // The last leg climbs 3.5 m over 50 m: on it the entity crosses into lane 1.
  CHECK(run.first("S0::Act0::G::M::E::A", TransitionKind::kEnd) ==
        Approx(*start + 20.0).margin(0.011));
  CHECK(run.now("Timed").road->lane == 1);
  // Clothoid: curvature from 0 rising by 0.0004 1/m^2 over 50 m: heading 0.5 rad at its end.
  const auto clothoid_end = run.first("S2::Act2::G::M::E::A", TransitionKind::kEnd);
  REQUIRE(clothoid_end);
  CHECK(run.at(*clothoid_end, "Clothoid").pose.h == Approx(0.5).margin(1e-3));
  CHECK(run.at(*clothoid_end, "Clothoid").speed == Approx(10.0));
  // Clothoid spline: 0 -> 0.02 -> 0 1/m over 2 x 25 m: heading 0.5 rad.
  const auto spline_end = run.first("S3::Act3::G::M::E::A", TransitionKind::kEnd);
  REQUIRE(spline_end);
  CHECK(run.at(*spline_end, "Spline").pose.h == Approx(0.5).margin(1e-3));
  // NURBS: a straight line along y = -12.25, the middle control point (x = 50) at 4 s, offset 1 s.
  CHECK(run.at(*start + 5.0, "Nurbs").pose.x == Approx(50.0).margin(0.05));
  CHECK(run.at(*start + 5.0, "Nurbs").pose.y == Approx(-12.25).margin(1e-6));
  // Absolute timing with offset 3 s: trajectory time t - 3, so x = 500 until 3 s, then 10 m/s
  // (50 m in 5 s): x = 525 at 5.5 s, the end at 8 s.
  CHECK(run.at(2.5, "Absolute").pose.x == Approx(500.0));
  CHECK(run.at(5.5, "Absolute").pose.x == Approx(525.0).margin(1e-6));
  CHECK(run.at(5.5, "Absolute").speed == Approx(10.0).margin(1e-6));
  CHECK(run.first("S6::Act6::G::M::E::A", TransitionKind::kEnd) == Approx(8.0).margin(0.011));
  // initialDistanceOffset 20: the path begins at x = 300, the entity at x = 320.
  CHECK(run.at(*start + 0.01, "Offset").pose.x == Approx(320.1).margin(0.02));
}

TEST_CASE("A NURBS trajectory's time is its fourth dimension, interpolated like its position",
          "[engine][trajectory]") {
  // x(u) = 10 + 80 u + 20 u^2 and, the control points' times being "the time dimension of the
  // control point", time(u) = 2 u (1 - u) 1 s + u^2 10 s = 2 u + 8 u^2 (weights 1). At 5 s:
  // u = 0.67539, x = 73.154; at 0.5 s: u = 0.15451, x = 22.838. (The middle point's time at its
  // Greville abscissa, interpolated in arc length, gave x = 79.444 at 5 s.)
  FixtureRun run(engine_fixture("trajectory_nurbs_timing.xosc"));
  run.run();
  const auto start = run.first("FollowAction", TransitionKind::kStart);
  REQUIRE(start);
  CHECK(run.at(*start + 0.5, "Car").pose.x == Approx(22.838).margin(0.01));
  CHECK(run.at(*start + 5.0, "Car").pose.x == Approx(73.154).margin(0.01));
  CHECK(run.at(*start + 10.0, "Car").pose.x == Approx(110.0).margin(1e-6));
  SECTION("esmini") {
    // esmini's NurbsShape: 101 samples of u (the control polygon is 100 m); the middle point's
    // basis function peaks at the sample u = 50 / 101, and time goes linearly in u from one
    // peak to the next: at 5 s u = 0.49505 + 4 / 9 x 0.50495 = 0.71947, x = 77.911.
    engine::SimulationOptions options;
    options.semantics = engine::Semantics::kEsmini;
    FixtureRun esmini(engine_fixture("trajectory_nurbs_timing.xosc"), options);
    esmini.run();
    CHECK(esmini.at(*start + 5.0, "Car").pose.x == Approx(77.911).margin(0.01));
    CHECK(esmini.at(*start + 10.0, "Car").pose.x == Approx(110.0).margin(1e-6));
  }
}

TEST_CASE("FollowTrajectoryAction in follow mode keeps its actor on the path, as esmini does",
          "[engine][trajectory]") {
  // followingMode follow leaves the driver model to the simulator; esmini moves its actor along
  // the path as in position mode, and so does Corsa under both readings.
  for (const engine::Semantics semantics :
       {engine::Semantics::kStandard, engine::Semantics::kEsmini}) {
    INFO(static_cast<int>(semantics));
    engine::SimulationOptions options;
    options.semantics = semantics;
    FixtureRun run(engine_fixture("action_follow_trajectory.xosc"), options);
    run.run();
    const auto start = run.first("S1::Act1::G::M::E::A", TransitionKind::kStart);
    const auto end = run.first("S1::Act1::G::M::E::A", TransitionKind::kEnd);
    REQUIRE(start);
    REQUIRE(end);
    // 50 + hypot(50, 3.5) = 100.12 m of path at 10 m/s (untimed: the entity keeps its speed),
    // ending in the step that passes the end.
    CHECK(*end - *start == Approx((50.0 + std::hypot(50.0, 3.5)) / 10.0).margin(0.011));
    double worst = 0.0;
    int around_corner = 0;
    for (double t = *start + 0.1; t < *end; t += 0.1) {
      const auto& pose = run.at(t, "Follow").pose;
      // The path: y = -8.75 up to x = 60, then rising 3.5 m over 50 m.
      const double path_y = pose.x <= 60.0 ? -8.75 : -8.75 + 3.5 * (pose.x - 60.0) / 50.0;
      worst = std::max(worst, std::abs(pose.y - path_y));
      around_corner += std::abs(pose.x - 60.0) < 5.0 ? 1 : 0;
    }
    CHECK(around_corner >= 9);  // the samples pass the corner at x = 60
    CHECK(worst < 1e-9);        // on the path, the corner too: no driver cutting it
    CHECK(run.at(*end, "Follow").pose.x == Approx(110.0).margin(1.0));
  }
}

TEST_CASE("A follow-mode walker whose path starts behind it walks the path from its start",
          "[engine][trajectory]") {
  // A pedestrian at (50, -8.75) facing +x walks, untimed at 1.5 m/s, a path that leads back
  // along -x to x = 40 and then across to (40, -1.75). On the path as esmini has it: it turns
  // to the path's heading at once and never goes beyond x = 50 (a pure-pursuit driver, which
  // Corsa's follow mode was before, turned on a circle out to x = 52).
  FixtureRun run(engine_fixture("action_follow_trajectory_turn_back.xosc"));
  run.run();
  const auto start = run.first("S::Act::G::M::E::Walk", TransitionKind::kStart);
  const auto end = run.first("S::Act::G::M::E::Walk", TransitionKind::kEnd);
  REQUIRE(start);
  REQUIRE(end);
  // 17 m at 1.5 m/s.
  CHECK(*end - *start == Approx(17.0 / 1.5).margin(0.11));
  for (double t = *start + 0.1; t < *end; t += 0.1) {
    const auto& pose = run.at(t, "Walker").pose;
    INFO(t);
    if (pose.y < -8.75 + 1e-9) {
      CHECK(pose.x <= 50.0 + 1e-9);
      CHECK(pose.x >= 40.0 - 1e-9);
      CHECK(pose.y == Approx(-8.75).margin(1e-9));
    } else {
      CHECK(pose.x == Approx(40.0).margin(1e-9));
    }
  }
  const auto& early = run.at(*start + 1.0, "Walker").pose;
  CHECK(early.x == Approx(48.5).margin(0.16));  // 1 s along -x, one step's speed at most off
  CHECK(std::abs(std::abs(early.h) - std::numbers::pi) < 1e-6);
  const auto& at_end = run.at(*end, "Walker").pose;
  CHECK(std::hypot(at_end.x - 40.0, at_end.y + 1.75) < 0.16);
  // Past the end it walks out along the last leg's direction (+y).
  const auto& later = run.at(*end + 2.0, "Walker").pose;
  CHECK(later.y - at_end.y > 2.5);
  CHECK(std::abs(later.h - 0.5 * std::numbers::pi) < 0.25);
}

TEST_CASE("A timed polyline whose last vertex repeats waits there until the last time",
          "[engine][trajectory]") {
  FixtureRun run(engine_fixture("action_follow_trajectory.xosc"));
  run.run();
  const auto start = run.first("S7::Act7::G::M::E::A", TransitionKind::kStart);
  const auto end = run.first("S7::Act7::G::M::E::A", TransitionKind::kEnd);
  REQUIRE(start);
  REQUIRE(end);
  // 20 m in 2 s, then the same point from trajectory time 2 to 3: standing for that second.
  CHECK(run.at(*start + 1.0, "Wait").pose.x == Approx(710.0).margin(1e-6));
  CHECK(run.at(*start + 1.0, "Wait").speed == Approx(10.0).margin(1e-6));
  CHECK(run.at(*start + 2.5, "Wait").pose.x == Approx(720.0).margin(1e-6));
  CHECK(run.at(*start + 2.5, "Wait").speed == Approx(0.0).margin(1e-6));
  CHECK(*end - *start == Approx(3.0).margin(0.011));
  // Then it stands where the trajectory left it, at the speed its last step gave it.
  CHECK(run.now("Wait").pose.x == Approx(720.0).margin(1e-6));
  CHECK(run.now("Wait").speed == 0.0);
}

TEST_CASE("A timed path that ends within a step leaves the car at the path's speed",
          "[engine][trajectory]") {
  // 15.68 m in 1.96 s (8 m/s), in followingMode position and follow, ending 0.06 s into the step
  // to 2 s at dt 0.1 s. That step goes on past the end, so the lane carries both on at 8 m/s,
  // not at the 4.8 m/s of the 0.48 m the step had left on the path.
  engine::SimulationOptions options;
  options.dt = 0.1;
  FixtureRun run(engine_fixture("trajectory_ends_mid_step.xosc"), options);
  run.run();
  for (const char* name : {"Position", "Follow"}) {
    INFO(name);
    CHECK(run.at(2.0, name).pose.x == Approx(26.0).margin(1e-9));
    CHECK(run.at(2.0, name).speed == Approx(8.0).margin(1e-9));
    CHECK(run.at(3.0, name).pose.x == Approx(34.0).margin(1e-9));
    CHECK(run.at(3.0, name).speed == Approx(8.0).margin(1e-9));
  }
}

TEST_CASE("A speed that turns negative along a path drives back toward its start, facing on",
          "[engine][trajectory]") {
  // Back: 2 m/s slowing at 2 m/s^2 to -2 m/s on an untimed 20 m path along +x; each step
  // travels its end speed: 0.9 m out at 1 s, back at the start at 1.9 s, facing +x throughout.
  // Reverse: -2 m/s from the start, so the path is driven forward in reverse gear, facing -x;
  // its vertices' h = 0 would back it off the path's start at once and are set aside.
  engine::SimulationOptions options;
  options.dt = 0.1;
  FixtureRun run(engine_fixture("trajectory_speed_turns_negative.xosc"), options);
  run.run();
  CHECK(all_text(run.diagnostics())
            .find("trajectory_speed_turns_negative.xosc:64: warning: trajectory 'reverse_line': "
                  "the vertex's heading faces along the path, which at a negative speed drives "
                  "off the path where the actor starts") != std::string::npos);
  CHECK(run.at(1.0, "Back").pose.x == Approx(0.9).margin(1e-9));
  CHECK(run.at(1.5, "Back").pose.x == Approx(0.6).margin(1e-9));
  CHECK(run.at(1.5, "Back").speed == Approx(-1.0).margin(1e-9));
  CHECK(run.at(1.5, "Back").pose.h == Approx(0.0).margin(1e-12));
  CHECK(run.at(1.9, "Back").pose.x == Approx(0.0).margin(1e-9));
  CHECK(run.at(3.0, "Back").pose.x == Approx(0.0).margin(1e-9));  // on no road it stands
  CHECK(run.at(0.5, "Reverse").pose.x == Approx(1.0).margin(1e-9));
  CHECK(run.at(0.5, "Reverse").pose.h == Approx(std::numbers::pi).margin(1e-9));
}

TEST_CASE("A vertex heading that would drive the actor off its path at once is set aside",
          "[engine][trajectory]") {
  // Turned faces -x at +2 m/s on a path from x = 20 to x = 0 whose vertices state h = 0.
  engine::SimulationOptions options;
  options.dt = 0.1;
  FixtureRun run(engine_fixture("trajectory_filler_heading.xosc"), options);
  run.run();
  CHECK(run.at(1.0, "Turned").pose.x == Approx(18.0).margin(1e-9));
  CHECK(run.at(1.0, "Turned").pose.h == Approx(std::numbers::pi).margin(1e-9));
  CHECK(run.at(1.0, "Turned").speed == Approx(2.0).margin(1e-12));
  CHECK(run.at(5.0, "Turned").pose.x == Approx(10.0).margin(1e-9));
  CHECK(run.at(5.0, "Turned").pose.h == Approx(std::numbers::pi).margin(1e-9));
  CHECK(all_text(run.diagnostics())
            .find("trajectory_filler_heading.xosc:37: warning: trajectory 'westward': the "
                  "vertex's heading faces against the path, which at a positive speed drives off "
                  "the path where the actor starts; the trajectory's stated headings are ignored "
                  "and the actor faces along the path") != std::string::npos);
  // esmini turns the car to the stated h = 0 and the action ends at once: it stands at x = 20.
  options.semantics = engine::Semantics::kEsmini;
  FixtureRun esmini(engine_fixture("trajectory_filler_heading.xosc"), options);
  esmini.run();
  CHECK(esmini.at(1.0, "Turned").pose.x == Approx(20.0).margin(1e-9));
  CHECK(esmini.at(1.0, "Turned").pose.h == Approx(0.0).margin(1e-9));
  CHECK(esmini.at(5.0, "Turned").pose.x == Approx(20.0).margin(1e-9));
}

TEST_CASE("A timed path whose vertices state a heading against it is driven in reverse gear",
          "[engine][trajectory]") {
  // Turned faces -x at +2 m/s; its path runs from x = 20 at 0 s to x = 0 at 10 s and its
  // vertices state h = 0. The times set the motion and the stated heading the orientation, under
  // both readings: backwards along -x at -2 m/s, facing +x, nothing set aside.
  for (const engine::Semantics semantics :
       {engine::Semantics::kStandard, engine::Semantics::kEsmini}) {
    engine::SimulationOptions options;
    options.dt = 0.1;
    options.semantics = semantics;
    FixtureRun run(engine_fixture("trajectory_timed_filler_heading.xosc"), options);
    run.run();
    CHECK(run.at(1.0, "Turned").pose.x == Approx(18.0).margin(1e-9));
    CHECK(run.at(1.0, "Turned").pose.h == Approx(0.0).margin(1e-9));
    CHECK(run.at(1.0, "Turned").speed == Approx(-2.0).margin(1e-9));
    CHECK(run.at(5.0, "Turned").pose.x == Approx(10.0).margin(1e-9));
    CHECK(run.at(5.0, "Turned").pose.h == Approx(0.0).margin(1e-9));
    CHECK(run.at(10.0, "Turned").pose.x == Approx(0.0).margin(1e-9));
    CHECK(all_text(run.diagnostics()).find("stated headings are ignored") == std::string::npos);
  }
}

TEST_CASE("Trajectory vertices stating a heading set the way the actor faces and drives",
          "[engine][trajectory]") {
  // Straight 20 m paths along +x; see the fixture for each case.
  engine::SimulationOptions options;
  options.dt = 0.1;
  FixtureRun run(engine_fixture("trajectory_stated_heading.xosc"), options);
  run.run();
  // Stated along the path, started at its end at -2 m/s: backwards toward the start, facing +x.
  CHECK(run.at(0.5, "AlongBack").pose.x == Approx(19.0).margin(1e-9));
  CHECK(run.at(0.5, "AlongBack").pose.h == Approx(0.0).margin(1e-12));
  CHECK(run.at(0.5, "AlongBack").speed == Approx(-2.0).margin(1e-9));
  // Stated against the path, started at its end at +2 m/s: forwards toward the start, facing -x.
  CHECK(run.at(0.5, "AgainstEnd").pose.x == Approx(19.0).margin(1e-9));
  CHECK(run.at(0.5, "AgainstEnd").pose.h == Approx(std::numbers::pi).margin(1e-9));
  // Timed, stated against the path: at the times' places, in reverse gear.
  CHECK(run.at(1.0, "TimedAgainst").pose.x == Approx(2.0).margin(1e-9));
  CHECK(run.at(1.0, "TimedAgainst").pose.h == Approx(std::numbers::pi).margin(1e-9));
  CHECK(run.at(1.0, "TimedAgainst").speed == Approx(-2.0).margin(1e-9));
  // A timed path that doubles back, every vertex stating h = pi: out in reverse, back forwards.
  CHECK(run.at(2.5, "TimedBack").pose.x == Approx(5.0).margin(1e-9));
  CHECK(run.at(2.5, "TimedBack").speed == Approx(-2.0).margin(1e-9));
  CHECK(run.at(2.5, "TimedBack").pose.h == Approx(std::numbers::pi).margin(1e-9));
  CHECK(run.at(7.5, "TimedBack").pose.x == Approx(5.0).margin(1e-9));
  CHECK(run.at(7.5, "TimedBack").speed == Approx(2.0).margin(1e-9));
  CHECK(run.at(7.5, "TimedBack").pose.h == Approx(std::numbers::pi).margin(1e-9));
  // A Timing over vertices without times leaves the speed to the speed actions, which go on.
  CHECK(all_text(run.diagnostics())
            .find("'timing_no_times' has fewer than two times; it is "
                  "followed at the speed the longitudinal actions give") != std::string::npos);
  CHECK(run.at(1.0, "TimingNoTimes").speed == Approx(3.0).margin(1e-9));
  CHECK(run.at(1.0, "TimingNoTimes").pose.x == Approx(2.55).margin(1e-9));
}

TEST_CASE("A path whose vertices state a heading says which way the car faces on it",
          "[engine][trajectory]") {
  // Both cars start at the end of a 20 m path along +x (initialDistanceOffset 20). Backs: the
  // vertices face +x and the speed is -2 m/s, so it backs toward the start facing +x. Turned:
  // the vertices face -x and the speed is +2 m/s, so it drives forward toward the start facing
  // -x. Both reach the start at 10 s, where the action ends and, with no road, they stand.
  engine::SimulationOptions options;
  options.dt = 0.1;
  FixtureRun run(engine_fixture("trajectory_first_vertex_heading.xosc"), options);
  run.run();
  CHECK(run.at(0.5, "Backs").pose.x == Approx(19.0).margin(1e-9));
  CHECK(run.at(0.5, "Backs").pose.h == Approx(0.0).margin(1e-12));
  CHECK(run.at(0.5, "Backs").speed == Approx(-2.0).margin(1e-12));
  CHECK(run.at(0.5, "Turned").pose.x == Approx(19.0).margin(1e-9));
  CHECK(run.at(0.5, "Turned").pose.h == Approx(std::numbers::pi).margin(1e-9));
  CHECK(run.at(0.5, "Turned").speed == Approx(2.0).margin(1e-12));
  CHECK(run.at(11.0, "Backs").pose.x == Approx(0.0).margin(1e-9));
  CHECK(run.at(11.0, "Turned").pose.x == Approx(0.0).margin(1e-9));
}

TEST_CASE("With esmini's refpoint_x_offset the body trails the reference point along its path",
          "[engine][trajectory][esmini]") {
  engine::SimulationOptions options = with_duration(20.0);
  options.dt = 0.1;
  FixtureRun run(engine_fixture("refpoint_trail.xosc"), options);
  run.run();
  const auto angle_gap = [](double a, double b) {
    return std::abs(std::remainder(a - b, 2.0 * std::numbers::pi));
  };
  SECTION("the rows of esmini's smoke test for follow_trajectory_by_front_axle") {
    // test_refpoint_x_offset: time, x, y, h (esmini rounds to 3 decimals).
    const double rows[][4] = {
        {0.0, 10.000, -3.000, 6.056}, {0.1, 10.238, -2.857, 6.117}, {2.4, 15.717, 0.430, 0.446},
        {2.5, 15.955, 0.573, 0.454},  {4.2, 20.004, 2.998, 0.520},  {4.3, 20.242, 2.855, 0.442},
        {8.4, 29.993, -2.994, 5.771}, {8.5, 29.776, -2.821, 5.787}, {10.7, 25.004, 0.997, 0.619},
        {10.8, 25.272, 1.027, 0.578}, {12.6, 30.247, 1.525, 0.197}, {12.7, 30.525, 1.525, 0.181},
        {16.0, 39.691, 1.525, 0.010}};
    for (const auto& row : rows) {
      INFO("t = " << row[0]);
      const engine::Pose& pose = run.at(row[0], "Front").pose;
      CHECK(pose.x == Approx(row[1]).margin(0.001));
      CHECK(pose.y == Approx(row[2]).margin(0.001));
      CHECK(angle_gap(pose.h, row[3]) < 0.001);
    }
  }
  SECTION("each step the axle 2.98 m behind moves straight toward the reference point") {
    for (const char* name : {"Front", "Placed"}) {
      INFO(name);
      for (double t = 0.1; t < 17.95; t += 0.1) {
        INFO("t = " << t);
        const engine::Pose& before = run.at(t - 0.1, name).pose;
        const engine::Pose& after = run.at(t, name).pose;
        const double axle_x = before.x - 2.98 * std::cos(before.h);
        const double axle_y = before.y - 2.98 * std::sin(before.h);
        CHECK(angle_gap(after.h, std::atan2(after.y - axle_y, after.x - axle_x)) < 1e-9);
      }
    }
  }
  SECTION("the reference point keeps the path; a teleport gives the body its heading") {
    CHECK(run.at(0.0, "Placed").pose.h == Approx(0.3).margin(1e-12));
    for (const double t : {0.0, 4.3, 9.0, 16.0}) {
      INFO("t = " << t);
      CHECK(run.at(t, "Plain").pose.x == Approx(run.at(t, "Front").pose.x + 100.0).margin(1e-9));
      CHECK(run.at(t, "Placed").pose.y == Approx(run.at(t, "Front").pose.y).margin(1e-9));
    }
    // Without the property the car faces the segment it drives (-0.540 rad on the second).
    CHECK(run.at(4.3, "Plain").pose.h == Approx(-0.5404195).margin(1e-6));
  }
  SECTION("a value that is no number is ignored with a warning at the property") {
    CHECK_THAT(all_text(run.diagnostics()),
               Catch::Contains("refpoint_trail.xosc:66: warning: vehicle 'Bad': property "
                               "refpoint_x_offset '2.98m' is no number >= 0"));
    for (const double t : {0.0, 4.3, 9.0, 16.0}) {
      INFO("t = " << t);
      CHECK(run.at(t, "Bad").pose.h == run.at(t, "Plain").pose.h);
      CHECK(run.at(t, "Bad").pose.x == Approx(run.at(t, "Plain").pose.x + 200.0).margin(1e-9));
    }
  }
}

TEST_CASE("ASAM TrailerConnect: the car reverses along the quarter circle facing forward",
          "[engine][asam][trajectory]") {
  FixtureRun run(asam("TrailerConnect.xosc"), with_duration(120.0));
  run.run();
  const auto start = run.first("ReverseTrajectoryAction", TransitionKind::kStart);
  const auto end = run.first("ReverseTrajectoryAction", TransitionKind::kEnd);
  REQUIRE(start);
  REQUIRE(end);
  // A quarter circle of radius 12 m (18.85 m) at 4 m/s backwards: 4.71 s; the car turns by
  // pi / 2 while it backs up, its heading against its path.
  CHECK(*end - *start == Approx(4.71).margin(0.02));
  CHECK(run.at(*start + 1.0, "Car").speed == Approx(-4.0));
  const double turned = run.at(*end, "Car").pose.h - run.at(*start, "Car").pose.h;
  CHECK(std::abs(std::remainder(turned, 2.0 * 3.141592653589793)) == Approx(1.5708).margin(0.01));
}

TEST_CASE("LongitudinalDistanceAction closes to 20 m behind within its deceleration limit",
          "[engine][distance]") {
  FixtureRun run(engine_fixture("action_distance_profile.xosc"));
  run.run();
  const auto end = run.first("S0::Act0::G::M::E::A", TransitionKind::kEnd);
  REQUIRE(end);
  const auto& lead = run.at(*end, "Lead");
  const auto& chaser = run.at(*end, "Chaser");
  CHECK(lead.pose.x - chaser.pose.x == Approx(20.0).margin(0.15));
  CHECK(chaser.speed == Approx(10.0).margin(0.06));
  for (const auto& [tick, states] : run.trace().ticks()) {
    CHECK(states[run.entity("Chaser")].acceleration >= -4.0 - 1e-9);
    CHECK(states[run.entity("Chaser")].acceleration <= 2.0 + 1e-9);
    CHECK(states[run.entity("Lead")].pose.x > states[run.entity("Chaser")].pose.x + 4.5);
  }
}

TEST_CASE("A continuous LongitudinalDistanceAction keeps a 1.5 s free-space time gap ahead",
          "[engine][distance]") {
  FixtureRun run(engine_fixture("action_distance_profile.xosc"));
  run.run();
  // Gap (lane 1, driving +s) leads Lead by 1.5 s x its speed between the boxes (4.5 m long):
  // settled at Lead's 10 m/s, 15 m + 4.5 m between reference points. Continuous: never ends.
  CHECK(run.now("Gap").speed == Approx(10.0).margin(0.05));
  CHECK(run.now("Gap").pose.x - run.now("Lead").pose.x == Approx(19.5).margin(0.3));
  CHECK_FALSE(run.first("S4::Act4::G::M::E::A", TransitionKind::kEnd));
  for (const auto& [tick, states] : run.trace().ticks()) {
    CHECK(states[run.entity("Gap")].speed >= 0.0);
    CHECK(states[run.entity("Gap")].pose.x > states[run.entity("Lead")].pose.x + 4.5);
  }
}

TEST_CASE("LateralDistanceAction moves 2.5 m right of the reference at its lateral speed limit",
          "[engine][distance]") {
  FixtureRun run(engine_fixture("action_distance_profile.xosc"));
  run.run();
  const auto start = run.first("S1::Act1::G::M::E::A", TransitionKind::kStart);
  const auto end = run.first("S1::Act1::G::M::E::A", TransitionKind::kEnd);
  REQUIRE(start);
  REQUIRE(end);
  CHECK(run.at(*end, "Lead").pose.y - run.at(*end, "Side").pose.y == Approx(2.5).margin(0.03));
  // 1 m at no more than 0.5 m/s: at least 2 s.
  CHECK(*end - *start > 2.0);
  for (const auto& [tick, states] : run.trace().ticks()) {
    CHECK(std::abs(states[run.entity("Side")].lateral_speed) <= 0.5 + 1e-9);
  }
}

TEST_CASE("Distance actions without DynamicConstraints reach their distance at once",
          "[engine][distance]") {
  FixtureRun run(engine_fixture("action_distance_unlimited.xosc"));
  run.run();
  // Init, before time starts: 25 m between the 4.5 m boxes (29.5 m between reference points),
  // at Lead's speed; Side 2.5 m right of Lead (lane -2's centre at -5.25 m).
  const auto& lead0 = run.at(0.0, "Lead");
  CHECK(lead0.pose.x - run.at(0.0, "Follower").pose.x == Approx(29.5).margin(1e-6));
  CHECK(run.at(0.0, "Follower").speed == Approx(10.0));
  CHECK(run.at(0.0, "Side").pose.y == Approx(lead0.pose.y - 2.5).margin(1e-6));
  // Non-continuous: over once placed; the Follower drives on at 10 m/s while Lead speeds up.
  CHECK(run.at(1.0, "Follower").pose.x == Approx(80.5).margin(1e-6));
  CHECK(run.now("Follower").speed == Approx(10.0));
  // Continuous from 1 s: Tail is 15 m behind at once and stays so while Lead speeds up at
  // 4 m/s^2, twice Tail's Performance (unlimited dynamics are not held to it).
  const auto start = run.first("S0::Act0::G::M::E::A", TransitionKind::kStart);
  REQUIRE(start);
  for (const auto& [tick, states] : run.trace().ticks()) {
    if (run.sim().time_of(tick) < *start + 0.015) continue;
    const double gap = states[run.entity("Lead")].pose.x - states[run.entity("Tail")].pose.x;
    CHECK(gap == Approx(15.0).margin(0.01));
  }
  CHECK(run.now("Tail").speed == Approx(30.0));
}

TEST_CASE("SpeedProfileAction goes through its entries, linearly or smoothly, within limits",
          "[engine][speed_profile]") {
  FixtureRun run(engine_fixture("action_distance_profile.xosc"));
  run.run();
  const auto start = run.first("S2::Act2::G::M::E::A", TransitionKind::kStart);
  const auto end = run.first("S2::Act2::G::M::E::A", TransitionKind::kEnd);
  REQUIRE(start);
  REQUIRE(end);
  // 0 -> 10 m/s in 5 s (linear: 5 m/s at 2.5 s), then 10 -> 20 at maxAcceleration 2: 5 s more.
  CHECK(run.at(*start + 2.5, "Profile").speed == Approx(5.0).margin(1e-6));
  CHECK(run.at(*start + 5.0, "Profile").speed == Approx(10.0).margin(1e-6));
  CHECK(run.at(*start + 7.5, "Profile").speed == Approx(15.0).margin(0.03));
  CHECK(*end - *start == Approx(10.0).margin(0.02));
  CHECK(run.now("Profile").speed == Approx(20.0));
  // follow: a smooth (cubic) first entry: slower at first, the same half way.
  CHECK(run.at(*start + 1.25, "Smooth").speed == Approx(1.5625).margin(1e-6));
  CHECK(run.at(*start + 2.5, "Smooth").speed == Approx(5.0).margin(1e-6));
  for (const auto& [tick, states] : run.trace().ticks()) {
    CHECK(states[run.entity("Profile")].acceleration <= 2.0 + 1e-9);
    CHECK(states[run.entity("Smooth")].acceleration <= 4.0 + 1e-9);
  }
}

TEST_CASE("A jerk-limited speed plan rounds the corners of the profile's lines",
          "[engine][speed_profile]") {
  using engine::detail::JerkLimits;
  using engine::detail::JerkProfile;
  const JerkLimits limits{5.0, 10.0, 4.0, 3.0};  // m/s^2 up, down; m/s^3 up, down
  // Largest change of acceleration (m/s^3) between 1 ms samples, up (> 0) and down (< 0).
  const auto jerk_range = [](const JerkProfile& plan) {
    double up = 0.0;
    double down = 0.0;
    const double h = 1e-3;
    for (double t = h; t + h <= plan.end_time() + 1.0; t += h) {
      const double jerk =
          (plan.speed_at(t + h) - 2.0 * plan.speed_at(t) + plan.speed_at(t - h)) / (h * h);
      up = std::max(up, jerk);
      down = std::min(down, jerk);
    }
    return std::make_pair(up, down);
  };
  SECTION("several entries: parallel to the first line, on the later ones, late to the last") {
    // From rest: 10 m/s at 4 s, 4 m/s at 8 s, 8 m/s at 10 s (slopes 2.5, -1.5, 2 m/s^2).
    const JerkProfile plan({{0.0, 0.0}, {4.0, 10.0}, {8.0, 4.0}, {10.0, 8.0}}, 0.0, limits);
    // 0 to 2.5 m/s^2 takes 0.625 s at 4 m/s^3: 0.78125 m/s then, 0.78125 m/s below the line.
    CHECK(plan.speed_at(0.625) == Approx(0.78125).margin(1e-12));
    CHECK(plan.speed_at(2.0) == Approx(5.0 - 0.78125).margin(1e-12));
    // The corner onto -1.5 m/s^2 (3 m/s^3 down, 4/3 s long) is centred where that parallel
    // line, 2.5 t - 0.78125, crosses the second, 16 - 1.5 t: t = 16.78125 / 4.
    const double corner = 16.78125 / 4.0;
    const double start = corner - 2.0 / 3.0;
    const double tau = 4.0 - start;
    CHECK(plan.speed_at(4.0) ==
          Approx(2.5 * start - 0.78125 + 2.5 * tau - 1.5 * tau * tau).margin(1e-9));
    CHECK(plan.speed_at(4.0) == Approx(8.885).margin(1e-3));  // esmini's row at 6.00 s
    // On the second line itself between its corners, and 8 m/s from 10 + (2 / 3) / 2 s.
    CHECK(plan.speed_at(7.0) == Approx(5.5).margin(1e-12));
    CHECK(plan.end_time() == Approx(10.0 + 1.0 / 3.0).margin(1e-12));
    CHECK(plan.speed_at(plan.end_time()) == 8.0);
    CHECK(plan.speed_at(12.0) == 8.0);
    const auto [up, down] = jerk_range(plan);
    CHECK(up <= 4.0 + 1e-3);
    CHECK(down >= -3.0 - 1e-3);
  }
  SECTION("one entry the limits allow is reached on time") {
    const JerkProfile plan({{0.0, 10.0}, {5.0, 13.0}}, 0.0, limits);
    CHECK(plan.end_time() == Approx(5.0).margin(1e-9));
    CHECK(plan.speed_at(5.0) == 13.0);
    // Ramps to A and back (c = 1/4 + 1/3 s^2/m per m/s^2 of A) with A held between: 3 m/s in
    // 5 s gives A^2 c / 2 + A (5 - A c) = 3, A = (5 - sqrt(25 - 6 c)) / c = 0.6227 m/s^2.
    const double c = 1.0 / 4.0 + 1.0 / 3.0;
    const double peak = (5.0 - std::sqrt(25.0 - 6.0 * c)) / c;
    CHECK(plan.speed_at(3.0) - plan.speed_at(2.0) == Approx(peak).margin(1e-9));
  }
  SECTION("one entry the limits do not allow on time is reached as soon as they do") {
    // 10 m/s down: a ramp to the peak deceleration A at 3 m/s^3 and back at 4 m/s^3 gains
    // A^2 (1/3 + 1/4) / 2, so A = sqrt(240 / 7) = 5.855 m/s^2, reached after A (1/3 + 1/4).
    const JerkProfile plan({{0.0, 15.0}, {3.0, 5.0}}, 0.0, limits);
    const double peak = std::sqrt(240.0 / 7.0);
    CHECK(plan.end_time() == Approx(peak * 7.0 / 12.0).margin(1e-9));
    CHECK(plan.speed_at(plan.end_time()) == 5.0);
    const auto [up, down] = jerk_range(plan);
    CHECK(up <= 4.0 + 1e-3);
    CHECK(down >= -3.0 - 1e-3);
  }
  SECTION("the peak acceleration is held to the limit, and a start accelerating is kept") {
    // 0 to 40 m/s: a triangle would peak above 5 m/s^2, so 5 m/s^2 is held in between.
    const JerkProfile plan({{0.0, 0.0}, {1.0, 40.0}}, 0.0, limits);
    const double ramps = 5.0 / 4.0 + 5.0 / 3.0;
    CHECK(plan.end_time() == Approx(ramps + (40.0 - 12.5 * (1.0 / 4.0 + 1.0 / 3.0)) / 5.0));
    CHECK(plan.speed_at(plan.end_time()) == 40.0);
    // Already at 2 m/s^2: the plan starts with that slope.
    const JerkProfile moving({{0.0, 10.0}, {4.0, 20.0}}, 2.0, limits);
    CHECK((moving.speed_at(0.01) - 10.0) / 0.01 == Approx(2.0).margin(0.05));
    CHECK(moving.speed_at(moving.end_time()) == 20.0);
  }
  SECTION("a rate not given is unbounded: the acceleration may jump that way") {
    const double inf = std::numeric_limits<double>::infinity();
    const JerkProfile plan({{0.0, 0.0}, {4.0, 10.0}, {6.0, 10.0}}, 0.0, {5.0, 10.0, inf, 3.0});
    CHECK(plan.speed_at(1.0) == Approx(2.5).margin(1e-12));  // on the first line at once
    CHECK(plan.end_time() == Approx(4.0 + 2.5 / 3.0 / 2.0).margin(1e-12));
    for (double t = 0.0; t < 6.0; t += 0.01) {
      CHECK(std::isfinite(plan.speed_at(t)));
    }
    CHECK(plan.speed_at(6.0) == 10.0);
  }
}

TEST_CASE("SpeedProfileAction in followingMode follow keeps its jerk limits",
          "[engine][speed_profile]") {
  FixtureRun run(engine_fixture("speed_profile_jerk.xosc"));
  run.run();
  const auto corners = run.first("corners", TransitionKind::kStart);
  const auto corners_end = run.first("corners", TransitionKind::kEnd);
  const auto on_time = run.first("on_time", TransitionKind::kStart);
  const auto on_time_end = run.first("on_time", TransitionKind::kEnd);
  const auto late = run.first("late", TransitionKind::kStart);
  const auto late_end = run.first("late", TransitionKind::kEnd);
  REQUIRE(corners);
  REQUIRE(corners_end);
  REQUIRE(on_time);
  REQUIRE(on_time_end);
  REQUIRE(late);
  REQUIRE(late_end);
  const double dt = 0.01;
  // The profile's lines, rounded: 8.885 m/s at its second entry (esmini's speed-profile_test row
  // at 6.00 s, its action started at 2 s), 5.5 m/s on the second line, 8 m/s 1/3 s after the
  // last entry's time.
  CHECK(run.at(*corners + 4.0, "Car").speed == Approx(8.885).margin(1e-3));
  CHECK(run.at(*corners + 7.0, "Car").speed == Approx(5.5).margin(1e-9));
  CHECK(*corners_end - *corners == Approx(10.0 + 1.0 / 3.0).margin(dt));
  CHECK(run.at(*corners_end, "Car").speed == Approx(8.0).margin(1e-9));
  // 13 m/s on time, 5 s on; then 3 m/s late, after sqrt(240 / 7) 7 / 12 = 3.416 s, not 3 s (the
  // Performance's rates, no DynamicConstraints; the small acceleration left from the last step
  // before, 0.015 m/s^2, adds 0.005 s).
  CHECK(*on_time_end - *on_time == Approx(5.0).margin(dt));
  CHECK(run.at(*on_time_end, "Car").speed == Approx(13.0).margin(1e-9));
  CHECK(*late_end - *late == Approx(std::sqrt(240.0 / 7.0) * 7.0 / 12.0).margin(2.0 * dt));
  CHECK(run.now("Car").speed == Approx(3.0).margin(1e-9));
  // The acceleration changes by at most 4 m/s^3 up and 3 m/s^3 down, and stays within 5 / 10.
  double previous = 0.0;
  for (const auto& [tick, states] : run.trace().ticks()) {
    const double a = states[run.entity("Car")].acceleration;
    CHECK(a <= 5.0 + 1e-9);
    CHECK(a >= -10.0 - 1e-9);
    CHECK((a - previous) / dt <= 4.0 + 1e-6);
    CHECK((a - previous) / dt >= -3.0 - 1e-6);
    previous = a;
  }
}

TEST_CASE("A SpeedProfileAction entry of no duration takes no step of its own",
          "[engine][speed_profile]") {
  // {0 m/s at once, then 10 m/s in 5 s} from rest at dt 0.1 s: the ramp starts in the first
  // step (0.2 m/s at 0.1 s, 10 m/s at 5 s) and a step travels its end speed times dt, so the
  // car has gone 0.1 * (0.2 + 0.4 + ... + 10) = 25.5 m at 5 s (esmini's rising_edge rows).
  engine::SimulationOptions options;
  options.dt = 0.1;
  FixtureRun run(engine_fixture("speed_profile_jump.xosc"), options);
  run.run();
  CHECK(run.at(0.1, "Car").speed == Approx(0.2).margin(1e-9));
  CHECK(run.at(5.0, "Car").speed == Approx(10.0).margin(1e-9));
  CHECK(run.at(5.0, "Car").pose.x - run.at(0.0, "Car").pose.x == Approx(25.5).margin(1e-9));
}

}  // namespace
}  // namespace corsa::test
