// Traffic: signal controllers cycling through their phases with their conditions and actions
// (OpenSCENARIO 1.3 §6.5.2, §7.5.2), traffic swarms, sources, sinks and stops, TrafficAreaAction
// and TrafficDistribution (§7.5.6), pedestrians on sidewalks and crossing the road, and the NPCs
// of `--npc` as engine entities.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "engine_fixture.h"
#include "run_corsa.h"
#include "temp_dir.h"

namespace corsa::test {
namespace {

using Catch::Detail::Approx;
using engine::TransitionKind;

// The generated entities (those with lifetimes) of a finished run.
std::vector<size_t> generated(const corsa::engine::Simulation& sim) {
  std::vector<size_t> out;
  for (size_t i = 0; i < sim.entity_count(); ++i) {
    if (!sim.lifetimes(i).empty()) out.push_back(i);
  }
  return out;
}

TEST_CASE("Traffic signal controllers cycle through their phases; signal conditions and actions",
          "[engine][signals]") {
  FixtureRun run(engine_fixture("traffic_signal_phases.xosc"));
  corsa::engine::WorldSnapshot world;
  run.sim().fill_snapshot(world);
  const auto signal = [&](const std::string& id) -> std::string {
    for (const auto& s : world.signals) {
      if (s.id == id) return s.state;
    }
    return "";
  };
  CHECK(signal("1") == "off;off;on");
  CHECK(signal("2").empty());  // Side starts 1 s after Main
  run.run();
  // Main: go 0-5, caution 5-7, stop 7-10, go 10-15; forced to stop at 12 (run ends at 14).
  const auto main_stop = run.first("MainStop", TransitionKind::kStart);
  REQUIRE(main_stop);
  CHECK(*main_stop == Approx(7.0).margin(0.011));
  CHECK(run.count("SignalRed", TransitionKind::kStart) == 1);
  const auto red = run.first("SignalRed", TransitionKind::kStart);
  REQUIRE(red);
  CHECK(*red == Approx(7.0).margin(0.011));
  // Side: stop 1-5, go 5-11.
  const auto side_go = run.first("SideGoes", TransitionKind::kStart);
  REQUIRE(side_go);
  CHECK(*side_go == Approx(5.0).margin(0.011));
  // SideGoes set it to 2 at 5 s, SignalRed to 1 at 7 s.
  CHECK(run.sim().parameter("Dummy")->text() == "1");
  run.sim().fill_snapshot(world);
  CHECK(signal("3") == "flashing");
  // Forced to "stop" at 12 s, which lasts its 3 s: stop at the end (14 s), not "go".
  CHECK(signal("1") == "on;off;off");
  CHECK(run.now("Ego").speed == Approx(0.0));
}

TEST_CASE("A TrafficSignalGroupState sets every signal of the OpenDRIVE signal group",
          "[engine][signals]") {
  FixtureRun run(engine_fixture("traffic_signal_groups.xosc"));
  corsa::engine::WorldSnapshot world;
  const auto signal = [&](const std::string& id) -> std::string {
    for (const auto& s : world.signals) {
      if (s.id == id) return s.state;
    }
    return "";
  };
  // "stop" at 0 s: the map's <controller id="Crossing"> groups 7 and 8; 9 is not in it.
  run.sim().fill_snapshot(world);
  CHECK(signal("7") == "on;off;off");
  CHECK(signal("8") == "on;off;off");
  CHECK(signal("9").empty());
  // A state action naming the group (at 2.01 s) sets both; one naming signal 9 sets 9 only.
  while (run.sim().time() < 3.0) run.sim().step();
  run.sim().fill_snapshot(world);
  CHECK(signal("7") == "off;on;off");
  CHECK(signal("8") == "off;on;off");
  CHECK(signal("9") == "flashing");
  // "go" from 4 s: the group state, and signal 8's own TrafficSignalState over it.
  run.run();
  run.sim().fill_snapshot(world);
  CHECK(signal("7") == "off;off;on");
  CHECK(signal("8") == "off;on;off");
  CHECK(signal("9") == "flashing");
  const std::string text = all_text(run.diagnostics());
  CHECK_THAT(text, Catch::Contains("TrafficSignalStateAction names the signal group 'Crossing', "
                                   "not a signal (read as the state of each of its 2 signals)"));
  CHECK_THAT(text, Catch::Contains("TrafficSignalGroupState of TrafficSignalController 'Lone' "
                                   "sets no signal"));
  corsa::engine::SimulationOptions strict;
  strict.strict = true;
  FixtureRun strict_run(engine_fixture("traffic_signal_groups.xosc"), strict);
  CHECK_THROWS_WITH(strict_run.run(), Catch::Contains("names the signal group 'Crossing'") &&
                                          Catch::Contains("an error under --strict"));
}

TEST_CASE("A traffic swarm keeps its vehicles in the ring around the central entity, by the seed",
          "[engine][traffic]") {
  corsa::engine::SimulationOptions options;
  options.seed = 7;
  FixtureRun run(engine_fixture("traffic_swarm.xosc"), options);
  const size_t own = 1;
  size_t most = 0;
  while (run.sim().step()) {
    const auto& ego = run.now("Ego");
    size_t present = 0;
    const bool swarming = run.sim().time() < 20.0;  // TrafficStopAction at 20 s
    for (size_t i = own; i < run.sim().entity_count(); ++i) {
      const auto& s = run.sim().state(i);
      if (!s.placed) continue;
      ++present;
      REQUIRE(s.road);
      if (swarming) {
        // Inside the ellipse (semi-major 120 m along the road): leavers are removed at once.
        CHECK(std::abs(s.pose.x - ego.pose.x) <= 120.0);
        // DirectionOfTravelDistribution same="1" opposite="0": all drive Ego's way.
        CHECK(std::cos(s.pose.h - ego.pose.h) > 0.9);
      }
    }
    CHECK(present <= 8);
    most = std::max(most, present);
  }
  CHECK(most == 8);
  CHECK(run.sim().entity_count() >= 1 + 8);

  FixtureRun again(engine_fixture("traffic_swarm.xosc"), options);
  again.run();
  REQUIRE(again.sim().entity_count() == run.sim().entity_count());
  for (size_t i = 0; i < run.sim().entity_count(); ++i) {
    CHECK(again.sim().state(i).pose.x == run.sim().state(i).pose.x);
  }
  options.seed = 8;
  FixtureRun other(engine_fixture("traffic_swarm.xosc"), options);
  other.run();
  bool differs = other.sim().entity_count() != run.sim().entity_count();
  for (size_t i = 1; !differs && i < run.sim().entity_count(); ++i) {
    differs = other.sim().state(i).pose.x != run.sim().state(i).pose.x;
  }
  CHECK(differs);
}

TEST_CASE("A traffic source emits at its rate, a sink absorbs, a stop ends the source",
          "[engine][traffic]") {
  FixtureRun run(engine_fixture("traffic_source_sink.xosc"));
  run.run();
  // 0.5 vehicles/s from 0.1 s to 20 s: about 10 vehicles (the first at once).
  const size_t spawned = run.sim().entity_count() - 1;
  CHECK(spawned >= 9);
  CHECK(spawned <= 11);
  size_t present = 0;
  for (size_t i = 1; i < run.sim().entity_count(); ++i) {
    const auto& s = run.sim().state(i);
    if (s.placed) {
      ++present;
      // Nobody passed the sink at s = 400 (10 m radius).
      REQUIRE(s.road);
      CHECK(s.road->s < 411.0);
    }
  }
  // At 15 m/s the 350 m to the sink take 23 s: the vehicles of the first 17 s are gone by 40 s.
  CHECK(present < spawned);
  CHECK(present <= 3);
}

TEST_CASE("TrafficAreaAction on a road range keeps its number inside, replacing those that leave",
          "[engine][traffic][area]") {
  FixtureRun run(engine_fixture("traffic_area_road_range.xosc"));
  run.run();
  const auto& sim = run.sim();
  const auto ids = generated(sim);
  REQUIRE(ids.size() >= 6);
  // Every tick from 1 s on: at most 6 present, each on road 1, lane -1 or -2, s in [100, 400].
  size_t full_ticks = 0;
  for (const auto& [tick, states] : run.trace().ticks()) {
    if (tick < 100) continue;
    size_t present = 0;
    for (const size_t i : ids) {
      if (i >= states.size() || !states[i].placed) continue;
      ++present;
      REQUIRE(states[i].road);
      CHECK((states[i].road->lane == -1 || states[i].road->lane == -2));
      CHECK(states[i].road->s >= 100.0 - 0.2);  // spawned inside, driving toward +s
      CHECK(states[i].road->s <= 400.0 + 0.2);  // removed in the step they leave
    }
    CHECK(present <= 6);
    full_ticks += present == 6 ? 1 : 0;
  }
  CHECK(full_ticks > 3000);  // of about 3,900: the area is kept full
  // Those that drove out were removed (and respawned): lives with a removal time.
  size_t removed = 0;
  for (const size_t i : ids) {
    for (const auto& life : sim.lifetimes(i)) {
      if (life.removed) {
        ++removed;
        CHECK(*life.removed > life.spawned);
      }
    }
  }
  CHECK(removed >= 6);  // 300 m at 13.9 m/s: each lives about 20 s or less in 40 s
}

TEST_CASE("A controller setSpeed that is no number warns once and spawns at the speed limit",
          "[engine][traffic][area]") {
  FixtureRun run(engine_fixture("traffic_area_bad_set_speed.xosc"));
  run.run();
  const auto& sim = run.sim();
  size_t buses = 0;
  for (const size_t i : generated(sim)) {
    if (sim.entity(i).category != corsa::engine::EntityCategory::kBus) continue;
    const int64_t tick = std::llround(sim.lifetimes(i).front().spawned / sim.dt());
    const auto& state = run.trace().ticks().at(tick).at(i);
    REQUIRE(state.road);
    INFO(sim.entity(i).name << " on lane " << state.road->lane << " at " << state.speed << " m/s");
    CHECK(state.speed == Approx(state.road->lane == -1 ? 80.0 / 3.6 : 30.0 / 3.6).margin(0.1));
    ++buses;
  }
  CHECK(buses > 1);
  const std::string text = all_text(run.diagnostics());
  const std::string warning =
      "traffic_area_bad_set_speed.xosc:23: warning: controller property 'setSpeed' is not a "
      "non-negative number ('12 m/s'): its default is used";
  CHECK_THAT(text, Catch::Contains(warning));
  CHECK(text.find(warning) == text.rfind(warning));  // once, though every bus reads it
}

TEST_CASE("Area-spawned entities start at their entry's speed, their controller's, or the limit",
          "[engine][traffic][area]") {
  FixtureRun run(engine_fixture("traffic_area_speeds.xosc"));
  run.run();
  const auto& sim = run.sim();
  size_t cars_fast = 0, cars_town = 0, vans = 0, buses = 0;
  for (const size_t i : generated(sim)) {
    const auto& lives = sim.lifetimes(i);
    REQUIRE_FALSE(lives.empty());
    const int64_t tick = std::llround(lives.front().spawned / sim.dt());
    const auto& states = run.trace().ticks().at(tick);
    REQUIRE(i < states.size());
    const auto& state = states[i];
    REQUIRE(state.placed);
    REQUIRE(state.road);
    const auto category = sim.entity(i).category;
    INFO(sim.entity(i).name << " on lane " << state.road->lane << " at " << state.speed << " m/s");
    // Spawned at the tick; the controller has had at most one step (< 0.1 m/s) since.
    if (category == corsa::engine::EntityCategory::kVan) {
      CHECK(state.speed >= 5.0 - 0.1);
      CHECK(state.speed <= 6.0 + 0.1);
      ++vans;
    } else if (category == corsa::engine::EntityCategory::kBus) {
      CHECK(state.speed == Approx(12.0).margin(0.1));
      ++buses;
    } else if (state.road->lane == -1) {
      CHECK(state.speed == Approx(80.0 / 3.6).margin(0.1));  // the lane's own limit
      ++cars_fast;
    } else {
      CHECK(state.speed == Approx(30.0 / 3.6).margin(0.1));  // the road type's limit
      ++cars_town;
    }
  }
  CHECK(cars_fast > 0);
  CHECK(cars_town > 0);
  CHECK(vans > 0);
  CHECK(buses > 0);
}

TEST_CASE("TrafficDistribution weights pick the spawned objects and their boxes, by the seed",
          "[engine][traffic][distribution]") {
  FixtureRun run(engine_fixture("traffic_area_road_range.xosc"));
  run.run();
  size_t cars = 0, trucks = 0, lives = 0;
  for (const size_t i : generated(run.sim())) {
    const auto& info = run.sim().entity(i);
    const size_t n = run.sim().lifetimes(i).size();
    lives += n;
    if (info.category == corsa::engine::EntityCategory::kTruck) {
      CHECK(info.box.length == Approx(12.0));
      trucks += n;
    } else {
      CHECK(info.category == corsa::engine::EntityCategory::kCar);
      CHECK(info.box.length == Approx(4.6));
      cars += n;
    }
  }
  CHECK(lives >= 12);
  CHECK(cars > trucks);  // weights 3 : 1
  CHECK(trucks > 0);

  // A swarm with a one-template distribution spawns only that object, with its own controller.
  FixtureRun swarm(engine_fixture("traffic_distribution_swarm.xosc"));
  swarm.run();
  const auto vans = generated(swarm.sim());
  REQUIRE(vans.size() >= 6);
  for (const size_t i : vans) {
    CHECK(swarm.sim().entity(i).category == corsa::engine::EntityCategory::kVan);
    CHECK(swarm.sim().entity(i).box.length == Approx(5.2));
  }
}

TEST_CASE("A TrafficAreaAction that is not continuous spawns once inside its polygon",
          "[engine][traffic][area]") {
  corsa::engine::SimulationOptions options;
  options.seed = 7;
  FixtureRun run(engine_fixture("traffic_area_polygon.xosc"), options);
  run.run();
  const auto ids = generated(run.sim());
  REQUIRE(ids.size() == 5);
  const auto& first = run.trace().ticks().at(1);
  for (const size_t i : ids) {
    const auto lives = run.sim().lifetimes(i);
    REQUIRE(lives.size() == 1);
    CHECK(lives[0].spawned == Approx(0.01));  // all at the first step after Init
    CHECK_FALSE(lives[0].removed);            // they drive on, out of the area
    REQUIRE(i < first.size());
    CHECK(first[i].pose.x >= 200.0);
    CHECK(first[i].pose.x <= 500.0);
    CHECK(std::abs(first[i].pose.y) <= 12.0);
  }
  // 40 s later most have driven out of the rectangle, and none came in their place.
  size_t outside = 0;
  for (const size_t i : ids) {
    const double x = run.now(run.sim().entity(i).name).pose.x;
    outside += (x < 200.0 || x > 500.0) ? 1 : 0;
  }
  CHECK(outside >= 3);
  CHECK(run.sim().entity_count() == 6);  // Ego and the five
}

TEST_CASE("Generated traffic is the same for the same seed and differs for another",
          "[engine][traffic][area]") {
  const auto positions = [](uint64_t seed) {
    corsa::engine::SimulationOptions options;
    options.seed = seed;
    FixtureRun run(engine_fixture("traffic_area_road_range.xosc"), options);
    run.run();
    std::vector<double> out;
    for (size_t i = 0; i < run.sim().entity_count(); ++i) {
      out.push_back(run.sim().state(i).pose.x);
      out.push_back(run.sim().state(i).pose.y);
    }
    return out;
  };
  const auto a = positions(3);
  CHECK(a == positions(3));
  CHECK(a != positions(4));
}

TEST_CASE("Pedestrians walk along the sidewalk and cross the road", "[engine][pedestrians]") {
  FixtureRun run(engine_fixture("traffic_pedestrians.xosc"));
  run.run();
  const auto& walker = run.now("Walker");
  REQUIRE(walker.road);
  CHECK(walker.road->lane == -4);  // still on the sidewalk
  CHECK(walker.road->s == Approx(50.0 + 1.4 * 25.0).margin(0.05));
  // The crosser walks across the six 3.5 m lanes (t from about -11 to +10.5), then stops at the
  // far edge of the road.
  const auto& before = run.at(0.5, "Crosser");
  REQUIRE(before.road);
  CHECK(before.road->lane == -4);
  const auto& middle = run.at(9.0, "Crosser");
  REQUIRE(middle.road);
  CHECK(std::abs(middle.road->lane) <= 3);
  CHECK(middle.pose.x == Approx(before.pose.x).margin(1e-6));  // straight across
  const auto& end = run.now("Crosser");
  CHECK(end.speed == 0.0);
  CHECK(end.pose.y > 10.5);
  CHECK(end.pose.y < 10.5 + 0.1);
}

TEST_CASE("NPCs are engine entities: seeded places, vehicles driving, pedestrians walking",
          "[engine][npc]") {
  const auto start = [](uint64_t seed) {
    corsa::engine::SimulationOptions options;
    options.seed = seed;
    options.npc.vehicles = 5;
    options.npc.pedestrians = 3;
    return std::make_unique<FixtureRun>(engine_fixture("controller_acc.xosc"), options);
  };
  auto run = start(11);
  auto& sim = run->sim();
  REQUIRE(sim.entity_count() == 2 + 5 + 3);
  for (int k = 0; k < 5; ++k) {
    const auto& info = sim.entity(2 + k);
    CHECK(info.name == "npc_vehicle_" + std::to_string(k));
    CHECK(info.kind == corsa::engine::ObjectKind::kVehicle);
    const auto& s = sim.state(2 + k);
    REQUIRE(s.placed);
    REQUIRE(s.road);
    CHECK(s.road->lane != -4);  // not on the sidewalk
    CHECK(s.speed >= 8.0);
    CHECK(s.speed <= 14.0);
  }
  for (int k = 0; k < 3; ++k) {
    const auto& info = sim.entity(7 + k);
    CHECK(info.name == "npc_pedestrian_" + std::to_string(k));
    CHECK(info.kind == corsa::engine::ObjectKind::kPedestrian);
    const auto& s = sim.state(7 + k);
    REQUIRE(s.road);
    CHECK(s.road->lane == -4);  // straight.xodr's only sidewalk
    CHECK(s.speed >= 1.0);
    CHECK(s.speed <= 1.6);
  }
  // In the world the sensors see, like every entity.
  corsa::engine::WorldSnapshot world;
  sim.fill_snapshot(world);
  REQUIRE(world.entities.size() == 10);
  CHECK(world.entities[9].visible);
  const double x0 = sim.state(7).pose.x;
  while (sim.time() < 5.0) {
    sim.step();
  }
  // The pedestrian walked about 5-8 m along the sidewalk.
  CHECK(std::abs(sim.state(7).pose.x - x0) > 4.5);
  CHECK(std::abs(sim.state(7).pose.x - x0) < 8.5);
  REQUIRE(sim.state(7).road);
  CHECK(sim.state(7).road->lane == -4);
  // Same seed, same places at tick 0; another seed, others.
  const auto places = [](FixtureRun& r) {
    std::vector<double> out;
    for (size_t i = 2; i < r.sim().entity_count(); ++i) {
      out.push_back(r.sim().state(i).pose.x);
      out.push_back(r.sim().state(i).pose.y);
    }
    return out;
  };
  const auto a = places(*start(11));
  CHECK(a == places(*start(11)));
  CHECK(a != places(*start(12)));
}

TEST_CASE("corsa run --npc adds the NPCs, and the summary says when generated entities lived",
          "[engine][npc][cli]") {
  corsa::test::TempDir dir;
  const auto summary = dir.path() / "summary.json";
  const auto result = corsa::test::run_corsa(
      {"run", "tests/engine/fixtures/controller_acc.xosc", "--npc", "vehicles=2,pedestrians=1",
       "--seed", "5", "--duration", "2", "--summary", summary.string(), "--quiet"});
  INFO(result.err);
  REQUIRE(result.exit_code == 0);
  const std::string json = corsa::test::slurp(summary);
  CHECK_THAT(json, Catch::Contains("\"name\": \"npc_vehicle_1\""));
  CHECK_THAT(json, Catch::Contains("\"name\": \"npc_pedestrian_0\""));
  CHECK_THAT(json, Catch::Contains("\"generated\": true, \"present\": true, \"lifetimes\": "
                                   "[{\"spawned\": 0}]"));
  // The scenario's own entities keep the fields they had.
  const size_t lead = json.find("\"name\": \"Lead\"");
  REQUIRE(lead != std::string::npos);
  CHECK(json.substr(lead, json.find('}', lead) - lead).find("generated") == std::string::npos);

  const auto bad = corsa::test::run_corsa(
      {"run", "tests/engine/fixtures/controller_acc.xosc", "--npc", "cars=3", "--quiet"});
  CHECK(bad.exit_code == 2);
  CHECK_THAT(bad.err, Catch::Contains("--npc"));
}

}  // namespace
}  // namespace corsa::test
