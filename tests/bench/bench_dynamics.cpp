// The dynamics controller on a 50-vehicle scenario (target: above 100x real time).
// 50 cars on the bundled 2 km motorway, 25 each way in three lanes 50 m apart, each with a
// speed change after a few seconds and every fifth a lane change; all under `--controller
// dynamics` (SimulationOptions::controller). Each repetition runs 30 s of simulated time
// (3,000 steps of 0.01 s) on a fresh Simulation; the default controller is timed alongside.
//
//   corsa_bench_dynamics [REPETITIONS] [CONTROLLER...]
//
// Release build; prints the median of the repetitions (default 5) for each controller (default:
// dynamics, acc, default), and the load average, since wall time on a shared machine includes
// waiting for a core. Instruction counts of one controller's run, which do not depend on the
// load: valgrind --tool=callgrind corsa_bench_dynamics 1 dynamics

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/engine/run.h"
#include "corsa/engine/simulation.h"
#include "corsa/xodr/map.h"
#include "corsa/xosc/scenario.h"
#include "motorway_fleet.h"

namespace {

constexpr int kVehicles = 50;
constexpr double kSimSeconds = 30.0;

// The 50 cars: 25 each way in three lanes 50 m apart, each changing speed after 2-9 s, every
// fifth changing lanes (toward the middle lane) after 12-17 s.
std::vector<corsa::test::FleetVehicle> fleet() {
  std::vector<corsa::test::FleetVehicle> vehicles;
  for (int i = 0; i < kVehicles; ++i) {
    corsa::test::FleetVehicle v;
    v.name = "D" + std::to_string(i);
    v.lane = (i % 2 == 0 ? -1 : 1) * (1 + (i / 2) % 3);
    const int slot = i / 6;
    v.s = v.lane < 0 ? 100.0 + 50.0 * slot : 1900.0 - 50.0 * slot;
    v.speed = 24 + i % 5;
    v.speed_change = corsa::test::FleetVehicle::SpeedChange{20.0 + i % 7, 4.0, 2.0 + i % 8};
    if (i % 5 == 0) {
      // Toward the middle lane: the outer lanes move left, the others right.
      const int delta = std::abs(v.lane) == 1 ? -1 : 1;
      v.lane_change.emplace();
      v.lane_change->lanes = std::abs(v.lane) == 2 ? 0 : delta;
      v.lane_change->after = 12.0 + i % 6;
    }
    vehicles.push_back(v);
  }
  return vehicles;
}

struct Timing {
  double wall = 0.0;  ///< s
  double cpu = 0.0;   ///< s of this process's CPU time (the machine is shared: wall time includes
                      ///< waiting for a core)
};

// Median wall and CPU times (s) of `repetitions` runs of kSimSeconds under `controller`.
Timing median_run(const corsa::xosc::Scenario& scenario,
                  const std::shared_ptr<const corsa::xodr::Map>& map, const std::string& controller,
                  int repetitions, corsa::Diagnostics& diagnostics) {
  std::vector<double> walls, cpus;
  for (int r = 0; r < repetitions; ++r) {
    corsa::engine::SimulationOptions options;
    options.duration = kSimSeconds;
    options.controller = controller;
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    corsa::engine::Simulation sim(scenario, map, options, diagnostics);
    sim.run();
    cpus.push_back(static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC);
    walls.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(walls.begin(), walls.end());
  std::sort(cpus.begin(), cpus.end());
  return {walls[walls.size() / 2], cpus[cpus.size() / 2]};
}

}  // namespace

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  std::vector<std::string> controllers(argv + std::min(argc, 2), argv + argc);
  if (controllers.empty()) {
    controllers = {"dynamics", "acc", "default"};
  }
  corsa::Diagnostics diagnostics;
  const auto scenario = corsa::xosc::parse_scenario(
      corsa::test::motorway_fleet_scenario(fleet(), "50 vehicles, dynamics"),
      corsa::test::motorway_fleet_path(), {}, diagnostics);
  const auto map = corsa::engine::load_road_network(scenario, diagnostics);
  for (const std::string& controller : controllers) {
    const Timing t = median_run(scenario, map, controller, repetitions, diagnostics);
    std::printf(
        "%-8s %d vehicles, %.0f s simulated: median %.3f s wall (%.0fx real time), %.3f s CPU "
        "(%.0fx)\n",
        controller.c_str(), kVehicles, kSimSeconds, t.wall, kSimSeconds / t.wall, t.cpu,
        kSimSeconds / t.cpu);
  }
  double load[3] = {0.0, 0.0, 0.0};
  if (getloadavg(load, 3) == 3) {
    std::printf("load average %.2f %.2f %.2f\n", load[0], load[1], load[2]);
  }
  return 0;
}
