// Issue #6 (traffic, continued) and issue #9's NPCs: car following along the lane path,
// TrafficDistribution, TrafficAreaAction, NPCs as engine entities, spawn and removal times.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "engine_fixture.h"
#include "run_corsa.h"
#include "temp_dir.h"

namespace {

using corsa::test::engine_fixture;
using corsa::test::FixtureRun;

std::filesystem::path asam(const std::string& name) {
  return std::filesystem::path(CORSA_SHARED_DIR) / "conformance/asam-osc-1.3" / name;
}

bool collided(const corsa::engine::Simulation& sim, size_t a) {
  for (const auto& c : sim.collisions()) {
    if (c.first == a || c.second == a) return true;
  }
  return false;
}

}  // namespace

TEST_CASE("The acc controller follows a standing vehicle just across a road link",
          "[engine][acc]") {
  FixtureRun run(engine_fixture("traffic_follow_across_link.xosc"));
  run.run();
  CHECK(run.sim().collisions().empty());
  const auto& follower = run.now("Follower");
  const auto& lead = run.now("Lead");
  REQUIRE(follower.road);
  // The follower drove through the link onto road 2 (lane 1, toward -s) and waits behind.
  CHECK(run.sim().road_id(follower.road->road) == "2");
  CHECK(follower.road->lane == 1);
  CHECK(follower.speed < 0.5);
  // Bumper to bumper: lead rear (x 550 + 1.4 - 2.25) minus follower front (x + 1.4 + 2.25).
  const double gap = (lead.pose.x + 1.4 - 2.25) - (follower.pose.x + 1.4 + 2.25);
  CHECK(gap > 2.5);
  CHECK(gap < 6.0);
}

TEST_CASE("ASAM TrafficJam: Ego drives into the jam as asked, and stops before it under acc",
          "[engine][acc][asam]") {
  // The scenario gives Ego 36.1 m/s and no controller: an ideal driver meets the standing A5
  // (same lane, 151 m ahead) after about 4 s. That collision is what the scenario asks for.
  FixtureRun ideal(asam("TrafficJam.xosc"));
  ideal.run();
  REQUIRE_FALSE(ideal.sim().collisions().empty());
  const auto& first = ideal.sim().collisions().front();
  CHECK(first.time == Approx(4.05).margin(0.05));
  CHECK(ideal.sim().entity(first.first).name == "Ego");
  CHECK(ideal.sim().entity(first.second).name == "A5");

  // With a car-following driver Ego stops behind A5: no collision at all.
  corsa::engine::SimulationOptions options;
  options.controller = "acc";
  FixtureRun acc(asam("TrafficJam.xosc"), options);
  acc.run();
  CHECK_FALSE(collided(acc.sim(), acc.entity("Ego")));
  CHECK(acc.now("Ego").speed < 5.0);  // from 36.1 m/s, still creeping up at the 10 s stop
  CHECK(acc.now("Ego").pose.y < acc.now("A5").pose.y - 4.5);
}

namespace {

// The generated entities (those with lifetimes) of a finished run.
std::vector<size_t> generated(const corsa::engine::Simulation& sim) {
  std::vector<size_t> out;
  for (size_t i = 0; i < sim.entity_count(); ++i) {
    if (!sim.lifetimes(i).empty()) out.push_back(i);
  }
  return out;
}

}  // namespace

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
