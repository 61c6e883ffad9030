// Routes (OpenSCENARIO 1.3 §6.6): AssignRouteAction, AcquirePositionAction and the route
// strategies through junctions; routes whose lanes need lane changes (a waypoint on another
// lane, a turn only from the inner lane) under every controller, and a route that cannot be
// followed.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "engine_fixture.h"

namespace corsa::test {
namespace {

using Catch::Detail::Approx;

/// The OpenDRIVE id of the road an entity is on at the end of the run ("" off the roads).
std::string final_road(FixtureRun& run, const std::string& name) {
  const auto& road = run.now(name).road;
  return road ? run.sim().road_id(road->road) : std::string();
}

std::string road_of(FixtureRun& run, const engine::EntityState& state) {
  return state.road ? run.sim().road_id(state.road->road) : std::string();
}

/// The lane of `name` when it first passes road s `s` on road `road` (toward +s); 0 if never.
int lane_passing(FixtureRun& run, const std::string& name, const std::string& road, double s) {
  const size_t index = run.entity(name);
  for (const auto& [tick, states] : run.trace().ticks()) {
    const auto& at = states[index].road;
    if (at && run.sim().road_id(at->road) == road && at->s >= s) {
      return at->lane;
    }
  }
  return 0;
}

/// Checks that `name` moved smoothly: no jump between steps beyond its speed,
/// lateral speed at most `max_lateral` m/s; returns the largest lateral speed seen.
double check_smooth(FixtureRun& run, const std::string& name, double max_lateral) {
  const size_t index = run.entity(name);
  const double dt = run.sim().dt();
  const engine::EntityState* previous = nullptr;
  double largest = 0.0;
  for (const auto& [tick, states] : run.trace().ticks()) {
    const engine::EntityState& now = states[index];
    if (previous != nullptr) {
      const double moved = std::hypot(now.pose.x - previous->pose.x, now.pose.y - previous->pose.y);
      INFO(name << " at tick " << tick);
      // Speed is along the entity's own path (also in the turn, 1.75 m outside the reference
      // line), plus the lateral motion of a lane change (1 % at 1.4 m/s across and 10 along).
      // A step that starts at a road's end takes the curvature of that road: the first step
      // into the turn is up to 8.75 % long.
      const bool new_road = !now.road || !previous->road || now.road->road != previous->road->road;
      const double slack = new_road ? 1.0875 * 1.01 : 1.01;
      CHECK(moved <= std::max(now.speed, previous->speed) * dt * slack + 1e-9);
      CHECK(std::abs(now.lateral_speed) <= max_lateral);
    }
    largest = std::max(largest, std::abs(now.lateral_speed));
    previous = &now;
  }
  return largest;
}

TEST_CASE("Routes take their entities through the junction the way the route goes",
          "[engine][route]") {
  FixtureRun run(engine_fixture("action_assign_route.xosc"));
  run.run();
  CHECK(run.sim().end_reason() == engine::EndReason::kStopTrigger);
  CHECK(run.diagnostics().count(Severity::kWarning) == 0);
  // Without a route the straightest way: road 1 west over the junction onto road 3.
  CHECK(final_road(run, "Straight") == "3");
  // The route's waypoint on road 2 turns the entity right (north).
  CHECK(final_road(run, "Right") == "2");
  CHECK(run.now("Right").road->lane == -1);
  CHECK(run.now("Right").pose.y > 20.0);
  // AcquirePositionAction (at 0.5 s) to road 4: a left turn (south).
  CHECK(final_road(run, "Acquire") == "4");
  CHECK(run.now("Acquire").pose.y < -20.0);
  // Each strategy reaches its destination road.
  CHECK(final_road(run, "Fastest") == "4");
  CHECK(final_road(run, "Fewest") == "2");
  CHECK(final_road(run, "Random") == "1");
  // Speeds are untouched by routing.
  CHECK(run.now("Right").speed == Approx(10.0));
}

TEST_CASE("A random route is the same for the same seed", "[engine][route]") {
  engine::SimulationOptions options;
  options.seed = 7;
  FixtureRun a(engine_fixture("action_assign_route.xosc"), options);
  FixtureRun b(engine_fixture("action_assign_route.xosc"), options);
  a.run();
  b.run();
  CHECK(a.now("Random").pose.x == b.now("Random").pose.x);
  CHECK(a.now("Random").pose.y == b.now("Random").pose.y);
}

TEST_CASE("scenarios/route_waypoint.xosc: Ego turns left at the junction to its destination",
          "[engine][route][scenarios]") {
  FixtureRun run(std::filesystem::path(CORSA_SOURCE_DIR) / "scenarios/route_waypoint.xosc");
  run.run();
  CHECK(run.sim().end_reason() == engine::EndReason::kStopTrigger);
  // Through the left-turn connecting road 102 onto road 4, stopped within 1 m of s = 80.
  bool turned = false;
  for (const auto& [tick, states] : run.trace().ticks()) {
    const auto& road = states[run.entity("Ego")].road;
    turned = turned || (road && run.sim().road_id(road->road) == "102");
  }
  CHECK(turned);
  CHECK(final_road(run, "Ego") == "4");
  CHECK(run.now("Ego").road->s == Approx(80.0).margin(1.0));
  CHECK(run.sim().collisions().empty());
}

TEST_CASE("A route through a waypoint on another lane and a turn from the inner lane changes lanes",
          "[engine][route][lanes]") {
  FixtureRun run(engine_fixture("route_lane_waypoint.xosc"));
  run.run();
  CHECK(run.diagnostics().count(Severity::kWarning) == 0);
  // Ego starts on lane -1, is on the waypoint's lane -2 when it passes s = 90, back on lane -1
  // (the only one that leads to the left turn) before the junction, and turns left.
  CHECK(lane_passing(run, "Ego", "1", 11.0) == -1);
  CHECK(lane_passing(run, "Ego", "1", 90.0) == -2);
  CHECK(lane_passing(run, "Ego", "1", 195.0) == -1);
  CHECK(lane_passing(run, "Ego", "102", 0.0) == -1);
  CHECK(road_of(run, run.now("Ego")) == "3");
  CHECK(run.now("Ego").road->lane == -1);
  // AcquirePositionAction: from lane -2 onto road 3.
  CHECK(lane_passing(run, "Acquire", "1", 61.0) == -2);
  CHECK(lane_passing(run, "Acquire", "1", 195.0) == -1);
  CHECK(road_of(run, run.now("Acquire")) == "3");
  // Smooth sinusoidal lane changes over 4 s at 10 m/s: at most (pi / 2) 3.5 m / 4 s = 1.37 m/s.
  const double largest = check_smooth(run, "Ego", 1.45);
  CHECK(largest > 1.2);
  check_smooth(run, "Acquire", 1.45);
  CHECK(run.now("Ego").speed == Approx(10.0));
  CHECK(run.sim().collisions().empty());
}

TEST_CASE("Route lane changes are driven by the acc and dynamics controllers too",
          "[engine][route][lanes][controllers]") {
  for (const char* controller : {"acc", "dynamics"}) {
    engine::SimulationOptions options;
    options.controller = controller;
    FixtureRun run(engine_fixture("route_lane_waypoint.xosc"), options);
    run.run();
    INFO(controller);
    CHECK(run.diagnostics().count(Severity::kWarning) == 0);
    CHECK(lane_passing(run, "Ego", "1", 90.0) == -2);
    CHECK(road_of(run, run.now("Ego")) == "3");
    CHECK(run.now("Ego").road->lane == -1);
    CHECK(road_of(run, run.now("Acquire")) == "3");
    CHECK(std::abs(run.now("Ego").road->t - (-1.75)) < 0.3);
  }
}

// Steps of Stray (route_lane_blocked.xosc) whose length is not 0.1 m (10 m/s, 0.01 s) to 1 mm;
// checks every step within 0.01 m of it, a step onto or off a road within `crossing_margin`.
int stray_off_steps(FixtureRun& run, double crossing_margin) {
  const size_t index = run.entity("Stray");
  const engine::EntityState* previous = nullptr;
  int off_steps = 0;
  for (const auto& [tick, states] : run.trace().ticks()) {
    const engine::EntityState& now = states[index];
    if (previous != nullptr && tick > 1) {
      INFO("tick " << tick);
      const double step = std::hypot(now.pose.x - previous->pose.x, now.pose.y - previous->pose.y);
      const bool crossing = now.road.has_value() != previous->road.has_value() ||
                            (now.road && now.road->road != previous->road->road);
      CHECK(step == Approx(0.1).margin(crossing ? crossing_margin : 0.01));
      off_steps += std::abs(step - 0.1) > 0.001 ? 1 : 0;
    }
    previous = &now;
  }
  return off_steps;
}

TEST_CASE("A route that a lane change leaves for the oncoming lane warns once at the route",
          "[engine][route][lanes]") {
  FixtureRun run(engine_fixture("route_lane_oncoming.xosc"));
  run.run();
  // The LaneChangeAction takes Stray into lane 1, driven the other way, which has no lane end at
  // the junction on this map: it can be carried on along the route neither by its own lane nor
  // from the route's lane beside it, so it is off its route (it stops at road 1's end).
  CHECK(road_of(run, run.now("Stray")) == "1");
  CHECK(run.now("Stray").road->lane == 1);
  const auto warnings = all_text(run.diagnostics());
  CHECK(run.diagnostics().count(Severity::kWarning) == 1);
  CHECK_THAT(warnings, Catch::Contains("route_lane_oncoming.xosc:23: warning:"));
  CHECK_THAT(warnings, Catch::Contains("'Stray' cannot follow its route 'LeftTurn'"));
  CHECK_THAT(warnings, Catch::Contains("to road '102' (lane -1 does)"));
}

TEST_CASE(
    "An entity a lane change holds in the oncoming lane takes the route's way through the "
    "junction, without a warning",
    "[engine][route][lanes][semantics]") {
  // Lane 1 of road 1 ends at the junction too (connecting road 103, the way back from road 2),
  // but not along the route: Stray, on lane 1 there, takes the route's left turn (connecting
  // road 102) from lane -1 beside it and drives on along road 3 (heading north). It is not off
  // its route while its lane's end still leads on along it, so nothing warns (the warning used
  // to come when the lane change switched it to lane 1).
  for (const engine::Semantics semantics :
       {engine::Semantics::kStandard, engine::Semantics::kEsmini}) {
    engine::SimulationOptions options;
    options.semantics = semantics;
    FixtureRun run(engine_fixture("route_lane_oncoming_twoway.xosc"), options);
    run.run();
    INFO("semantics " << static_cast<int>(semantics));
    CHECK(run.at(5.0, "Stray").road->lane == 1);
    REQUIRE(run.now("Stray").road);
    CHECK(road_of(run, run.now("Stray")) == "3");
    CHECK(run.now("Stray").pose.h == Approx(std::numbers::pi / 2).margin(1e-6));
    CHECK(run.diagnostics().count(Severity::kWarning) == 0);
  }
}

TEST_CASE(
    "An entity held off its route's lane takes the route's way through the junction, keeping "
    "its lateral place",
    "[engine][route][lanes][semantics]") {
  // §6.8: routes define the decision behaviour at junctions; esmini reads it so too.
  engine::SimulationOptions options;
  FixtureRun run(engine_fixture("route_lane_blocked.xosc"), options);
  run.run();
  // Stray reaches the end of road 1 on lane -2, mid lane change (at 10 m/s, 80 m from s = 150:
  // 50 m done). It goes on along the route's connecting road 102 (a left turn, which only has
  // lane -1), as far right of that lane's centre as it was of lane -1's, and on along road 3
  // (heading north), instead of straight on to road 2 (heading east). No step jumps (a jump of
  // a lane would be 3.5 m). Off every lane of road 102 too, up to 5.25 m outside its 20 m
  // radius, the step is as long as the speed gives: 0.1 m at 10 m/s and 0.01 s (the lane
  // change's lateral motion adds at most 0.0003 m), where the reference line's s alone would
  // make it 26 % longer. The two steps that cross onto and off road 102 are scaled as where
  // they start: the one onto it (from the straight road 1, scale 1) starts at road 1's end,
  // so its whole 0.1 m of s lies on road 102 and it is 0.121 m long, within that 26 %.
  CHECK(stray_off_steps(run, 0.026) <= 2);
  CHECK(run.at(5.0, "Stray").road->lane == -2);
  CHECK(run.now("Stray").pose.h == Approx(std::numbers::pi / 2).margin(1e-6));
  CHECK(run.now("Stray").pose.x == Approx(225.25).margin(0.01));
  CHECK(all_text(run.diagnostics()).find("cannot follow its route") == std::string::npos);
  SECTION("esmini's reading takes the same way") {
    options.semantics = engine::Semantics::kEsmini;
    FixtureRun esmini(engine_fixture("route_lane_blocked.xosc"), options);
    esmini.run();
    // Its step onto road 102 starts 0.07 m before road 1's end: 0.106 m long.
    CHECK(stray_off_steps(esmini, 0.01) <= 2);
    CHECK(esmini.now("Stray").pose.h == Approx(std::numbers::pi / 2).margin(1e-6));
    CHECK(esmini.now("Stray").pose.x == Approx(225.25).margin(0.01));
    CHECK(all_text(esmini.diagnostics()).find("cannot follow its route") == std::string::npos);
  }
  SECTION("the dynamics controller steers along too") {
    options.controller = "dynamics";
    FixtureRun dynamics(engine_fixture("route_lane_blocked.xosc"), options);
    dynamics.run();
    CHECK(dynamics.now("Stray").pose.h == Approx(std::numbers::pi / 2).margin(0.05));
    CHECK(dynamics.now("Stray").pose.x == Approx(225.25).margin(0.5));
  }
}

TEST_CASE(
    "A route that only exists against a lane's direction of travel is driven so, with a "
    "warning",
    "[engine][route]") {
  FixtureRun run(engine_fixture("route_against_traffic.xosc"));
  run.run();
  // Lane 1 of right-hand traffic is driven toward -s; the route takes it toward +s.
  const auto& at = run.now("Wrong").road;
  REQUIRE(at);
  CHECK(at->lane == 1);
  CHECK(at->s == Approx(150.1).margin(0.2));
  const auto warnings = all_text(run.diagnostics());
  CHECK(run.diagnostics().count(Severity::kWarning) == 1);
  CHECK_THAT(warnings, Catch::Contains("route_against_traffic.xosc:26: warning:"));
  CHECK_THAT(warnings, Catch::Contains("route 'Upstream': waypoint 2 can be reached from waypoint "
                                       "1 only against the direction of travel (lane 1 of road 1 "
                                       "driven toward +s)"));
}

}  // namespace
}  // namespace corsa::test
