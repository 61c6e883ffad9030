// Readings the standard leaves to the simulator, and esmini's where it differs
// (SimulationOptions::semantics, `corsa run --semantics esmini`; docs/openscenario.md,
// "Differences from esmini"), on focused scenarios whose values are derived by hand.

#include <cmath>
#include <numbers>

#include "engine_fixture.h"
#include "positions/position_common.h"

namespace corsa::test {
namespace {

using Catch::Detail::Approx;

engine::SimulationOptions esmini_reading() {
  engine::SimulationOptions options;
  options.semantics = engine::Semantics::kEsmini;
  return options;
}

}  // namespace

TEST_CASE("A step travels the speed at its end times dt, under either reading",
          "[engine][semantics]") {
  // From s = 10 the car speeds up linearly from 0 to 10 m/s in 2 s (a = 5 m/s^2), then holds
  // 10 m/s. Each step moves by the speed at its end: sum over k = 1..n of v(k dt) dt, which
  // exceeds the exact integral (s(1) = 12.5, s(2) = 20, s(4) = 40) by dt/2 times the speed gained,
  // 0.01 / 2 * 5 = 0.025 m after 1 s and 0.01 / 2 * 10 = 0.05 m from 2 s on, as esmini's.
  const auto check = [](FixtureRun& run) {
    run.run();
    CHECK(run.at(1.0, "Car").road->s == Approx(12.525).margin(1e-9));
    CHECK(run.at(2.0, "Car").road->s == Approx(20.05).margin(1e-9));
    CHECK(run.at(4.0, "Car").road->s == Approx(40.05).margin(1e-9));
    CHECK(run.at(2.0, "Car").speed == Approx(10.0).margin(1e-12));
  };
  SECTION("standard") {
    FixtureRun run(engine_fixture("semantics_speed_travel.xosc"));
    check(run);
  }
  SECTION("esmini") {
    FixtureRun run(engine_fixture("semantics_speed_travel.xosc"), esmini_reading());
    check(run);
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

TEST_CASE("During a lane change the path is as long as the speed gives, under either reading",
          "[engine][semantics]") {
  // At 10 m/s the car changes 3.5 m to the right linearly in 1 s: 0.035 m across in each step of
  // 0.1 m. The path is 0.1 m a step, so the lane gets sqrt(0.1^2 - 0.035^2) = 0.0936750 m of it
  // for the 100 steps of the change: s(4) = 50 - 100 * (0.1 - 0.0936750) = 49.3674970 (not 50,
  // as if the lane were followed at the speed with the lateral motion on top), and the heading
  // turns by asin(0.35) = 0.3575711 rad toward the new lane, as esmini's.
  const auto check = [](FixtureRun& run) {
    run.run();
    CHECK(run.at(4.0, "Car").road->s ==
          Approx(50.0 - 100.0 * (0.1 - std::sqrt(0.008775))).margin(1e-6));
    CHECK(run.at(1.5, "Car").pose.h == Approx(-std::asin(0.35)).margin(1e-9));
    CHECK(run.at(4.0, "Car").road->lane == -2);
  };
  SECTION("standard") {
    FixtureRun run(engine_fixture("semantics_lateral_travel.xosc"));
    check(run);
  }
  SECTION("esmini") {
    FixtureRun run(engine_fixture("semantics_lateral_travel.xosc"), esmini_reading());
    check(run);
  }
}

TEST_CASE("A SpeedAction beyond the Performance is exact, or esmini's stretched to its limits",
          "[engine][semantics]") {
  // 10 m/s; Performance 2 m/s^2 up, 4 m/s^2 down, 15 m/s. At t1 = 1 s: linear to 20 m/s in 2 s;
  // at t2 = 5 s: cubic to 5 m/s in 1 s (3 x 15 / 2 = 22.5 m/s^2 at its steepest).
  SECTION("standard") {
    // The TransitionDynamics hold as written: 15 m/s half way, 20 m/s at t1 + 2; then 12.5 m/s
    // half way down and 5 m/s at t2 + 1.
    FixtureRun run(engine_fixture("semantics_performance.xosc"));
    run.run();
    const auto up = run.first("up", engine::TransitionKind::kStart);
    const auto down = run.first("down", engine::TransitionKind::kStart);
    REQUIRE(up);
    REQUIRE(down);
    CHECK(run.at(*up + 1.0, "Car").speed == Approx(15.0).margin(1e-9));
    CHECK(run.at(*up + 2.0, "Car").speed == Approx(20.0).margin(1e-9));
    CHECK(run.at(*down + 0.5, "Car").speed == Approx(12.5).margin(1e-9));
    CHECK(run.at(*down + 1.0, "Car").speed == Approx(5.0).margin(1e-9));
    // esmini's DefaultController is ours: no substitute.
    CHECK(run.sim().controller_substitute(run.entity("Car")).empty());
  }
  // Held to the Performance: the target to maxSpeed, 15 m/s; 5 m/s in 2 s (2.5 m/s^2) stretched
  // to 2.5 s at 2 m/s^2: 12 m/s at t1 + 1, 15 m/s from t1 + 2.5. Down, 10 m/s by a cubic
  // peaking at 15 m/s^2 stretched by 15 / 4 to 3.75 s: at t2 + 1.87 (p = 1.87 / 3.75, just
  // before half way) 15 - 10 (3 p^2 - 2 p^3) = 10.02 m/s, and 5 m/s at its end. Two ways there:
  // esmini's reading, and the same actions in TransitionDynamics followingMode follow (1.3: "the
  // actor tries to follow the shape as best as it can. This may be restricted by the
  // 'Performance' properties (for vehicles)"), under the standard reading.
  const auto check_held = [](FixtureRun& run) {
    run.run();
    const auto up = run.first("up", engine::TransitionKind::kStart);
    const auto down = run.first("down", engine::TransitionKind::kStart);
    REQUIRE(up);
    REQUIRE(down);
    CHECK(run.at(*up + 1.0, "Car").speed == Approx(12.0).margin(1e-9));
    CHECK(run.at(*up + 2.0, "Car").speed == Approx(14.0).margin(1e-9));
    CHECK(run.at(*up + 2.5, "Car").speed == Approx(15.0).margin(1e-9));
    CHECK(run.at(*up + 3.5, "Car").speed == Approx(15.0).margin(1e-9));
    const double p = 1.87 / 3.75;
    CHECK(run.at(*down + 1.87, "Car").speed ==
          Approx(15.0 - 10.0 * (3.0 * p * p - 2.0 * p * p * p)).margin(1e-9));
    CHECK(run.at(*down + 3.75, "Car").speed == Approx(5.0).margin(1e-9));
  };
  SECTION("esmini") {
    FixtureRun run(engine_fixture("semantics_performance.xosc"), esmini_reading());
    check_held(run);
  }
  SECTION("standard, followingMode follow") {
    FixtureRun run(engine_fixture("speed_follow_performance.xosc"));
    check_held(run);
  }
}

TEST_CASE("--disable-controllers moves every entity under the default controller",
          "[engine][semantics][controllers]") {
  // The fixture's Car has esmini's AEBController, which this engine lacks and acc stands in
  // for; esmini's --disable_controllers ignores it, and so does
  // SimulationOptions::disable_controllers.
  engine::SimulationOptions options;
  options.disable_controllers = true;
  FixtureRun run(engine_fixture("compat_appearance_values.xosc"), options);
  run.run();
  CHECK(run.sim().controller_substitute(run.entity("Car")).empty());
  CHECK_THAT(corsa::test::all_text(run.diagnostics()),
             !Catch::Contains("controller 'AEBController' is not one of this engine's"));
}

TEST_CASE("An Act its StopTrigger stops takes the stopTransition, or esmini's endTransition",
          "[engine][semantics][storyboard]") {
  // Act "first" is stopped at 1 s; Act "second" waits for first's endTransition to set 10 m/s.
  SECTION("standard") {
    FixtureRun run(engine_fixture("semantics_act_stop.xosc"));
    run.run();
    CHECK(run.first("first", engine::TransitionKind::kStop));
    CHECK_FALSE(run.first("first", engine::TransitionKind::kEnd));
    CHECK_FALSE(run.first("second", engine::TransitionKind::kStart));
    CHECK(run.now("Car").speed == Approx(0.0));
  }
  SECTION("esmini") {
    FixtureRun run(engine_fixture("semantics_act_stop.xosc"), esmini_reading());
    run.run();
    const auto ended = run.first("first", engine::TransitionKind::kEnd);
    REQUIRE(ended);
    CHECK(*ended == Approx(1.0));
    CHECK(run.first("second", engine::TransitionKind::kStart));
    CHECK(run.now("Car").speed == Approx(10.0));
  }
}

TEST_CASE("A TrafficSwarmAction ends when its swarm is stopped, under either reading",
          "[engine][semantics][traffic]") {
  // The swarm starts at 0.5 s and a TrafficStopAction stops it at 20 s; the run ends at 25 s.
  const auto check = [](FixtureRun& run) {
    run.run();
    const auto started = run.first("StartSwarm", engine::TransitionKind::kStart);
    const auto ended = run.first("StartSwarm", engine::TransitionKind::kEnd);
    REQUIRE(started);
    REQUIRE(ended);
    CHECK(*started < 0.6);
    CHECK(*ended >= 20.0);
    CHECK(*ended < 20.1);
  };
  SECTION("standard") {
    FixtureRun run(engine_fixture("traffic_swarm.xosc"));
    check(run);
  }
  SECTION("esmini") {
    FixtureRun run(engine_fixture("traffic_swarm.xosc"), esmini_reading());
    check(run);
  }
}

TEST_CASE("A relative Orientation on a left lane turns from the lane's direction of travel",
          "[engine][semantics][positions]") {
  // Lane 1 at s = 100, h = pi relative, 10 m/s for 2 s: pi from the lane's direction of travel
  // (-s) faces +s; s(2) = 100 + 20, under either reading (esmini's).
  const auto check = [](FixtureRun& run) {
    run.run();
    CHECK(run.at(0.0, "Car").pose.h == Approx(0.0).margin(1e-9));
    CHECK(run.at(2.0, "Car").road->s == Approx(120.0).margin(1e-9));
  };
  SECTION("standard") {
    FixtureRun run(engine_fixture("semantics_lane_orientation.xosc"));
    check(run);
  }
  SECTION("esmini") {
    FixtureRun run(engine_fixture("semantics_lane_orientation.xosc"), esmini_reading());
    check(run);
  }
}

TEST_CASE("A RoutePosition in lane coordinates turns from, or faces, the lane's traffic",
          "[engine][semantics][positions][route]") {
  // Lane 1 at path s 50 of a route along road 1 from s = 50 (road s 100), h = pi relative,
  // 10 m/s for 2 s: pi from the lane's direction of travel (-s) faces +s; s(2) = 120. Bare, at
  // the same place without an Orientation (1.3: "the relative reference context with
  // Heading=Pitch=Roll=0"), faces the lane's direction of travel, -s, against the route's way.
  const auto check = [](FixtureRun& run) {
    run.run();
    CHECK(run.at(0.0, "Car").pose.h == Approx(0.0).margin(1e-9));
    CHECK(run.at(2.0, "Car").road->s == Approx(120.0).margin(1e-9));
    CHECK(run.at(0.0, "Bare").road->lane == 1);
    CHECK(std::abs(run.at(0.0, "Bare").pose.h) == Approx(std::numbers::pi).margin(1e-9));
  };
  SECTION("standard") {
    FixtureRun run(engine_fixture("semantics_route_orientation.xosc"));
    check(run);
  }
  SECTION("esmini") {
    FixtureRun run(engine_fixture("semantics_route_orientation.xosc"), esmini_reading());
    check(run);
  }
}

TEST_CASE("A RoutePosition in lane coordinates with an absolute Orientation, or esmini's relative",
          "[engine][semantics][positions][route]") {
  // Road 1 runs along +x (heading 0); lane 1 carries traffic toward -s, lane -1 toward +s. Abs
  // (lane 1) and AbsRight (lane -1) state an absolute h = 0.5, Rel (lane 1) a relative one.
  // Expected by hand: the standard's absolute heading is the world's, 0.5 on either lane; esmini
  // reads any Orientation of FromLaneCoordinates as turned from the lane's direction of travel:
  // pi + 0.5 on lane 1, which wraps to 0.5 - pi, and 0.5 on lane -1. A relative one turns from
  // the lane's direction of travel under both readings.
  constexpr double kPi = std::numbers::pi;
  const auto turn = [](double from, double to) { return std::remainder(to - from, 2.0 * kPi); };
  SECTION("standard") {
    FixtureRun run(engine_fixture("semantics_route_lane_absolute.xosc"));
    run.run();
    CHECK(run.at(0.0, "Abs").road->lane == 1);
    CHECK(run.at(0.0, "Abs").pose.h == Approx(0.5).margin(1e-9));
    CHECK(run.at(0.0, "AbsRight").pose.h == Approx(0.5).margin(1e-9));
    CHECK(turn(kPi + 0.5, run.at(0.0, "Rel").pose.h) == Approx(0.0).margin(1e-9));
  }
  SECTION("esmini") {
    FixtureRun run(engine_fixture("semantics_route_lane_absolute.xosc"), esmini_reading());
    run.run();
    CHECK(run.at(0.0, "Abs").road->lane == 1);
    CHECK(turn(kPi + 0.5, run.at(0.0, "Abs").pose.h) == Approx(0.0).margin(1e-9));
    CHECK(run.at(0.0, "AbsRight").pose.h == Approx(0.5).margin(1e-9));
    CHECK(turn(kPi + 0.5, run.at(0.0, "Rel").pose.h) == Approx(0.0).margin(1e-9));
  }
}

TEST_CASE(
    "A RoutePosition in lane coordinates without Orientation faces its lane's traffic, or "
    "esmini's pi on lanes of positive id",
    "[engine][semantics][positions][route]") {
  // A left-hand-traffic road along +x: lane 1 carries traffic toward +s (heading 0), lane -1
  // toward -s (pi). The standard's missing Orientation is a relative 0 from the lane's direction
  // of travel; esmini's reader turns a lane of positive id by pi from +s and any other by 0,
  // whatever the traffic rule.
  constexpr double kPi = std::numbers::pi;
  SECTION("standard") {
    FixtureRun run(engine_fixture("semantics_route_lane_lht.xosc"));
    run.run();
    CHECK(run.at(0.0, "Left").road->lane == 1);
    CHECK(run.at(0.0, "Left").pose.h == Approx(0.0).margin(1e-9));
    CHECK(std::abs(run.at(0.0, "Right").pose.h) == Approx(kPi).margin(1e-9));
  }
  SECTION("esmini") {
    FixtureRun run(engine_fixture("semantics_route_lane_lht.xosc"), esmini_reading());
    run.run();
    CHECK(run.at(0.0, "Left").road->lane == 1);
    CHECK(std::abs(run.at(0.0, "Left").pose.h) == Approx(kPi).margin(1e-9));
    CHECK(run.at(0.0, "Right").pose.h == Approx(0.0).margin(1e-9));
  }
}

TEST_CASE("A time headway towards an entity behind holds for no rule, under either reading",
          "[engine][semantics][conditions]") {
  // Car (s = 50) waits for its headway to Behind (s = 10) to exceed 1 s before going 20 m/s. No
  // headway is defined towards an entity behind: the condition does not hold (esmini's reading;
  // an infinite headway would start the event at once).
  const auto check = [](FixtureRun& run) {
    run.run();
    CHECK_FALSE(run.first("away", engine::TransitionKind::kStart));
    CHECK(run.now("Car").speed == Approx(10.0));
  };
  SECTION("standard") {
    FixtureRun run(engine_fixture("semantics_headway_behind.xosc"));
    check(run);
  }
  SECTION("esmini") {
    FixtureRun run(engine_fixture("semantics_headway_behind.xosc"), esmini_reading());
    check(run);
  }
}

TEST_CASE("A RelativeLanePosition without Orientation faces its lane's traffic, or esmini's +s",
          "[engine][semantics][positions]") {
  // Ref stands on lane 1 facing +s (against that lane's traffic); Other is placed one lane
  // further left (lane 2) and 10 m on, without Orientation: lane 2's traffic (-s), or under
  // esmini's reading the road's +s (here also the way Ref faces, as in esmini's
  // left-hand-traffic_by_heading).
  SECTION("standard") {
    FixtureRun run(engine_fixture("semantics_relative_lane_heading.xosc"));
    run.run();
    CHECK(run.at(0.0, "Other").road->lane == 2);
    CHECK(std::abs(run.at(0.0, "Other").pose.h) == Approx(std::numbers::pi).margin(1e-9));
  }
  SECTION("esmini") {
    FixtureRun run(engine_fixture("semantics_relative_lane_heading.xosc"), esmini_reading());
    run.run();
    CHECK(run.at(0.0, "Other").road->lane == 2);
    CHECK(run.at(0.0, "Other").pose.h == Approx(0.0).margin(1e-9));
  }
}

TEST_CASE(
    "Road-based positions turn a missing or relative heading from the lane or +s, or esmini's +s",
    "[engine][semantics][positions]") {
  // A straight road along +x (road heading 0); lanes 1 to 3 carry traffic toward -s (heading
  // pi). Back stands on lane -1 facing -s, against its lane's traffic. Expected headings by hand:
  // the lane's traffic is 0 on lane -1 and pi on lanes 1 and 2; pi + 0.5 wraps to 0.5 - pi.
  constexpr double kPi = std::numbers::pi;
  const auto heading_of = [](FixtureRun& run, const char* name) {
    return run.at(0.0, name).pose.h;
  };
  // The difference of two headings in (-pi, pi], so that pi and -pi compare equal.
  const auto turn = [](double from, double to) { return std::remainder(to - from, 2.0 * kPi); };
  const auto check_common = [&](FixtureRun& run) {
    // Same under both readings: a relative heading of a RelativeLanePosition given by dsLane
    // turns from the target lane's direction of travel (below); a relative heading of a
    // RelativeRoadPosition from +s (0.5); a LanePosition without Orientation faces its
    // lane's traffic (lane 2: pi); a RelativeLanePosition without Orientation on the lane of a
    // reference entity that drives against it faces that lane's traffic, +s, not the
    // reference's -s (esmini: the road's +s, the same here). A RoadPosition or a
    // RelativeRoadPosition without Orientation on lane 2 faces the road's +s (0), not its
    // lane's traffic: 1.3 turns their "relative reference context with Heading=Pitch=Roll=0"
    // from "the tangent to the road s-axis".
    CHECK(turn(heading_of(run, "RelRoadTurned"), 0.5) == Approx(0.0).margin(1e-9));
    CHECK(turn(heading_of(run, "LaneLeft"), kPi) == Approx(0.0).margin(1e-9));
    CHECK(run.at(0.0, "SameLane").road->lane == -1);
    CHECK(run.at(0.0, "SameLane").road->s == Approx(210.0).margin(1e-9));
    CHECK(turn(heading_of(run, "SameLane"), 0.0) == Approx(0.0).margin(1e-9));
    CHECK(run.at(0.0, "RoadLeft").road->lane == 2);
    CHECK(turn(heading_of(run, "RoadLeft"), 0.0) == Approx(0.0).margin(1e-9));
    CHECK(run.at(0.0, "RelRoadLeft").road->lane == 2);
    CHECK(turn(heading_of(run, "RelRoadLeft"), 0.0) == Approx(0.0).margin(1e-9));
  };
  SECTION("standard") {
    FixtureRun run(engine_fixture("semantics_road_frame_headings.xosc"));
    run.run();
    check_common(run);
    // A relative heading of a RelativeLanePosition turns from the target lane's direction of
    // travel (lane 1: pi + 0.5).
    CHECK(run.at(0.0, "LeftTurned").road->lane == 1);
    CHECK(turn(heading_of(run, "LeftTurned"), 0.5 - kPi) == Approx(0.0).margin(1e-9));
    // dsLane 30 from lane -1 with dLane 2: the way Back faces (s = 200 - 30), lane 1, facing
    // its traffic turned by 0.5 (pi + 0.5).
    CHECK(run.at(0.0, "LeftAlongLane").road->s == Approx(170.0).margin(1e-9));
    CHECK(run.at(0.0, "LeftAlongLane").road->lane == 1);
    CHECK(turn(heading_of(run, "LeftAlongLane"), 0.5 - kPi) == Approx(0.0).margin(1e-9));
  }
  SECTION("esmini") {
    FixtureRun run(engine_fixture("semantics_road_frame_headings.xosc"), esmini_reading());
    run.run();
    check_common(run);
    // esmini turns the relative heading of a RelativeLanePosition given by ds from the road's
    // +s (0.5), and steps dLane 2 from lane -1 across the centre lane without counting it: lane 2.
    CHECK(run.at(0.0, "LeftTurned").road->lane == 2);
    CHECK(turn(heading_of(run, "LeftTurned"), 0.5) == Approx(0.0).margin(1e-9));
    // dsLane: Back faces -s on a right lane, so esmini mirrors dLane 2 to -2: lane -3, facing
    // its traffic (+s) turned by 0.5; 30 m along lane -1's traffic (+s), against the way Back
    // faces.
    CHECK(run.at(0.0, "LeftAlongLane").road->s == Approx(230.0).margin(1e-9));
    CHECK(run.at(0.0, "LeftAlongLane").road->lane == -3);
    CHECK(turn(heading_of(run, "LeftAlongLane"), 0.5) == Approx(0.0).margin(1e-9));
  }
}

TEST_CASE(
    "A RelativeLanePosition given by dsLane runs the way the entity faces, or esmini's lane's",
    "[engine][semantics][positions]") {
  // Ref stands on lane 1 (traffic toward -s) at s = 100 facing -s; Other: dLane -1, dsLane 10,
  // offset 0.5, without Orientation (fixture comment). Fwd stands on lane 2 at s = 200 facing
  // +s; Ahead is placed as Other, relative to Fwd. Lane centres: lane 1 at t = 1.75, lane 2 at
  // t = 5.25, lane 3 at t = 8.75.
  SECTION("standard") {
    FixtureRun run(engine_fixture("semantics_relative_lane_along_lane.xosc"));
    run.run();
    // 1.3: dsLane "in the direction the reference entity is facing": Ref faces -s, s = 90; lane
    // 1 + (-1): the centre lane, t = 0 + 0.5 along +t, which lies in lane 1; facing lane 1's
    // traffic (pi) as the reference's lane.
    CHECK(run.at(0.0, "Other").road->s == Approx(90.0).margin(1e-9));
    CHECK(run.at(0.0, "Other").road->t == Approx(0.5).margin(1e-9));
    CHECK(run.at(0.0, "Other").road->lane == 1);
    CHECK(std::abs(run.at(0.0, "Other").pose.h) == Approx(std::numbers::pi).margin(1e-9));
    // Fwd faces +s: s = 210; lane 2 + (-1) = 1, t = 1.75 + 0.5 (dLane and offset do not turn
    // with the entity); facing lane 1's traffic (pi).
    CHECK(run.at(0.0, "Ahead").road->s == Approx(210.0).margin(1e-9));
    CHECK(run.at(0.0, "Ahead").road->lane == 1);
    CHECK(run.at(0.0, "Ahead").road->t == Approx(2.25).margin(1e-9));
    CHECK(std::abs(run.at(0.0, "Ahead").pose.h) == Approx(std::numbers::pi).margin(1e-9));
  }
  SECTION("esmini") {
    FixtureRun run(engine_fixture("semantics_relative_lane_along_lane.xosc"), esmini_reading());
    run.run();
    // 10 m along lane 1's traffic: s = 90; dLane and offset mirrored: lane 2, t = 5.25 - 0.5;
    // facing lane 2's traffic (pi).
    CHECK(run.at(0.0, "Other").road->s == Approx(90.0).margin(1e-9));
    CHECK(run.at(0.0, "Other").road->lane == 2);
    CHECK(run.at(0.0, "Other").road->t == Approx(4.75).margin(1e-9));
    CHECK(std::abs(run.at(0.0, "Other").pose.h) == Approx(std::numbers::pi).margin(1e-9));
    // 10 m along lane 2's traffic: s = 190, against the way Fwd faces; Fwd faces +s on a left
    // lane, so dLane and offset mirrored: lane 3, t = 8.75 - 0.5; facing lane 3's traffic (pi).
    CHECK(run.at(0.0, "Ahead").road->s == Approx(190.0).margin(1e-9));
    CHECK(run.at(0.0, "Ahead").road->lane == 3);
    CHECK(run.at(0.0, "Ahead").road->t == Approx(8.25).margin(1e-9));
    CHECK(std::abs(run.at(0.0, "Ahead").pose.h) == Approx(std::numbers::pi).margin(1e-9));
  }
}

TEST_CASE("A dsLane position's dLane past the last lane counts toward the entity's left",
          "[engine][semantics][positions][lenient]") {
  // Fixture comment: Far on lane 3 (the road's last left lane) and Near on lane 1, both facing
  // -s at s = 100 and 300; Beyond and Across are dLane 1, dsLane 10 from them.
  SECTION("standard") {
    FixtureRun run(engine_fixture("semantics_relative_lane_past_lanes.xosc"));
    run.run();
    // Lane 3 + 1 = 4 does not exist: toward Far's left (-t), lane 2, 10 m the way Far faces.
    CHECK(run.at(0.0, "Beyond").road->lane == 2);
    CHECK(run.at(0.0, "Beyond").road->s == Approx(90.0).margin(1e-9));
    CHECK(run.at(0.0, "Beyond").road->t == Approx(5.25).margin(1e-9));
    CHECK_THAT(all_text(run.diagnostics()),
               Catch::Contains("semantics_relative_lane_past_lanes.xosc:78:") &&
                   Catch::Contains("road '1' has no lane 4 (lane 3 plus dLane 1) at s = 90 (read "
                                   "as lane 2, esmini's count: dLane lanes toward the reference "
                                   "entity's left, the centre lane not counted)"));
    // Lane 1 + 1 = 2 exists: the lane id plus dLane, no warning for it.
    CHECK(run.at(0.0, "Across").road->lane == 2);
    CHECK(run.at(0.0, "Across").road->s == Approx(290.0).margin(1e-9));
    CHECK_THAT(all_text(run.diagnostics()), !Catch::Contains("no lane 2"));
    engine::SimulationOptions strict;
    strict.strict = true;
    CHECK_THROWS_WITH(FixtureRun(engine_fixture("semantics_relative_lane_past_lanes.xosc"), strict),
                      Catch::Contains("semantics_relative_lane_past_lanes.xosc:78:") &&
                          Catch::Contains("road '1' has no lane 4") &&
                          Catch::Contains("an error under --strict"));
  }
  SECTION("esmini") {
    FixtureRun run(engine_fixture("semantics_relative_lane_past_lanes.xosc"), esmini_reading());
    run.run();
    // Mirrored: lane 3 - 1 = 2; from lane 1, -1 steps across the centre lane to lane -1.
    CHECK(run.at(0.0, "Beyond").road->lane == 2);
    CHECK(run.at(0.0, "Beyond").road->s == Approx(90.0).margin(1e-9));
    CHECK(run.at(0.0, "Across").road->lane == -1);
    CHECK(run.at(0.0, "Across").road->t == Approx(-1.75).margin(1e-9));
    CHECK(run.at(0.0, "Across").road->s == Approx(290.0).margin(1e-9));
    CHECK_THAT(all_text(run.diagnostics()), !Catch::Contains("esmini's count"));
  }
}

TEST_CASE("dLane past the last lane: esmini's count where its lane exists, else a located error",
          "[engine][semantics][positions][lenient]") {
  // Fixture comment: Ref on lane 3 of the straight road (lanes 3 to -3, lanes 1 to 3 driven
  // toward -s) at s = 100, turned by RefTurn from its lane's traffic; Up and Down are dLane
  // UpDLane and DownDLane (1 and -1), dsLane 10 from it.
  const auto fixture = engine_fixture("semantics_relative_lane_dlane_fallback.xosc");
  SECTION("opposite dLane values reach one lane from a reference facing -s") {
    FixtureRun run(fixture);
    run.run();
    // Up: lane 3 + 1 = 4 does not exist; esmini's count, toward Ref's left (-t): lane 2. Down:
    // lane 3 - 1 = 2 by the standard's count, without a warning.
    for (const char* name : {"Up", "Down"}) {
      CHECK(run.at(0.0, name).road->lane == 2);
      CHECK(run.at(0.0, name).road->s == Approx(90.0).margin(1e-9));
      CHECK(run.at(0.0, name).road->t == Approx(5.25).margin(1e-9));
    }
    const std::string text = all_text(run.diagnostics());
    CHECK_THAT(text, Catch::Contains("semantics_relative_lane_dlane_fallback.xosc:73:") &&
                         Catch::Contains("no lane 4 (lane 3 plus dLane 1) at s = 90 (read as "
                                         "lane 2, esmini's count"));
    CHECK_THAT(text, !Catch::Contains("plus dLane -1"));
  }
  SECTION("esmini's reading mirrors both for a reference facing -s on a left lane") {
    // Up's dLane -1: lane 2; Down's dLane 1: lane 4, which does not exist.
    CHECK_THROWS_WITH(FixtureRun(fixture, esmini_reading()),
                      Catch::Contains("semantics_relative_lane_dlane_fallback.xosc:76:") &&
                          Catch::Contains("road '1' has no lane 4 at s = 90"));
  }
  SECTION("from a reference facing +s esmini's count finds no lane either: a located error") {
    // Ref faces +s, its left is +t: lane 3 + 1 = 4, and esmini's count gives lane 4 too, 10 m
    // ahead at s = 110.
    const auto run = [&] { FixtureRun(fixture, {}, {{"RefTurn", "3.141592653589793"}}); };
    CHECK_THROWS_WITH(run(), Catch::Contains("semantics_relative_lane_dlane_fallback.xosc:73:") &&
                                 Catch::Contains("road '1' has no lane 4 at s = 110") &&
                                 !Catch::Contains("esmini's count"));
  }
  SECTION("a fallback lane that does not exist either leaves the located error") {
    // Ref faces -s: lane 3 - 8 = -5 does not exist (the last right lane is the sidewalk -4),
    // nor does esmini's count's lane 11.
    const auto run = [&] { FixtureRun(fixture, {}, {{"DownDLane", "-8"}}); };
    CHECK_THROWS_WITH(run(), Catch::Contains("semantics_relative_lane_dlane_fallback.xosc:76:") &&
                                 Catch::Contains("road '1' has no lane -5 at s = 90") &&
                                 !Catch::Contains("lane 11"));
  }
}

TEST_CASE("lane_across_centre steps lanes without counting the centre lane",
          "[engine][semantics][positions]") {
  // The lane d lanes over, lane 0 skipped when the step crosses or lands on it.
  CHECK(engine::detail::lane_across_centre(-1, 1) == 1);
  CHECK(engine::detail::lane_across_centre(1, -2) == -2);
  CHECK(engine::detail::lane_across_centre(2, -2) == -1);
  CHECK(engine::detail::lane_across_centre(1, -1) == -1);
  CHECK(engine::detail::lane_across_centre(-3, 2) == -1);  // on one side: the lane ids' sum
  CHECK(engine::detail::lane_across_centre(3, 1) == 4);    // past the last lane: not checked
  CHECK(engine::detail::lane_across_centre(2, 0) == 2);
  CHECK(engine::detail::lane_across_centre(0, -1) == -1);  // from the centre lane: the sum
}

TEST_CASE("A RoutePosition in road coordinates turns from the road's +s, or esmini's way",
          "[engine][semantics][positions][route]") {
  // Fixture comment: path s 600 lies on road 2 (heading pi), which the route drives toward -s
  // (heading 0). Without an Orientation both readings face the road's +s, not along the route;
  // an absolute Orientation is esmini's relative one.
  constexpr double kPi = std::numbers::pi;
  // The difference of two headings in (-pi, pi], so that pi and -pi compare equal.
  const auto turn = [](double from, double to) { return std::remainder(to - from, 2.0 * kPi); };
  SECTION("standard") {
    FixtureRun run(engine_fixture("semantics_route_road_orientation.xosc"));
    run.run();
    CHECK(run.at(0.0, "Bare").pose.x == Approx(610.0).margin(1e-9));
    CHECK(turn(run.at(0.0, "Bare").pose.h, kPi) == Approx(0.0).margin(1e-9));
    CHECK(turn(run.at(0.0, "Turned").pose.h, kPi + 0.5) == Approx(0.0).margin(1e-9));
    CHECK(turn(run.at(0.0, "Fixed").pose.h, 0.5) == Approx(0.0).margin(1e-9));
  }
  SECTION("esmini") {
    FixtureRun run(engine_fixture("semantics_route_road_orientation.xosc"), esmini_reading());
    run.run();
    CHECK(run.at(0.0, "Bare").pose.x == Approx(610.0).margin(1e-9));
    CHECK(turn(run.at(0.0, "Bare").pose.h, kPi) == Approx(0.0).margin(1e-9));
    CHECK(turn(run.at(0.0, "Turned").pose.h, kPi + 0.5) == Approx(0.0).margin(1e-9));
    CHECK(turn(run.at(0.0, "Fixed").pose.h, kPi + 0.5) == Approx(0.0).margin(1e-9));
  }
}

TEST_CASE("A RoutePosition from the current entity turns its Orientation from the entity's",
          "[engine][semantics][positions][route]") {
  // Fixture comment: Car on road 1 at x = 100 with h 0.3, p 0.02, r -0.01 (not the road's);
  // Same, Turned and Fixed at its place on the route without Orientation, relative (h 0.5,
  // p 0.04, r 0.03) and absolute (h 1, p 0.05, r -0.02). Swapping the relative and absolute
  // readings would give Turned h 0.5 and Fixed h 1.3.
  const auto check = [](FixtureRun& run) {
    run.run();
    // Placed on a road, an entity takes the road surface's pitch and roll (0 on this flat road)
    // whatever its Orientation gives: Car and the three placed from it record 0, and the heading
    // tells the readings apart.
    const auto& car = run.at(0.0, "Car").pose;
    REQUIRE(car.h == Approx(0.3).margin(1e-9));
    for (const char* name : {"Car", "Same", "Turned", "Fixed"}) {
      CHECK(run.at(0.0, name).pose.p == 0.0);
      CHECK(run.at(0.0, name).pose.r == 0.0);
    }
    const auto& same = run.at(0.0, "Same").pose;
    CHECK(same.x == Approx(100.0).margin(1e-9));
    CHECK(same.h == Approx(car.h).margin(1e-9));
    const auto& turned = run.at(0.0, "Turned").pose;
    CHECK(turned.x == Approx(100.0).margin(1e-9));
    CHECK(turned.h == Approx(car.h + 0.5).margin(1e-9));
    CHECK(run.at(0.0, "Fixed").pose.h == Approx(1.0).margin(1e-9));
  };
  SECTION("standard") {
    FixtureRun run(engine_fixture("semantics_route_entity_orientation.xosc"));
    check(run);
  }
  SECTION("esmini") {
    FixtureRun run(engine_fixture("semantics_route_entity_orientation.xosc"), esmini_reading());
    check(run);
  }
}

TEST_CASE("A RelativeLanePosition's dLane is added to the lane id, or esmini's skips lane 0",
          "[engine][semantics][positions]") {
  // Ref drives lane -1 facing +s; Other is dLane 1, ds 10, offset 1 from it. Standard: lane id
  // -1 + 1 = 0, the centre lane (1.3: "adding dLane to that of the reference entity"), on the
  // reference line plus the offset. esmini steps across the centre lane without counting it:
  // lane 1, its centre (1.75 m) plus the offset.
  SECTION("standard") {
    FixtureRun run(engine_fixture("semantics_relative_lane_centre.xosc"));
    run.run();
    CHECK(run.at(0.0, "Other").pose.y == Approx(1.0).margin(1e-9));
    CHECK(run.at(0.0, "Other").pose.x == Approx(110.0).margin(1e-9));
    CHECK(run.at(0.0, "Other").pose.h == Approx(0.0).margin(1e-9));  // as Ref's lane runs
    CHECK(run.at(0.0, "Other").road->lane == 1);                     // the lane the offset reaches
  }
  SECTION("esmini") {
    FixtureRun run(engine_fixture("semantics_relative_lane_centre.xosc"), esmini_reading());
    run.run();
    CHECK(run.at(0.0, "Other").pose.y == Approx(2.75).margin(1e-9));
    CHECK(run.at(0.0, "Other").pose.x == Approx(110.0).margin(1e-9));
    CHECK(run.at(0.0, "Other").pose.h == Approx(0.0).margin(1e-9));  // the road's +s
    CHECK(run.at(0.0, "Other").road->lane == 1);
  }
}

TEST_CASE("A RelativeTargetLane counts to the reference's left, or esmini's adds it to the lane id",
          "[engine][semantics][lanes]") {
  // Truck drives lane 1 toward -s and changes to RelativeTargetLane -1 of itself over 1 s: the
  // lane on its right, lane 2 (1.3: the reference entity's negative y-axis); esmini's lane id
  // 1 - 1, skipping 0: lane -1, across the reference line.
  SECTION("standard") {
    FixtureRun run(engine_fixture("semantics_relative_target_lane.xosc"));
    run.run();
    CHECK(run.at(2.0, "Truck").road->lane == 2);
    CHECK(run.at(2.0, "Truck").pose.y == Approx(5.25).margin(1e-9));
  }
  SECTION("esmini") {
    FixtureRun run(engine_fixture("semantics_relative_target_lane.xosc"), esmini_reading());
    run.run();
    CHECK(run.at(2.0, "Truck").road->lane == -1);
    CHECK(run.at(2.0, "Truck").pose.y == Approx(-1.75).margin(1e-9));
  }
}

TEST_CASE("A ReachPositionCondition ignores the Orientation, or esmini's compares the heading",
          "[engine][semantics][conditions]") {
  // The car's own place with a relative Orientation h = 0.1, from 0.2 s on; the action
  // teleports the car to its own road position, aligned with the road.
  SECTION("standard") {
    FixtureRun run(engine_fixture("semantics_reach_heading.xosc"));
    run.run();
    const auto start = run.first("S::A::G::M::Aligned::Align", engine::TransitionKind::kStart);
    REQUIRE(start);
    CHECK(*start == Approx(0.21));
    // The teleport takes the step (as esmini's): the car stands where it was put, then drives on.
    CHECK(run.at(*start + 0.01, "Car").pose.x == Approx(run.at(*start, "Car").pose.x));
    CHECK(run.at(*start + 0.02, "Car").pose.x ==
          Approx(run.at(*start, "Car").pose.x + 0.1).margin(1e-9));
    CHECK(run.at(*start + 0.01, "Car").pose.h == Approx(0.0).margin(1e-12));
  }
  SECTION("esmini") {
    FixtureRun run(engine_fixture("semantics_reach_heading.xosc"), esmini_reading());
    run.run();
    const auto start = run.first("S::A::G::M::Aligned::Align", engine::TransitionKind::kStart);
    REQUIRE(start);
    // Heading within 0.05 rad of 0.1: 10 m/s x 0.05 of lateral speed, 1.374 sin(pi t / 4) m/s
    // from 0.01 s on: t = 0.474 s, first seen at 0.49 s.
    CHECK(*start == Approx(0.49));
    CHECK(run.at(*start, "Car").pose.h > 0.05);
    CHECK(run.at(*start - 0.01, "Car").pose.h < 0.05);
    // The teleport takes the step: the car stands where it was put, then drives on.
    CHECK(run.at(*start + 0.01, "Car").pose.x == Approx(run.at(*start, "Car").pose.x));
    CHECK(run.at(*start + 0.02, "Car").pose.x ==
          Approx(run.at(*start, "Car").pose.x + 0.1).margin(1e-9));
  }
}

TEST_CASE("A ReachPositionCondition on a WorldPosition compares the place alone, either reading",
          "[engine][semantics][conditions]") {
  // The WorldPosition's h faces against the car; esmini checks the heading only of a position
  // with an Orientation element, which a WorldPosition has not. The car (10 m/s from x = 50)
  // comes within 1 m of x = 60.55 after 0.955 s, first seen at 0.96 s.
  const auto check = [](FixtureRun& run) {
    run.run();
    const auto start = run.first("S::A::G::M::Reached::Stop", engine::TransitionKind::kStart);
    REQUIRE(start);
    CHECK(*start == Approx(0.96));
    CHECK(std::abs(run.at(*start, "Car").pose.x - 60.55) < 1.0);
    CHECK(std::abs(run.at(*start - 0.01, "Car").pose.x - 60.55) > 1.0);
    CHECK(std::abs(run.at(*start, "Car").pose.h) < 1e-12);
  };
  SECTION("standard") {
    FixtureRun run(engine_fixture("semantics_reach_world_heading.xosc"));
    check(run);
  }
  SECTION("esmini") {
    FixtureRun run(engine_fixture("semantics_reach_world_heading.xosc"), esmini_reading());
    check(run);
  }
}

TEST_CASE(
    "A RelativeSpeedCondition's direction is the triggering entity's, or esmini's reference's",
    "[engine][semantics][conditions]") {
  // Ref drives 10 m/s along +x, Trig 10 m/s along a line 60 degrees to it. Longitudinally, in
  // Trig's frame: 10 - 10 cos 60 = 5 m/s; in Ref's frame: 10 cos 60 - 10 = -5 m/s. "faster"
  // waits for more than 0, "slower" for less than -4; both are checked from the first step on.
  SECTION("standard") {
    FixtureRun run(engine_fixture("semantics_relative_speed_frame.xosc"));
    run.run();
    CHECK(run.at(1.0, "Trig").pose.h == Approx(std::numbers::pi / 3).margin(1e-9));
    CHECK(run.at(1.0, "Ref").pose.h == Approx(0.0).margin(1e-12));
    const auto faster = run.first("S::A::G::M::faster", engine::TransitionKind::kStart);
    REQUIRE(faster);
    CHECK(*faster == Approx(0.0).margin(1e-12));
    CHECK_FALSE(run.first("S::A::G::M::slower", engine::TransitionKind::kStart));
  }
  SECTION("esmini") {
    FixtureRun run(engine_fixture("semantics_relative_speed_frame.xosc"), esmini_reading());
    run.run();
    const auto slower = run.first("S::A::G::M::slower", engine::TransitionKind::kStart);
    REQUIRE(slower);
    CHECK(*slower == Approx(0.0).margin(1e-12));
    CHECK_FALSE(run.first("S::A::G::M::faster", engine::TransitionKind::kStart));
  }
}

TEST_CASE("A step to a continuous relative speed jumps under either reading",
          "[engine][semantics]") {
  for (const bool esmini : {false, true}) {
    FixtureRun run(engine_fixture("semantics_step_relative_speed.xosc"),
                   esmini ? esmini_reading() : engine::SimulationOptions{});
    run.run();
    const auto start = run.first("S::A::G::M::E::Go", engine::TransitionKind::kStart);
    REQUIRE(start);
    // 1.2 x 30 m/s from the step the action starts in; a Performance of 10 m/s^2 would have
    // allowed 0.1 m/s there.
    CHECK(run.at(*start + 0.01, "Chaser").speed == Approx(36.0));
    CHECK(run.now("Chaser").speed == Approx(36.0));
  }
}

TEST_CASE("A lane change goes on to its target lane from where a teleport put the car, or stops",
          "[engine][semantics]") {
  // At 10 m/s the car changes from lane -1 (t = -1.75) to lane -2 (t = -5.25) linearly in 2 s
  // from t = 1.01 s. Halfway, at 2.01 s, a TeleportAction puts it on lane -3 (t = -8.75) at
  // s = 100. The teleport assigns no lateral control (Annex A), so the lane change carries on:
  // the second half of the line runs from t = -8.75 to lane -2, so t(2.51) = -7.0 and the car is
  // on lane -2 from 3.01 s, when the action ends. The teleport takes its step (the car stands at
  // s = 100, t = -8.75 at 2.02 s); the next step makes up its 0.035 m, then 0.035 m a step. No
  // step swerves back toward the lanes it left (the lateral offset was measured from lane -1's
  // centre).
  SECTION("standard") {
    FixtureRun run(engine_fixture("semantics_teleport_lane_change.xosc"));
    run.run();
    CHECK(run.at(2.02, "Car").road->s == Approx(100.0).margin(1e-9));
    CHECK(run.at(2.02, "Car").road->t == Approx(-8.75).margin(1e-9));
    CHECK(run.at(2.03, "Car").road->t == Approx(-8.75 + 0.07).margin(1e-9));
    CHECK(run.at(2.51, "Car").road->t == Approx(-7.0).margin(1e-9));
    CHECK(run.at(3.01, "Car").road->t == Approx(-5.25).margin(1e-9));
    CHECK(run.at(4.0, "Car").road->lane == -2);
    CHECK(run.at(4.0, "Car").road->t == Approx(-5.25).margin(1e-9));
    for (int tick = 203; tick < 301; ++tick) {
      const double step =
          run.at((tick + 1) * 0.01, "Car").road->t - run.at(tick * 0.01, "Car").road->t;
      CHECK(step == Approx(0.035).margin(1e-9));
    }
    const auto ended = run.first("ChangeAction", engine::TransitionKind::kEnd);
    REQUIRE(ended);
    CHECK(*ended == Approx(3.01).margin(0.011));
  }
  SECTION("esmini") {
    // esmini's TeleportAction takes the lateral and longitudinal domains: the lane change stops
    // and the car stays on lane -3, where the teleport put it.
    FixtureRun run(engine_fixture("semantics_teleport_lane_change.xosc"), esmini_reading());
    run.run();
    CHECK(run.at(2.02, "Car").road->t == Approx(-8.75).margin(1e-9));
    CHECK(run.at(4.0, "Car").road->lane == -3);
    CHECK(run.at(4.0, "Car").road->t == Approx(-8.75).margin(1e-9));
    CHECK(run.first("ChangeAction", engine::TransitionKind::kStop));
    CHECK_FALSE(run.first("ChangeAction", engine::TransitionKind::kEnd));
  }
}

TEST_CASE("A teleport to a RelativeLanePosition of the car itself without offset",
          "[engine][semantics]") {
  // A quarter into a linear 2 s lane change from lane -1 (t = -1.75) to lane -2 (t = -5.25),
  // the car is at t = -2.625 when, at 1.51 s, it is teleported to a RelativeLanePosition of
  // itself (dLane 0, ds 0) without offset, aligned with the lane.
  SECTION("standard") {
    // 1.3: a missing offset is 0, the lane's centre; the lane change goes on from there.
    FixtureRun run(engine_fixture("semantics_teleport_in_place.xosc"));
    run.run();
    CHECK(run.at(1.52, "Car").road->t == Approx(-1.75).margin(1e-9));
    CHECK(run.at(3.5, "Car").road->t == Approx(-5.25).margin(1e-9));
  }
  SECTION("esmini") {
    // esmini leaves the car where it is across the lane, its heading along it; the teleport
    // stops the lane change, so it drives on there.
    FixtureRun run(engine_fixture("semantics_teleport_in_place.xosc"), esmini_reading());
    run.run();
    CHECK(run.at(1.51, "Car").road->t == Approx(-2.625).margin(1e-9));
    for (const double t : {1.52, 2.01, 3.5}) {
      CAPTURE(t);
      CHECK(run.at(t, "Car").road->t == Approx(-2.625).margin(1e-9));
      CHECK(run.at(t, "Car").pose.h == Approx(0.0).margin(1e-12));
    }
  }
}

TEST_CASE(
    "Under esmini's reading a lane change started in the step of a teleport goes from where the "
    "teleport put the car",
    "[engine][semantics][lane]") {
  // The teleport (to lane -3, t = -8.75) takes the step from 1.01 s to 1.02 s; the linear 2 s
  // change to lane -2 (t = -5.25) started in the same step then moves the car 0.0175 m a step
  // to the left, never right of lane -3's centre (it used to be measured from the wrong lane,
  // 3.5 m off: t = -12.25).
  FixtureRun run(engine_fixture("semantics_teleport_and_lane_change.xosc"), esmini_reading());
  run.run();
  CHECK(run.at(1.02, "Car").road->s == Approx(100.0).margin(1e-9));
  CHECK(run.at(1.02, "Car").road->t == Approx(-8.75).margin(1e-9));
  for (int tick = 102; tick < 400; ++tick) {
    const double t = run.at(tick * 0.01, "Car").road->t;
    INFO("tick " << tick);
    CHECK(t >= -8.75 - 1e-9);
    CHECK(t <= -5.25 + 1e-9);
  }
  CHECK(run.at(2.02, "Car").road->t == Approx(-7.0).margin(0.02));
  CHECK(run.at(4.0, "Car").road->lane == -2);
  CHECK(run.at(4.0, "Car").road->t == Approx(-5.25).margin(1e-9));
}

TEST_CASE("A continuous LaneOffsetAction never ends, or ends at its target as esmini's",
          "[engine][semantics][lane]") {
  // action_lane_offset.xosc: from 1.01 s Shifter moves 1 m sideways (sinusoidal, 0.5 m/s^2: pi
  // seconds, not continuous); Shadow's continuous LaneOffsetAction, a step to Shifter's offset
  // less 0.5 m, reaches its target at once. The standard: a continuous action does not end, and
  // Shadow keeps tracking Shifter. esmini ends it there (its smoke test: test_maneuver_groups_x_3,
  // test_action_dynamics), and Shadow keeps the offset it had, -0.5 m.
  for (const bool esmini : {false, true}) {
    CAPTURE(esmini);
    FixtureRun run(engine_fixture("action_lane_offset.xosc"),
                   esmini ? esmini_reading() : engine::SimulationOptions{});
    run.run();
    CHECK(run.first("ShiftEvent::Shift", engine::TransitionKind::kEnd) == Approx(4.16));
    CHECK(run.now("Shifter").road->t == Approx(-4.25));
    const auto mirror_end = run.first("ShadowEvent::Mirror", engine::TransitionKind::kEnd);
    if (esmini) {
      REQUIRE(mirror_end);
      CHECK(*mirror_end == Approx(1.01).margin(0.011));
      CHECK(run.now("Shadow").road->t == Approx(-8.75 - 0.5));
    } else {
      CHECK_FALSE(mirror_end);
      CHECK(run.now("Shadow").road->t == Approx(-8.75 + 1.0 - 0.5));
    }
  }
}

TEST_CASE("A linear rate toward a moving relative target goes on until met, under either reading",
          "[engine][semantics]") {
  // Lead goes 7 -> 15 m/s at 2 m/s^2 from 2 s; Chaser (5 m/s) is asked at 2 s for Lead's speed
  // at 4 m/s^2, not continuous. +0.4 m/s a step until it meets Lead's speed (8.6 m/s at 2.9 s),
  // 9 m/s in continuous time; a duration fixed at the start from Lead's speed then would have
  // ended at 2.5 s at 7.8 m/s.
  for (const engine::Semantics semantics :
       {engine::Semantics::kStandard, engine::Semantics::kEsmini}) {
    engine::SimulationOptions options;
    options.semantics = semantics;
    options.dt = 0.1;
    FixtureRun met(engine_fixture("rate_toward_relative.xosc"), options);
    met.run();
    CHECK(*met.first("chase", engine::TransitionKind::kEnd) == Approx(2.9).margin(1e-9));
    CHECK(met.at(2.5, "Chaser").speed == Approx(7.0).margin(1e-9));
    CHECK(met.at(4.0, "Chaser").speed == Approx(8.6).margin(1e-9));
  }
}

TEST_CASE("An untimed trajectory step travels its end speed, under either reading",
          "[engine][semantics]") {
  // 0 -> 10 m/s linearly in 2 s along a straight untimed Polyline at dt 0.1 s: each step travels
  // its end speed, 0.1 * (0.5 + 1 + ... + 10) = 10.5 m at 2 s, as on a lane (the mean of each
  // step's speeds, the exact integral, would give 10 m).
  for (const engine::Semantics semantics :
       {engine::Semantics::kStandard, engine::Semantics::kEsmini}) {
    engine::SimulationOptions options;
    options.semantics = semantics;
    options.dt = 0.1;
    FixtureRun end(engine_fixture("trajectory_untimed_accelerating.xosc"), options);
    end.run();
    CHECK(end.at(2.0, "Car").pose.x == Approx(10.5).margin(1e-9));
  }
}

TEST_CASE("A trajectory's last step goes past its end, then on no road the car stands",
          "[engine][semantics]") {
  // No road network; Car (5 m/s, untimed) and Timed (5 m/s by its times) reach the end of their
  // 9.8 m paths in the step to 2 s. The last step goes on past the end for the rest of the step
  // (x = 10, not the end point 9.8), then both stand there at 0 m/s (not straight on at 5 m/s).
  for (const engine::Semantics semantics :
       {engine::Semantics::kStandard, engine::Semantics::kEsmini}) {
    engine::SimulationOptions options;
    options.semantics = semantics;
    options.dt = 0.1;
    FixtureRun stands(engine_fixture("no_roads_after_trajectory.xosc"), options);
    stands.run();
    for (const char* name : {"Car", "Timed"}) {
      INFO(name);
      CHECK(stands.at(2.0, name).pose.x == Approx(10.0).margin(1e-9));
      CHECK(stands.at(4.0, name).pose.x == Approx(10.0).margin(1e-9));
      CHECK(stands.at(2.1, name).speed == 0.0);
    }
  }
}

TEST_CASE("An entity slower than 1e-3 m/s stands still, under either reading",
          "[engine][semantics][conditions]") {
  // StandStillCondition names no speed: esmini's threshold, |v| < 1e-3 m/s. Creep drives
  // 0.0005 m/s and stands still from 0 s: its 1 s condition holds at 1 s. Crawl drives 0.002 m/s
  // and never stands still.
  const auto check = [](FixtureRun& run) {
    run.run();
    CHECK(run.first("marks::maneuver::CreepStill", engine::TransitionKind::kStart) == Approx(1.0));
    CHECK_FALSE(run.first("marks::maneuver::CrawlStill", engine::TransitionKind::kStart));
    CHECK(run.now("Creep").speed == Approx(0.0005));
  };
  SECTION("standard") {
    FixtureRun run(engine_fixture("semantics_stand_still_creep.xosc"));
    check(run);
  }
  SECTION("esmini") {
    FixtureRun run(engine_fixture("semantics_stand_still_creep.xosc"), esmini_reading());
    check(run);
  }
}

}  // namespace corsa::test
