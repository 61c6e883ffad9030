// What used to warn and complete at once now runs: monitors, lights, animations, user-defined
// values, random routes; a controller the engine does not have is stood in for and listed; the
// run-time lenient readings (the centre lane, an s past the road's end, a deleted entity's last
// position) and their --strict form; esmini's frame of a relative orientation on a lane.

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <utility>

#include "corsa/engine/outputs.h"
#include "corsa/engine/world_snapshot.h"
#include "engine_fixture.h"
#include "temp_dir.h"

using corsa::test::engine_fixture;
using corsa::test::FixtureRun;

namespace {

const corsa::engine::EntitySnapshot& snapshot_of(const corsa::engine::WorldSnapshot& world,
                                                 const std::string& name) {
  for (const auto& entity : world.entities) {
    if (entity.name == name) return entity;
  }
  FAIL("no entity " << name << " in the snapshot");
  return world.entities.front();
}

corsa::engine::SimulationOptions with_gap(const std::string& gap) {
  corsa::engine::SimulationOptions options;
  options.values = {{"Gap", gap}};
  return options;
}

}  // namespace

TEST_CASE("SetMonitorAction sets the scenario's verdicts, which the summary reports",
          "[engine][compat][monitors]") {
  FixtureRun run(engine_fixture("compat_appearance_values.xosc"));
  run.run();
  const auto monitors = run.sim().monitors();
  REQUIRE(monitors.size() == 2);
  CHECK(monitors[0] == std::pair<std::string, bool>{"Passed", true});
  CHECK(monitors[1] == std::pair<std::string, bool>{"Untouched", false});
  const std::string summary = corsa::engine::summary_json(run.sim(), 0.0);
  CHECK_THAT(summary, Catch::Contains("\"monitors\": {\"Passed\": true, \"Untouched\": false}"));
}

TEST_CASE("a light switched by LightStateAction and an animation reach the world snapshot",
          "[engine][compat][appearance]") {
  using corsa::engine::light_bit;
  using corsa::engine::VehicleLight;
  FixtureRun run(engine_fixture("compat_appearance_values.xosc"));
  corsa::engine::WorldSnapshot world;
  // The low beam is switched on at the first step past 0.5 s; the door opens from 1 s over 1 s.
  while (run.sim().time() < 0.45) run.sim().step();
  run.sim().fill_snapshot(world);
  CHECK((snapshot_of(world, "Car").lights_set & light_bit(VehicleLight::kLowBeam)) == 0);
  CHECK(snapshot_of(world, "Car").animations.empty());
  while (run.sim().time() < 1.505) run.sim().step();
  run.sim().fill_snapshot(world);
  const auto& halfway = snapshot_of(world, "Car");
  CHECK((halfway.lights_set & light_bit(VehicleLight::kLowBeam)) != 0);
  CHECK((halfway.lights_on & light_bit(VehicleLight::kLowBeam)) != 0);
  REQUIRE(halfway.animations.size() == 1);
  CHECK(halfway.animations[0].type == "doorFrontLeft");
  CHECK(halfway.animations[0].state == Approx(0.4).margin(0.02));
  run.run();
  run.sim().fill_snapshot(world);
  const auto& end = snapshot_of(world, "Car");
  REQUIRE(end.animations.size() == 1);
  CHECK(end.animations[0].state == Approx(0.8));
  CHECK(snapshot_of(world, "Far").lights_set == 0);
  CHECK(snapshot_of(world, "Far").animations.empty());
}

TEST_CASE("UserDefinedValueConditions compare with values given from outside",
          "[engine][compat][values]") {
  FixtureRun wide(engine_fixture("compat_appearance_values.xosc"), with_gap("5"));
  wide.run();
  CHECK(wide.sim().variable("Reacted")->text() == "true");
  FixtureRun narrow(engine_fixture("compat_appearance_values.xosc"), with_gap("2"));
  narrow.run();
  CHECK(narrow.sim().variable("Reacted")->text() == "false");
  // Set during the run, as a driver model or the Python module would.
  FixtureRun later(engine_fixture("compat_appearance_values.xosc"));
  while (later.sim().time() < 2.0) later.sim().step();
  CHECK(later.sim().variable("Reacted")->text() == "false");
  CHECK_THAT(corsa::test::all_text(later.diagnostics()),
             Catch::Contains("no value 'Gap' is given (corsa run --value Gap=...)"));
  later.sim().set_user_value("Gap", "10");
  later.run();
  CHECK(later.sim().variable("Reacted")->text() == "true");
}

