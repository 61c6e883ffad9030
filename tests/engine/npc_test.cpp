// Generated traffic never runs into anyone (controllers/npc_caution.h): NPCs start clear of
// everyone, vehicles keep out of the scenario's vehicles' way and stop at red lights, walkers
// pass each other.

#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "controllers/npc_caution.h"
#include "engine_fixture.h"

namespace corsa::test {
namespace {

std::filesystem::path demo() {
  return std::filesystem::path(CORSA_SOURCE_DIR) / "scenarios/demo/cut_in_city.xosc";
}

// Whether entity `i` of `sim` is one of its NPCs: these scenarios have no traffic actions, so
// the generated entities (those with lifetimes) are the NPCs.
bool is_npc(const engine::Simulation& sim, size_t i) { return !sim.lifetimes(i).empty(); }

bool is_npc_vehicle(const engine::Simulation& sim, size_t i) {
  return is_npc(sim, i) && sim.entity(i).kind == engine::ObjectKind::kVehicle;
}

}  // namespace

TEST_CASE("Over five seeds of the demo with NPCs no collision involves an NPC",
          "[engine][npc][collisions]") {
  // Before the NPCs took precautions: 15 such collisions over these seeds (walkers through
  // each other, the cutting-in car and the oncoming truck into NPC cars ahead of them).
  size_t npc_collisions = 0;
  std::string which;
  for (uint64_t seed = 0; seed < 5; ++seed) {
    engine::SimulationOptions options;
    options.seed = seed;
    options.npc.vehicles = 6;
    options.npc.pedestrians = 12;
    FixtureRun run(demo(), options);
    REQUIRE(run.sim().entity_count() == 3 + 6 + 12);
    run.run();
    for (const engine::CollisionRecord& c : run.sim().collisions()) {
      const std::string a = run.sim().entity(c.first).name;
      const std::string b = run.sim().entity(c.second).name;
      if (is_npc(run.sim(), c.first) || is_npc(run.sim(), c.second)) {
        ++npc_collisions;
        which += "seed " + std::to_string(seed) + " at " + std::to_string(c.time) + " s: " + a +
                 " and " + b + "\n";
      }
    }
  }
  INFO(which);
  CHECK(npc_collisions == 0);
}

TEST_CASE("At Town04's junction no two boxes overlap, the scenario's vehicles' and NPCs' alike",
          "[engine][npc][collisions]") {
  // The Ego stands on the driving lane before the junction and the truck crosses on its green.
  // With both on the border lanes (the Ego on a 0.64 m shoulder, the truck on the sidewalk
  // behind it, their lanes' centres 1.3 m apart) the truck drove through the Ego at 1.13 s and
  // NPC walkers into both.
  const auto scenario = std::filesystem::path(CORSA_SOURCE_DIR) / "scenarios/town04_junction.xosc";
  for (uint64_t seed = 0; seed < 5; ++seed) {
    INFO("seed " << seed);
    engine::SimulationOptions options;
    options.seed = seed;
    options.npc.vehicles = 20;
    options.npc.pedestrians = 10;
    FixtureRun run(scenario, options);
    engine::Simulation& sim = run.sim();
    REQUIRE(sim.entity_count() == 2 + 20 + 10);
    std::string overlaps;
    std::set<std::pair<size_t, size_t>> seen;
    do {
      for (size_t a = 0; a < sim.entity_count(); ++a) {
        for (size_t b = a + 1; b < sim.entity_count(); ++b) {
          // Each pair once, when its boxes first overlap.
          if (sim.colliding(a, b) && seen.emplace(a, b).second) {
            overlaps += std::to_string(sim.time()) + " s: " + sim.entity(a).name + " and " +
                        sim.entity(b).name + "\n";
          }
        }
      }
    } while (sim.step());
    CHECK(std::abs(sim.time() - 10.0) < 1e-9);  // the whole run, to the stop trigger
    INFO(overlaps);
    CHECK(overlaps.empty());
    CHECK(sim.collisions().empty());
  }
}

TEST_CASE("NPCs start clear of everyone and out of the path ahead of scenario vehicles",
          "[engine][npc]") {
  for (uint64_t seed = 0; seed < 5; ++seed) {
    INFO("seed " << seed);
    engine::SimulationOptions options;
    options.seed = seed;
    options.npc.vehicles = 12;
    options.npc.pedestrians = 30;
    FixtureRun run(demo(), options);
    engine::Simulation& sim = run.sim();
    for (size_t a = 0; a < sim.entity_count(); ++a) {
      for (size_t b = a + 1; b < sim.entity_count(); ++b) {
        INFO(sim.entity(a).name << " and " << sim.entity(b).name);
        CHECK_FALSE(sim.colliding(a, b));
      }
    }
    // No NPC vehicle within 60 m ahead of a scenario vehicle in its lane, going its way.
    for (size_t s = 0; s < 3; ++s) {
      const engine::EntityState& scenario = sim.state(s);
      for (size_t n = 3; n < sim.entity_count(); ++n) {
        const engine::EntityState& npc = sim.state(n);
        if (sim.entity(n).kind != engine::ObjectKind::kVehicle || !scenario.road || !npc.road ||
            npc.road->lane != scenario.road->lane) {
          continue;
        }
        const double ahead = (npc.pose.x - scenario.pose.x) * std::cos(scenario.pose.h) +
                             (npc.pose.y - scenario.pose.y) * std::sin(scenario.pose.h);
        INFO(sim.entity(n).name << " " << ahead << " m ahead of " << sim.entity(s).name);
        CHECK_FALSE((ahead > 0.0 && ahead < 60.0));
      }
    }
  }
}

TEST_CASE("A thousand NPC vehicles fit on Town04, off its junctions, no two boxes overlapping",
          "[engine][npc]") {
  // Town04's driving lanes off junctions hold about 850 vehicles 10 m apart; the rest go
  // between them, 6 m apart.
  const auto town04 = engine_fixture("npc_town04_empty.xosc");
  for (uint64_t seed = 1; seed <= 2; ++seed) {
    INFO("seed " << seed);
    engine::SimulationOptions options;
    options.seed = seed;
    options.npc.vehicles = 1000;
    FixtureRun run(town04, options);
    engine::Simulation& sim = run.sim();
    CHECK(run.diagnostics().all().empty());  // no "placed N of 1000" warning
    REQUIRE(sim.entity_count() == 1000);
    const xodr::Map& map = *sim.map();
    size_t on_junctions = 0, overlapping = 0, close = 0;
    for (size_t a = 0; a < sim.entity_count(); ++a) {
      const engine::EntityState& state = sim.state(a);
      REQUIRE(state.road);
      on_junctions += map.road(state.road->road).in_junction() ? 1 : 0;
      for (size_t b = a + 1; b < sim.entity_count(); ++b) {
        overlapping += sim.colliding(a, b) ? 1 : 0;
        const engine::Pose& other = sim.state(b).pose;
        close += std::hypot(state.pose.x - other.x, state.pose.y - other.y) < 6.0 ? 1 : 0;
      }
    }
    CHECK(on_junctions == 0);
    CHECK(overlapping == 0);
    CHECK(close == 0);
  }
}

TEST_CASE("A generated vehicle never takes the name of an entity of the scenario",
          "[engine][npc]") {
  // The scenario's own vehicle is called npc_vehicle_1, as --npc calls its second vehicle.
  engine::SimulationOptions options;
  options.seed = 1;
  options.npc.vehicles = 3;
  FixtureRun run(engine_fixture("npc_name_taken.xosc"), options);
  REQUIRE(run.sim().entity_count() == 4);
  std::set<std::string> names;
  for (size_t i = 0; i < run.sim().entity_count(); ++i) {
    names.insert(run.sim().entity(i).name);
  }
  CHECK(names == std::set<std::string>{"npc_vehicle_0", "npc_vehicle_1", "npc_vehicle_1_2",
                                       "npc_vehicle_2"});
  CHECK(run.entity("npc_vehicle_1") == 0);  // the scenario's, found by its name
  CHECK_FALSE(is_npc(run.sim(), 0));
  CHECK(all_text(run.diagnostics()).find("called 'npc_vehicle_1_2'") != std::string::npos);
}

TEST_CASE("Three hundred NPC vehicles on Town04 drive a minute without running into each other",
          "[engine][npc][collisions]") {
  // Before placement kept vehicles that could not stop apart at the crossings they share, the
  // claims pass braked only firmly and the acc controller took its set speed at once when let
  // go: 2 collisions over these seeds (seed 5, at 1.15 s and 1.24 s, both pairs placed at speed
  // about 10 m before their crossing).
  const auto town04 = engine_fixture("npc_town04_empty.xosc");
  std::string which;
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    engine::SimulationOptions options;
    options.seed = seed;
    options.npc.vehicles = 300;
    options.npc.pedestrians = 100;
    options.duration = 60.0;
    FixtureRun run(town04, options);
    REQUIRE(run.sim().entity_count() == 400);
    run.run();
    for (const engine::CollisionRecord& c : run.sim().collisions()) {
      const std::string a = run.sim().entity(c.first).name;
      const std::string b = run.sim().entity(c.second).name;
      if (is_npc_vehicle(run.sim(), c.first) && is_npc_vehicle(run.sim(), c.second)) {
        which += "seed " + std::to_string(seed) + " at " + std::to_string(c.time) + " s: " + a +
                 " and " + b + "\n";
      }
    }
  }
  INFO(which);
  CHECK(which.empty());
}

