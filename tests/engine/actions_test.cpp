// Actions: one focused fixture each (tests/engine/fixtures/action_*.xosc), and the entity
// actions (AddEntityAction, DeleteEntityAction, VisibilityAction) on one fixture.

#include <fstream>
#include <numbers>
#include <sstream>

#include "corsa/engine/outputs.h"
#include "engine_fixture.h"
#include "temp_dir.h"

namespace corsa::test {
namespace {

using Catch::Detail::Approx;
using engine::TransitionKind;

double wrap(double a) { return std::remainder(a, 2.0 * std::numbers::pi); }

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Rows of the trajectory CSV for an entity, as (time) values.
std::vector<double> row_times(const std::string& csv, const std::string& entity) {
  std::vector<double> times;
  std::istringstream lines(csv);
  std::string line;
  std::getline(lines, line);  // header
  while (std::getline(lines, line)) {
    const size_t a = line.find(',');
    const size_t b = line.find(',', a + 1);
    if (line.substr(a + 1, b - a - 1) == entity) {
      times.push_back(std::stod(line.substr(0, a)));
    }
  }
  return times;
}

TEST_CASE("SpeedAction follows each shape over time, rate and distance",
          "[engine][action][speed]") {
  FixtureRun run(engine_fixture("action_speed_shapes.xosc"));
  run.run();
  // The act starts at the first tick after 1 s: 1.01 s.
  SECTION("step changes at once") {
    CHECK(run.at(1.0, "Step").speed == 10.0);
    CHECK(run.at(1.02, "Step").speed == 20.0);
    CHECK(run.first("StepEvent::StepAction", TransitionKind::kEnd) == Approx(1.01));
  }
  SECTION("linear over 4 s is half way after 2 s") {
    CHECK(run.at(3.01, "LinearTime").speed == Approx(15.0));
    CHECK(run.at(5.01, "LinearTime").speed == Approx(20.0));
    CHECK(run.first("LinearTimeAction", TransitionKind::kEnd) == Approx(5.01));
  }
  SECTION("a rate of 2 m/s^2 takes 5 s for 10 m/s") {
    CHECK(run.at(3.51, "LinearRate").speed == Approx(15.0));
    CHECK(run.at(3.51, "LinearRate").acceleration == Approx(2.0));
    CHECK(run.first("LinearRateAction", TransitionKind::kEnd) == Approx(6.01));
  }
  SECTION("cubic over 75 m covers that distance with zero end slopes") {
    // Each step travels its end speed: dt / 2 times the 10 m/s gained beyond the 75 m.
    const double travelled =
        run.at(6.01, "CubicDistance").odometer - run.at(1.01, "CubicDistance").odometer;
    CHECK(travelled == Approx(75.0 + 0.05).margin(0.01));
    CHECK(run.at(3.51, "CubicDistance").speed == Approx(15.0));
    CHECK(std::abs(run.at(1.03, "CubicDistance").acceleration) < 0.1);
    CHECK(run.first("CubicDistanceAction", TransitionKind::kEnd) == Approx(6.01));
  }
  SECTION("sinusoidal braking stops the car and it stays stopped") {
    CHECK(run.at(2.01, "SineBrake").speed == Approx(5.0));
    CHECK(run.at(3.01, "SineBrake").speed == 0.0);
    CHECK(run.now("SineBrake").speed == 0.0);
    CHECK(run.now("SineBrake").pose.x == run.at(3.01, "SineBrake").pose.x);
  }
}

TEST_CASE("SpeedAction with a relative target tracks continuously or applies once",
          "[engine][action][speed]") {
  FixtureRun run(engine_fixture("action_speed_relative.xosc"));
  run.run();
  CHECK(run.at(3.01, "Tracker").speed == Approx(10.0));
  CHECK(run.at(8.0, "Lead").speed == 25.0);
  CHECK(run.at(8.0, "Tracker").speed == Approx(20.0));  // followed the lead's step
  CHECK(run.at(8.0, "Once").speed == Approx(7.5));      // factor 0.5 of 15, applied once
  CHECK(run.count("TrackEvent::Track", TransitionKind::kEnd) == 0);
  CHECK(run.first("TrackEvent::Track", TransitionKind::kStop) == Approx(8.01));
  CHECK(run.first("HalfEvent::Half", TransitionKind::kEnd) == Approx(1.01));
}

TEST_CASE("LaneChangeAction reaches relative and absolute target lanes", "[engine][action][lane]") {
  FixtureRun run(engine_fixture("action_lane_change.xosc"));
  run.run();
  SECTION("one lane to the left of the direction of travel, sinusoidal over 3 s") {
    CHECK(run.at(1.0, "Left").road->lane == -3);
    CHECK(run.at(2.51, "Left").road->t == Approx(-7.0));
    CHECK(run.at(2.51, "Left").pose.h > 0.08);  // turned toward the new lane
    CHECK(run.first("LeftEvent::ToLeft", TransitionKind::kEnd) == Approx(4.01));
    CHECK(run.now("Left").road->lane == -2);
    CHECK(run.now("Left").road->t == Approx(-5.25));
    CHECK(run.now("Left").pose.h == Approx(0.0).margin(1e-12));
  }
  SECTION("absolute lane with a target offset over 60 m") {
    // The lane gets what the path at the speed leaves beside the lateral motion: its 60 m take
    // three steps longer than at the speed.
    CHECK(run.first("AbsoluteEvent::ToLaneMinus3", TransitionKind::kEnd) == Approx(4.04));
    CHECK(run.now("Absolute").road->lane == -3);
    CHECK(run.now("Absolute").road->t == Approx(-8.25));
  }
  SECTION("left of a car driving toward -s is toward the centre line") {
    CHECK(run.first("OncomingEvent::ToItsLeft", TransitionKind::kEnd) == Approx(3.01));
    CHECK(run.at(2.01, "Oncoming").road->t == Approx(3.5));
    // The path is as long as the speed gives: the heading turns by asin(lateral / path).
    CHECK(wrap(run.at(2.01, "Oncoming").pose.h - std::numbers::pi) ==
          Approx(std::asin(1.75 / 20.0)));
    CHECK(run.now("Oncoming").road->lane == 1);
    CHECK(run.now("Oncoming").road->t == Approx(1.75));
    CHECK(run.now("Oncoming").pose.x < run.at(0.0, "Oncoming").pose.x);
  }
}

TEST_CASE(
    "A teleport during a lane change onto a road without the target lane ends the change "
    "with a warning",
    "[engine][action][lane]") {
  FixtureRun run(engine_fixture("action_teleport_lane_change_no_lane.xosc"));
  run.run();
  // Road 3 has lanes 1 and -1 only: the change to lane -2 ends where the teleport put the car,
  // on lane -1's centre, and stays there.
  const auto warnings = all_text(run.diagnostics());
  CHECK(run.diagnostics().count(Severity::kWarning) == 1);
  CHECK_THAT(warnings, Catch::Contains("action_teleport_lane_change_no_lane.xosc:31: warning:"));
  CHECK_THAT(warnings, Catch::Contains("the TeleportAction put entity 'Car' where its road has no "
                                       "lane -2; the lane change ends there"));
  const auto ended = run.first("ChangeAction", engine::TransitionKind::kEnd);
  REQUIRE(ended);
  CHECK(*ended == Approx(2.01).margin(0.011));
  CHECK(run.sim().road_id(run.now("Car").road->road) == "3");
  CHECK(run.now("Car").road->lane == -1);
  CHECK(run.now("Car").road->t == Approx(-1.75).margin(1e-9));
  CHECK(run.at(3.0, "Car").road->t == Approx(-1.75).margin(1e-9));
}

TEST_CASE("LaneOffsetAction respects maxLateralAcc and a continuous relative offset tracks",
          "[engine][action][lane]") {
  FixtureRun run(engine_fixture("action_lane_offset.xosc"));
  run.run();
  // Sinusoidal, 1 m at 0.5 m/s^2: pi seconds.
  CHECK(run.first("ShiftEvent::Shift", TransitionKind::kEnd) == Approx(4.16));
  CHECK(run.now("Shifter").road->t == Approx(-4.25));
  CHECK(run.now("Shifter").road->lane == -2);
  CHECK(run.now("Shadow").road->t == Approx(-8.75 + 1.0 - 0.5));
  CHECK(run.count("ShadowEvent::Mirror", TransitionKind::kEnd) == 0);
}

TEST_CASE("A continuous LaneOffsetAction relative to the actor itself moves once, with a warning",
          "[engine][action][lane]") {
  FixtureRun run(engine_fixture("action_lane_offset_self.xosc"));
  run.run();
  // Lane -2's centre is at t = -5.25; +1 along t from there, sinusoidal at 1 m/s^2 (2.22 s from
  // 1 s), then held: tracking its own offset it would drift a metre a step.
  CHECK(run.at(2.0, "Drifter").road->t > -5.25);
  CHECK(run.at(2.0, "Drifter").road->t < -4.25);
  CHECK(run.at(3.5, "Drifter").road->t == Approx(-4.25).margin(1e-9));
  CHECK(run.now("Drifter").road->t == Approx(-4.25).margin(1e-9));
  CHECK(run.now("Drifter").road->lane == -2);
  const auto warnings = all_text(run.diagnostics());
  CHECK(run.diagnostics().count(Severity::kWarning) == 1);
  CHECK_THAT(warnings, Catch::Contains("action_lane_offset_self.xosc:34: warning: LaneOffsetAction "
                                       "of 'Drifter' is relative to itself"));
}

TEST_CASE("Lane offsets are along the lane's t-axis, also for cars driving toward -s",
          "[engine][action][lane]") {
  FixtureRun run(engine_fixture("action_lane_offset_t_axis.xosc"));
  run.run();
  // Left lanes (centres t = 1.75 and 5.25), driven toward -s: +1 is toward the road's +t, to
  // the right of the car; the relative offset adds to West's offset along t too.
  CHECK(run.now("West").road->t == Approx(2.75).margin(1e-9));
  CHECK(run.now("Mirror").road->t == Approx(5.25 + 1.0 + 0.5).margin(1e-9));
  CHECK(run.now("Changer").road->lane == 1);
  CHECK(run.now("Changer").road->t == Approx(1.25).margin(1e-9));
  // Driving toward +s the t-axis is the car's left.
  CHECK(run.now("East").road->t == Approx(-0.75).margin(1e-9));
}

TEST_CASE("TeleportAction places entities at every road-based and world position",
          "[engine][action][teleport]") {
  FixtureRun run(engine_fixture("action_teleport_positions.xosc"));
  const auto& w = run.now("W");
  CHECK(w.pose.x == 100.0);
  CHECK(w.road->lane == -2);
  CHECK(w.road->s == Approx(100.0));
  CHECK(run.now("RW").pose.x == 120.0);  // placed after W although written before it
  CHECK(run.now("RO").pose.x == Approx(140.0));
  CHECK(run.now("RO").road->lane == -1);
  CHECK(run.now("R").road->lane == -3);
  CHECK(run.now("RR").road->s == Approx(230.0));
  CHECK(run.now("RR").road->lane == -2);
  const auto& lane = run.now("L");
  CHECK(lane.road->t == Approx(5.45));
  CHECK(std::abs(wrap(lane.pose.h - std::numbers::pi)) < 1e-12);  // faces its lane's direction
  const auto& rl = run.now("RL");
  CHECK(rl.road->lane == 1);
  CHECK(rl.road->s == Approx(280.0));
  CHECK(rl.road->t == Approx(1.75));
  const auto& t = run.now("T");
  CHECK(t.pose.x == Approx(430.0));
  CHECK(t.pose.y == Approx(-2.25));
  run.run();
  CHECK(run.now("W").pose.x == 100.0);  // no speed: nobody moved
}

TEST_CASE("TeleportAction during the run reaches GeoPositions and trajectory positions",
          "[engine][action][teleport]") {
  FixtureRun run(engine_fixture("action_teleport_story.xosc"));
  run.run();
  // The map's geoReference is a transverse Mercator with an <offset>; the latitude and longitude
  // were computed for map point (250, -5.25) with Snyder's inverse formulas.
  const auto& geo = run.at(1.02, "Jumper");
  CHECK(geo.pose.x == Approx(250.0).margin(0.01));
  CHECK(geo.pose.y == Approx(-5.25).margin(0.01));
  CHECK(geo.road->lane == -2);
  // Clothoid from (600, -5.25), curvature 0 growing 0.001 /m^2 over 30 m (numerical integral).
  const auto& curl = run.at(2.02, "Jumper");
  CHECK(curl.pose.x == Approx(629.3981687713404).margin(1e-6));
  CHECK(curl.pose.y == Approx(-0.8146713831652308).margin(1e-6));
  CHECK(curl.pose.h == Approx(0.45));
  CHECK(curl.road->lane == -1);
}

TEST_CASE("a GeoPosition the map-to-Earth transform cannot serve is a located error",
          "[engine][action][teleport]") {
  SECTION("the transform cannot be made") {
    engine::SimulationOptions options;
    options.geo_projection = [](const std::string& crs) -> engine::GeographicToMap {
      throw InputError(make_error("", 0, "PROJ cannot read '" + crs.substr(0, 11) + "'"));
    };
    FixtureRun run(engine_fixture("action_teleport_story.xosc"), options);
    CHECK_THROWS_WITH(run.run(), Catch::Contains("action_teleport_story.xosc:31: error: PROJ "
                                                 "cannot read '+proj=tmerc'"));
  }
  SECTION("the point is outside the CRS") {
    engine::SimulationOptions options;
    options.geo_projection = [](const std::string&) -> engine::GeographicToMap {
      return [](double, double) { return std::optional<Vec2>(); };
    };
    FixtureRun run(engine_fixture("action_teleport_story.xosc"), options);
    CHECK_THROWS_WITH(run.run(), Catch::Contains("action_teleport_story.xosc:31: error: latitude "
                                                 "37.49995264447614, longitude "
                                                 "127.00282837009718 is outside the map's "
                                                 "geoReference '+proj=tmerc"));
  }
}

TEST_CASE("TeleportAction to RoutePositions measures path s along the route",
          "[engine][action][teleport][route]") {
  FixtureRun run(engine_fixture("action_teleport_route.xosc"));
  // 490 m on road 1, then road 2 (reversed, lane 1) from s = 300 down: path s 600 is road 2 s 190.
  const auto& on_lane = run.now("OnLane");
  CHECK(run.sim().road_id(on_lane.road->road) == "2");
  CHECK(on_lane.road->lane == 1);
  CHECK(on_lane.pose.x == Approx(610.0));
  CHECK(on_lane.pose.y == Approx(-1.75));
  CHECK(on_lane.pose.h == Approx(0.0).margin(1e-12));  // lane 1's traffic, the route's way
  // 490 + 300 + 20 m of junction: path s 850 is 40 m into road 3.
  const auto& on_road = run.now("OnRoad");
  CHECK(run.sim().road_id(on_road.road->road) == "3");
  CHECK(on_road.road->lane == -2);
  CHECK(on_road.pose.x == Approx(860.0));
}

TEST_CASE("ParameterAction and VariableAction change the values conditions compare",
          "[engine][action][parameter]") {
  SECTION("parameters") {
    FixtureRun run(engine_fixture("action_parameters.xosc"));
    run.run();
    CHECK(run.sim().parameter("Count")->text() == "5");
    CHECK(run.sim().parameter("Flag")->text() == "true");
    CHECK(run.first("Reaction::M::Stop", TransitionKind::kStart) == Approx(1.01));
    CHECK(run.now("Car").speed == 0.0);
  }
  SECTION("variables") {
    FixtureRun run(engine_fixture("action_variables.xosc"));
    run.run();
    CHECK(run.sim().variable("Gain")->number() == Approx(5.0));
    CHECK(run.sim().variable("Mode")->text() == "braking");
    CHECK(run.first("Reaction::M::Stop", TransitionKind::kStart) == Approx(1.01));
  }
}

TEST_CASE("EnvironmentAction sets the state the sensors see; time of day animates",
          "[engine][action][environment]") {
  FixtureRun run(engine_fixture("action_environment.xosc"));
  engine::WorldSnapshot snapshot;
  run.sim().fill_snapshot(snapshot);
  CHECK(snapshot.environment.time_of_day == Approx(11 * 3600 + 59 * 60 + 58));
  CHECK(snapshot.environment.fog_visual_range == 800.0);
  CHECK(snapshot.environment.precipitation == engine::PrecipitationType::kRain);
  CHECK(snapshot.environment.precipitation_intensity == 2.5);
  CHECK(snapshot.environment.cloud_cover == 0.5);
  CHECK(snapshot.environment.sun_azimuth == 1.5);
  CHECK(snapshot.environment.road_friction_scale == 0.7);
  CHECK(snapshot.environment.wet_road);
  REQUIRE(snapshot.entities.size() == 1);
  CHECK(snapshot.entities[0].name == "Car");
  CHECK(snapshot.entities[0].instance_id == 1);
  for (int i = 0; i < 150; ++i) {
    run.sim().step();
  }
  run.sim().fill_snapshot(snapshot);
  CHECK(snapshot.environment.time_of_day == Approx(11 * 3600 + 59 * 60 + 59.5));
  run.run();
  // TimeOfDayCondition >= 12:00:00 rises 2 s into the run.
  CHECK(run.first("Noon", TransitionKind::kStart) == Approx(2.0));
  CHECK(run.sim().environment().fog_visual_range == 50.0);
  run.sim().fill_snapshot(snapshot);
  CHECK(snapshot.environment.time_of_day == Approx(18.5 * 3600));  // no longer animated
}

TEST_CASE("CustomCommandAction reaches the handler of its type", "[engine][action][custom]") {
  FixtureRun run(engine_fixture("action_custom_command.xosc"));
  std::vector<std::pair<double, std::string>> calls;
  run.sim().set_custom_command_handler(
      "test:mark", [&](const xosc::UserDefinedAction& action, const engine::Simulation& sim) {
        calls.emplace_back(sim.time(), action.content);
      });
  run.run();
  REQUIRE(calls.size() == 2);
  CHECK(calls[0] == std::make_pair(0.0, std::string("init")));
  CHECK(calls[1].first == Approx(1.01));
  CHECK(calls[1].second == "one");
  bool warned = false;
  for (const auto& d : run.diagnostics().all()) {
    warned = warned || d.message.find("'test:nobody' has no handler") != std::string::npos;
  }
  CHECK(warned);
}

TEST_CASE(
    "An added entity appears at its position, a deleted one disappears from rows and conditions",
    "[engine][entities]") {
  corsa::test::TempDir dir;
  FixtureRun run(engine_fixture("entity_add_delete_visibility.xosc"));
  corsa::engine::TrajectoryRecorder recorder(dir.path() / "out.csv", 1);
  run.sim().add_observer(recorder);
  run.run();
  recorder.finish(run.sim());

  CHECK_FALSE(run.at(1.0, "Late").placed);
  const auto& added = run.at(2.5, "Late");
  REQUIRE(added.placed);
  REQUIRE(added.road);
  CHECK(added.road->lane == -3);
  CHECK(added.road->s == Approx(100.0).margin(0.5));
  CHECK(run.at(5.0, "Late").speed == Approx(8.0));  // its own action moved it once added

  CHECK(run.at(3.9, "Gone").placed);
  CHECK_FALSE(run.at(4.1, "Gone").placed);
  // The speed condition on Gone (faster than 5 m/s, after 4.5 s) never holds once it is gone.
  CHECK_FALSE(run.first("GoneFast", TransitionKind::kStart));

  const std::string csv = read_text(dir.path() / "out.csv");
  const auto late = row_times(csv, "Late");
  REQUIRE_FALSE(late.empty());
  CHECK(late.front() >= 2.0);
  const auto gone = row_times(csv, "Gone");
  REQUIRE_FALSE(gone.empty());
  CHECK(gone.back() < 4.1);
  CHECK(row_times(csv, "Ego").size() > late.size());
}

TEST_CASE("VisibilityAction hides the entity from the sensors in the world snapshot",
          "[engine][entities]") {
  FixtureRun run(engine_fixture("entity_add_delete_visibility.xosc"));
  corsa::engine::WorldSnapshot world;
  const size_t late = run.entity("Late");
  while (run.sim().time() < 2.5) {
    run.sim().step();
  }
  run.sim().fill_snapshot(world);
  CHECK(world.entities[late].visible);
  while (run.sim().time() < 3.5) {
    run.sim().step();
  }
  run.sim().fill_snapshot(world);
  CHECK_FALSE(world.entities[late].visible);
  CHECK_FALSE(run.now("Late").visible);
  run.run();
  run.sim().fill_snapshot(world);
  CHECK_FALSE(world.entities[run.entity("Gone")].visible);  // deleted
}

TEST_CASE("VisibilityAction's SensorReferenceSet makes the entity seen only by the sensors named",
          "[engine][entities]") {
  FixtureRun run(engine_fixture("visibility_sensor_refs.xosc"));
  corsa::engine::WorldSnapshot world;
  const size_t car = run.entity("Car");
  const auto seen = [&](std::string_view sensor) {
    return corsa::engine::visible_to(world.entities[car], sensor);
  };
  const auto at = [&](double t) {
    while (run.sim().time() < t) run.sim().step();
    run.sim().fill_snapshot(world);
  };
  at(0.5);
  CHECK(seen("front camera"));
  CHECK(seen("rear camera"));
  CHECK(world.entities[car].sensor_exceptions.empty());
  // sensors="true" for "front camera" and "lidar": the others, implicitly, do not see it.
  at(1.5);
  CHECK(seen("front camera"));
  CHECK(seen("lidar"));
  CHECK_FALSE(seen("rear camera"));
  CHECK_FALSE(world.entities[car].visible);
  // sensors="false" for "front camera": every other sensor sees it.
  at(2.5);
  CHECK_FALSE(seen("front camera"));
  CHECK(seen("lidar"));
  CHECK(seen("rear camera"));
  // Without a set, the flag holds for every sensor again.
  at(3.5);
  CHECK(seen("front camera"));
  CHECK(seen("rear camera"));
  CHECK(world.entities[car].sensor_exceptions.empty());
  CHECK_THAT(all_text(run.diagnostics()), !Catch::Contains("SensorReferenceSet"));
}

}  // namespace
}  // namespace corsa::test