TEST_CASE("an entity whose controller the engine lacks runs under acc, and the summary says so",
          "[engine][compat][controllers]") {
  FixtureRun run(engine_fixture("compat_appearance_values.xosc"));
  run.run();
  CHECK(run.sim().controller_substitute(run.entity("Car")) == "AEBController");
  CHECK(run.sim().controller_substitute(run.entity("Far")).empty());
  const std::string summary = corsa::engine::summary_json(run.sim(), 0.0);
  CHECK_THAT(summary, Catch::Contains("\"controller\": \"acc\", \"substitute_for\": "
                                      "\"AEBController\""));
  CHECK_THAT(corsa::test::all_text(run.diagnostics()),
             Catch::Contains("controller 'AEBController' is not one of this engine's") &&
                 Catch::Contains("stands in for it on 'Car'"));
}

TEST_CASE("a LanePosition on the centre lane and an s past the road's end are read leniently",
          "[engine][compat][lenient]") {
  FixtureRun run(engine_fixture("compat_appearance_values.xosc"));
  run.run();
  // laneId 0 is the reference line: offset -1.75 m puts the car in lane -1.
  const auto& car = run.at(0.0, "Car");
  REQUIRE(car.road);
  CHECK(car.road->lane == -1);
  CHECK(car.road->t == Approx(-1.75));
  // s 1010 on a 1000 m road: at its end, with a warning.
  const auto& far = run.at(0.0, "Far");
  REQUIRE(far.road);
  CHECK(far.road->s == Approx(1000.0));
  CHECK_THAT(corsa::test::all_text(run.diagnostics()),
             Catch::Contains("s = 1010 is outside road '1' (length 1000 m) (read as s = 1000, "
                             "the road's end)"));
  corsa::engine::SimulationOptions strict;
  strict.strict = true;
  CHECK_THROWS_WITH(FixtureRun(engine_fixture("compat_appearance_values.xosc"), strict),
                    Catch::Contains("s = 1010 is outside road '1'") &&
                        Catch::Contains("an error under --strict"));
}

TEST_CASE("a relative orientation on a left lane turns from the lane's direction of travel",
          "[engine][compat][positions]") {
  // Lanes 1 and 2 of the straight road (heading 0) run towards -s in right-hand traffic: without
  // an Orientation a car there faces pi. Relative h = pi turns from the lane's direction of
  // travel back to +s, under either reading (as esmini turns it).
  FixtureRun standard(engine_fixture("compat_esmini_readings.xosc"));
  standard.run();
  CHECK(std::cos(standard.at(0.0, "Left").pose.h) == Approx(-1.0));
  CHECK(std::cos(standard.at(0.0, "LeftTurned").pose.h) == Approx(1.0));
  corsa::engine::SimulationOptions options;
  options.semantics = corsa::engine::Semantics::kEsmini;
  FixtureRun esmini(engine_fixture("compat_esmini_readings.xosc"), options);
  esmini.run();
  CHECK(std::cos(esmini.at(0.0, "Left").pose.h) == Approx(-1.0));
  CHECK(std::cos(esmini.at(0.0, "LeftTurned").pose.h) == Approx(1.0));
  CHECK(esmini.at(0.0, "LeftTurned").pose.y > 0.0);
}

TEST_CASE("an s far past the road's end is the road's end, with a warning",
          "[engine][compat][lenient]") {
  FixtureRun run(engine_fixture("compat_esmini_readings.xosc"));
  run.run();
  const auto& far = run.at(0.0, "Far");
  REQUIRE(far.road);
  CHECK(far.road->s == Approx(1000.0));
  CHECK_THAT(corsa::test::all_text(run.diagnostics()),
             Catch::Contains("s = 1400 is outside road '1' (length 1000 m) (read as s = 1000, "
                             "the road's end)"));
  corsa::engine::SimulationOptions strict;
  strict.strict = true;
  CHECK_THROWS_WITH(FixtureRun(engine_fixture("compat_esmini_readings.xosc"), strict),
                    Catch::Contains("s = 1400 is outside road '1'") &&
                        Catch::Contains("an error under --strict"));
}