TEST_CASE("NPC vehicles stop at a red light and go on at green", "[engine][npc][signals]") {
  engine::SimulationOptions options;
  options.seed = 4;
  options.npc.vehicles = 4;
  FixtureRun run(engine_fixture("npc_signal.xosc"), options);
  engine::Simulation& sim = run.sim();
  // The NPCs driving toward +s that start before the light (s = 200 m).
  std::vector<size_t> waiting;
  for (size_t i = 1; i < sim.entity_count(); ++i) {
    const auto& road = sim.state(i).road;
    if (road && road->lane == -1 && road->s < 190.0) {
      waiting.push_back(i);
    }
  }
  REQUIRE(!waiting.empty());
  while (sim.time() < 14.5) {
    sim.step();
    for (const size_t i : waiting) {
      // The front (rear axle + 3.75 m of the car's box) stays behind the stop line.
      REQUIRE(sim.state(i).road);
      CHECK(sim.state(i).road->s + 3.75 < 200.0);
    }
  }
  for (const size_t i : waiting) {
    CHECK(sim.state(i).speed < 0.5);  // standing in the queue
  }
  run.run();
  for (const size_t i : waiting) {
    REQUIRE(sim.state(i).road);
    CHECK(sim.state(i).road->s > 200.0);  // through once green
  }
  CHECK(sim.collisions().empty());
}

