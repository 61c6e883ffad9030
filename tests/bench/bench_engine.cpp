// Engine stepping throughput (target: above 2 million entity-steps per second on a
// 100-vehicle scenario). 100 cars on the bundled 2 km motorway, 50 each way in three lanes,
// every one with an event that changes its speed after a few seconds and every tenth a lane
// change; each iteration runs 10 s of simulated time (1,000 steps of 0.01 s) on a fresh
// Simulation built from the loaded scenario and map (building it is timed apart).
//
//   corsa_bench_engine [--benchmark_repetitions=5]   (Release build; median of the repetitions)

#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/engine/run.h"
#include "corsa/engine/simulation.h"
#include "corsa/xodr/map.h"
#include "corsa/xosc/scenario.h"
#include "motorway_fleet.h"

namespace {

constexpr int kVehicles = 100;
constexpr int kSteps = 1000;

// Vehicle i: lane 1..3 (toward -s) for even i, -1..-3 (toward +s) for odd i, 40 m apart; a speed
// change after 1-6 s; every tenth on an outer lane moves one lane in (to the left of its
// direction of travel) once it has driven 60 m.
std::vector<corsa::test::FleetVehicle> fleet() {
  std::vector<corsa::test::FleetVehicle> vehicles;
  for (int i = 0; i < kVehicles; ++i) {
    corsa::test::FleetVehicle v;
    v.name = "V" + std::to_string(i);
    v.lane = (i % 2 == 0 ? 1 : -1) * (1 + (i / 2) % 3);
    const int slot = i / 6;
    v.s = v.lane > 0 ? 1900.0 - 40.0 * slot : 100.0 + 40.0 * slot;
    v.speed = 25 + (i % 7);
    v.max_speed = 60.0;
    v.max_acceleration = 6.0;
    v.max_deceleration = 9.0;
    v.speed_change = corsa::test::FleetVehicle::SpeedChange{22.0 + (i % 5), 3.0, 1.0 + i % 6};
    if (i % 10 == 0) {
      corsa::test::FleetVehicle::LaneChange change;
      change.lanes = (i / 2) % 3 == 2 ? 1 : 0;
      change.duration = 3.0;
      change.after_traveled = 60.0;
      v.lane_change = change;
    }
    vehicles.push_back(v);
  }
  return vehicles;
}

struct Fixture {
  corsa::Diagnostics diagnostics;
  corsa::xosc::Scenario scenario;
  std::shared_ptr<const corsa::xodr::Map> map;

  Fixture()
      : scenario(corsa::xosc::parse_scenario(
            corsa::test::motorway_fleet_scenario(fleet(), "100 vehicles"),
            corsa::test::motorway_fleet_path(), {}, diagnostics)),
        map(corsa::engine::load_road_network(scenario, diagnostics)) {}
};

Fixture& fixture() {
  static Fixture instance;  // built once, read-only afterwards
  return instance;
}

void BM_Step100Vehicles(benchmark::State& state) {
  Fixture& f = fixture();
  int64_t entity_steps = 0;
  for (auto _ : state) {
    state.PauseTiming();
    corsa::engine::Simulation sim(f.scenario, f.map, {}, f.diagnostics);
    state.ResumeTiming();
    for (int i = 0; i < kSteps; ++i) {
      sim.step();
    }
    entity_steps += static_cast<int64_t>(kSteps) * kVehicles;
    benchmark::DoNotOptimize(sim.state(0).pose.x);
  }
  state.counters["entity_steps_per_s"] =
      benchmark::Counter(static_cast<double>(entity_steps), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Step100Vehicles)->Unit(benchmark::kMillisecond);

void BM_Build100Vehicles(benchmark::State& state) {
  Fixture& f = fixture();
  for (auto _ : state) {
    corsa::engine::Simulation sim(f.scenario, f.map, {}, f.diagnostics);
    benchmark::DoNotOptimize(sim.entity_count());
  }
}
BENCHMARK(BM_Build100Vehicles)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