TEST_CASE("an entity added relative to itself after its deletion starts where it was deleted",
          "[engine][compat][lenient]") {
  FixtureRun run(engine_fixture("compat_esmini_readings.xosc"));
  run.run();
  // The conditions hold at 1.01 s and 2.01 s; their actions act on the next step: deleted from
  // 1.02 s where it was at 1.01 s (10 m/s from s 20), added again at 2.02 s 50 m further on,
  // at the 10 m/s it was deleted at (as esmini's re-added entity), so that it drives that step
  // on from there (0.1 m) and on.
  const auto& deleted = run.at(1.5, "Gone");
  CHECK(!deleted.placed);
  CHECK(deleted.pose.x == Approx(30.1));
  const auto& added = run.at(2.02, "Gone");
  CHECK(added.placed);
  CHECK(added.pose.x == Approx(deleted.pose.x + 50.0 + 0.1));
  CHECK(added.speed == Approx(10.0));
  CHECK(run.at(2.5, "Gone").pose.x == Approx(added.pose.x + 10.0 * 0.48).margin(1e-6));
  CHECK_THAT(corsa::test::all_text(run.diagnostics()),
             Catch::Contains("entity 'Gone' is referenced after it was deleted (read as the "
                             "position it was deleted at)"));
  // The same under esmini's reading.
  corsa::engine::SimulationOptions options;
  options.semantics = corsa::engine::Semantics::kEsmini;
  FixtureRun esmini(engine_fixture("compat_esmini_readings.xosc"), options);
  esmini.run();
  CHECK(esmini.at(2.5, "Gone").speed == Approx(10.0));
  CHECK(esmini.at(2.5, "Gone").pose.x > esmini.at(2.02, "Gone").pose.x + 4.0);
}

namespace {

// The tower's hitch and the trailer's coupler, world x/y.
std::pair<double, double> point_ahead(const corsa::engine::EntityState& state, double dx) {
  return {state.pose.x + dx * std::cos(state.pose.h), state.pose.y + dx * std::sin(state.pose.h)};
}

}  // namespace

TEST_CASE("a Vehicle's inline trailer is an entity towed behind it, through a lane change",
          "[engine][compat][trailer]") {
  FixtureRun run(engine_fixture("compat_trailer.xosc"));
  run.run();
  REQUIRE(run.sim().entity_count() == 2);
  CHECK(run.sim().entity(1).name == "Box");
  double largest_angle = 0.0;
  for (const auto& [tick, states] : run.trace().ticks()) {
    const auto hitch = point_ahead(states[0], 0.5);
    const auto coupler = point_ahead(states[1], 8.0);
    INFO("tick " << tick);
    CHECK(std::hypot(hitch.first - coupler.first, hitch.second - coupler.second) < 1e-6);
    largest_angle = std::max(largest_angle, std::abs(states[0].pose.h - states[1].pose.h));
  }
  // The trailer starts in line, lags the tractor's turns, and is straight again at the end.
  CHECK(run.at(0.0, "Box").pose.h == Approx(run.at(0.0, "Tractor").pose.h));
  CHECK(largest_angle > 0.01);
  CHECK(run.now("Box").pose.h == Approx(run.now("Tractor").pose.h).margin(0.01));
  CHECK(run.now("Box").speed == Approx(15.0).margin(0.05));
  CHECK(run.sim().collisions().empty());  // the tractor and its trailer touch at the hitch
}

TEST_CASE("a trailer no ScenarioObject names is called after its tower, as esmini calls it",
          "[engine][compat][trailer]") {
  // esmini's catalogs write a <Vehicle> or <CatalogReference> directly in <Trailer> (a lenient
  // reading): the file names no trailer entity, and esmini calls it "<tower>+" (its
  // lane_change_trig_by_variable's rows have "Truck+"), so Corsa does too, also down a chain.
  FixtureRun run(engine_fixture("compat_trailer_esmini_form.xosc"));
  run.run();
  REQUIRE(run.sim().entity_count() == 3);
  CHECK(run.sim().entity(0).name == "Tractor");
  CHECK(run.sim().entity(1).name == "Tractor+");
  CHECK(run.sim().entity(2).name == "Tractor++");
  // Still towed: each coupler on its tower's hitch.
  const auto hitch = point_ahead(run.now("Tractor"), 0.5);
  const auto coupler = point_ahead(run.now("Tractor+"), 8.0);
  CHECK(std::hypot(hitch.first - coupler.first, hitch.second - coupler.second) < 1e-6);
  const auto second_hitch = point_ahead(run.now("Tractor+"), -3.0);
  const auto second_coupler = point_ahead(run.now("Tractor++"), 5.0);
  CHECK(std::hypot(second_hitch.first - second_coupler.first,
                   second_hitch.second - second_coupler.second) < 1e-6);
}