TEST_CASE("Generated walkers on a busy sidewalk pass each other without touching",
          "[engine][npc]") {
  for (uint64_t seed = 0; seed < 3; ++seed) {
    INFO("seed " << seed);
    engine::SimulationOptions options;
    options.seed = seed;
    options.npc.pedestrians = 40;
    options.duration = 60.0;
    FixtureRun run(engine_fixture("npc_signal.xosc"), options);
    run.run();
    std::string which;
    for (const engine::CollisionRecord& c : run.sim().collisions()) {
      which += run.sim().entity(c.first).name + " and " + run.sim().entity(c.second).name + " at " +
               std::to_string(c.time) + " s\n";
    }
    INFO(which);
    CHECK(run.sim().collisions().empty());
  }
}

TEST_CASE("Traffic light states are read as red, yellow or go", "[engine][npc][signals]") {
  using engine::detail::signal_aspect;
  using engine::detail::SignalAspect;
  CHECK(signal_aspect("on;off;off") == SignalAspect::kStop);
  CHECK(signal_aspect("on;on;off") == SignalAspect::kStop);
  CHECK(signal_aspect("off;on;off") == SignalAspect::kCaution);
  CHECK(signal_aspect("off;off;on") == SignalAspect::kGo);
  CHECK(signal_aspect("Red") == SignalAspect::kStop);
  CHECK(signal_aspect("stop") == SignalAspect::kStop);
  CHECK(signal_aspect("amber") == SignalAspect::kCaution);
  CHECK(signal_aspect("green") == SignalAspect::kGo);
  CHECK(signal_aspect("flashing") == SignalAspect::kGo);
}

}  // namespace corsa::test