TEST_CASE("ConnectTrailerAction hooks a standing trailer up, DisconnectTrailerAction leaves it",
          "[engine][compat][trailer]") {
  FixtureRun run(corsa::test::asam("TrailerConnect.xosc"), corsa::test::with_duration(30));
  run.run();
  const auto connected = run.first("ConnectAction", corsa::engine::TransitionKind::kEnd);
  const auto released = run.first("DisconnectAction", corsa::engine::TransitionKind::kEnd);
  REQUIRE(connected);
  REQUIRE(released);
  // While connected the coupler (3.25 m ahead) is on the car's hitch (1.2 m behind).
  for (double t = *connected + 0.01; t < *released - 0.005; t += 0.5) {
    const auto hitch = point_ahead(run.at(t, "Car"), -1.2);
    const auto coupler = point_ahead(run.at(t, "Trailer"), 3.25);
    INFO("t = " << t);
    CHECK(std::hypot(hitch.first - coupler.first, hitch.second - coupler.second) < 1e-6);
  }
  // Standing before, moved by the car while connected, standing after.
  CHECK(run.at(*connected - 0.5, "Trailer").speed == 0.0);
  CHECK(std::abs(run.at(*released - 0.5, "Trailer").speed) > 3.0);
  const auto left = run.at(*released + 0.5, "Trailer").pose;
  CHECK(run.now("Trailer").pose.x == left.x);
  CHECK(run.now("Trailer").pose.y == left.y);
  // The car keeps reversing at 4 m/s after its trajectory ends (2 s before the connection), into
  // the standing trailer: that contact is the scenario's; none while they are connected.
  for (const auto& collision : run.sim().collisions()) CHECK(collision.time < *connected);
}

namespace {

/// The look of `light` in `entity`'s snapshot, or null.
const corsa::engine::LightLook* look_of(const corsa::engine::EntitySnapshot& entity,
                                        corsa::engine::VehicleLight light) {
  for (const auto& look : entity.light_looks) {
    if (look.light == light) return &look;
  }
  return nullptr;
}

}  // namespace

TEST_CASE("a LightStateAction fades linearly over its transitionTime to its intensity and colour",
          "[engine][compat][appearance]") {
  using corsa::engine::light_bit;
  using corsa::engine::VehicleLight;
  FixtureRun run(engine_fixture("light_fades.xosc"));
  corsa::engine::WorldSnapshot world;
  const double dt = run.sim().dt();
  const double red_cd = 100.0 / 0.2126;  // 100 cd of pure red: luminance 0.2126 per unit of red
  // Each action starts at the first step past its trigger time.
  auto start_after = [&](double t) { return (std::floor(t / dt + 1e-9) + 1.0) * dt; };
  auto at = [&](double t) -> const corsa::engine::EntitySnapshot& {
    while (run.sim().time() < t - 1e-9) run.sim().step();
    run.sim().fill_snapshot(world);
    return snapshot_of(world, "Car");
  };
  SECTION("a light set without intensity, colour or fade has no look") {
    const auto& car = at(0.8);
    CHECK((car.lights_on & light_bit(VehicleLight::kLowBeam)) != 0);
    CHECK(look_of(car, VehicleLight::kLowBeam) == nullptr);
    const auto* brake = look_of(car, VehicleLight::kBrake);
    REQUIRE(brake != nullptr);
    CHECK(brake->fixed_cd[0] == Approx(red_cd));
    CHECK(brake->fixed_cd[1] == 0.0);
    CHECK(brake->lamp_colour_cd == 0.0);
  }
  SECTION("the brake lamp fades from red at 100 cd to its own colour at 300 cd over 2 s") {
    const double since = start_after(1.0);
    for (const double into : {0.5, 1.0, 1.5}) {
      const auto& car = at(since + into);
      const double done = into / 2.0;
      const auto* brake = look_of(car, VehicleLight::kBrake);
      REQUIRE(brake != nullptr);
      INFO("t = " << run.sim().time());
      CHECK(brake->fixed_cd[0] == Approx((1.0 - done) * red_cd));
      CHECK(brake->lamp_colour_cd == Approx(done * 300.0));
      CHECK(brake->lamp_share == 0.0);
      CHECK((car.lights_on & light_bit(VehicleLight::kBrake)) != 0);
    }
    const auto& done = at(since + 2.5);
    const auto* brake = look_of(done, VehicleLight::kBrake);
    REQUIRE(brake != nullptr);  // still a luminous intensity
    CHECK(brake->fixed_cd[0] == 0.0);
    CHECK(brake->lamp_colour_cd == Approx(300.0));
  }
  SECTION("the low beam fades out over 1 s, lit until it has faded") {
    const double since = start_after(2.0);
    const auto& quarter = at(since + 0.25);
    const auto* beam = look_of(quarter, VehicleLight::kLowBeam);
    REQUIRE(beam != nullptr);
    CHECK(beam->lamp_share == Approx(0.75));
    CHECK((quarter.lights_on & light_bit(VehicleLight::kLowBeam)) != 0);
    const auto& off = at(since + 1.2);
    CHECK(look_of(off, VehicleLight::kLowBeam) == nullptr);
    CHECK((off.lights_on & light_bit(VehicleLight::kLowBeam)) == 0);
    CHECK((off.lights_set & light_bit(VehicleLight::kLowBeam)) != 0);
  }
  SECTION(
      "a flashing light without durations is on 0.5 s and off 0.5 s, the class model's default") {
    const double since = start_after(0.5);
    const uint32_t bit = light_bit(VehicleLight::kWarning);
    const std::pair<double, bool> samples[] = {{0.05, true},  {0.45, true}, {0.55, false},
                                               {0.95, false}, {1.05, true}, {1.45, true},
                                               {1.55, false}};
    for (const auto& [into, lit] : samples) {
      INFO("into the flashing " << into << " s");
      const auto& car = at(since + into);
      CHECK(((car.lights_on & bit) != 0) == lit);
      // Flashing in its off phase too, as the scenario set it.
      CHECK((car.lights_flashing & bit) != 0);
      const auto setting =
          std::find_if(car.light_settings.begin(), car.light_settings.end(),
                       [](const auto& s) { return s.light == VehicleLight::kWarning; });
      REQUIRE(setting != car.light_settings.end());
      CHECK(setting->mode == corsa::engine::LightMode::kFlashing);
      CHECK(setting->since == Approx(since));
      CHECK(setting->on_s == 0.5);
      CHECK(setting->off_s == 0.5);
    }
  }
  SECTION("the snapshot and the run's record keep the lights as they were set, in order") {
    const auto& car = at(2.5);
    // Brake (set twice), low beam (fading out: lit, its mode already off), warning lights.
    REQUIRE(car.light_settings.size() == 3);
    CHECK(car.light_settings[0].light == VehicleLight::kLowBeam);
    CHECK(car.light_settings[0].mode == corsa::engine::LightMode::kOff);
    CHECK(car.light_settings[0].transition_s == 1.0);
    CHECK((car.lights_on & light_bit(VehicleLight::kLowBeam)) != 0);
    CHECK(car.light_settings[1].light == VehicleLight::kBrake);
    CHECK(car.light_settings[1].candela == 300.0);
    CHECK(!car.light_settings[1].rgb);
    CHECK(car.lights_flashing == light_bit(VehicleLight::kWarning));
    const auto changes = run.sim().light_changes();
    REQUIRE(changes.size() == 5);
    // Three set at the first step past 0.5 s in document order, then 1 s and 2 s.
    CHECK(changes[0].setting.light == VehicleLight::kBrake);
    CHECK(changes[0].setting.rgb == std::array<double, 3>{1.0, 0.0, 0.0});
    CHECK(changes[0].setting.candela == 100.0);
    CHECK(changes[1].setting.light == VehicleLight::kLowBeam);
    CHECK(changes[2].setting.light == VehicleLight::kWarning);
    CHECK(changes[3].setting.since == Approx(start_after(1.0)));
    CHECK(changes[4].setting.mode == corsa::engine::LightMode::kOff);
    const std::string summary = corsa::engine::summary_json(run.sim(), 0.0);
    CHECK_THAT(summary, Catch::Contains("{\"time\": 2.01, \"light\": \"lowBeam\", \"mode\": "
                                        "\"off\", \"transition_time\": 1}"));
  }
}
