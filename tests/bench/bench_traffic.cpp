// City-scale traffic and long runs (targets: 1,000 car-following vehicles on Town04 at 20x real
// time or more on 2 cores; 800 vehicles in at most 10x the time of 100; recording a trajectory
// at most 10% of a long run's time).
//
//   corsa_bench_traffic [--runs N] [--part scale|long|all] [--vehicles N] [--threads T]
//                       [--seconds S] [--copies K] [--out DIR]
//
// scale: `--npc vehicles=N` on ../shared/data/xodr/Town04.xodr (an empty scenario of its own), N
//   from 100 to 1,000, 10 s simulated (1,000 steps of 0.01 s) on a fresh Simulation per run;
//   the NPCs' placement is timed apart from the steps. 1,000 and 800 vehicles also on 2 threads.
//   Printed: median wall and CPU time of the steps, the real-time factor (simulated / wall),
//   microseconds per vehicle-step, and the 800 / 100 ratio (100 vehicles is the baseline).
//   `--vehicles N` runs only N vehicles (on `--threads T`, default 1) and `--seconds S`
//   simulates S seconds instead of 10: a short run of one size for a profiler (perf, callgrind;
//   `valgrind --tool=callgrind --separate-threads=yes` counts each thread's part). With
//   `--copies K`, K simulations of N vehicles take a step each in turn: the memory a step of
//   K x N vehicles touches at the density of N (whether a larger run costs more per vehicle-step
//   because of its density or because of its memory). Copy k runs with seed k, so the copies
//   place their vehicles in different places (the map's memory of K x N vehicles too).
// long: the 1,200 s scenarios of tests/bench/scenarios (long_standstill: seven vehicles that
//   stop within 40 s and stand; long_motorway: 24 car followers on the Town04 motorway loop),
//   each without a trajectory (the baseline), with the CSV and with the binary trajectory
//   (.corsatraj); median CPU time of the whole run (load, simulate, write) and the recording's
//   share, and the median system time of the runs with a trajectory (the kernel's part of
//   writing it: most of it is not the recorder's to save). The files go to a new folder in
//   `--out DIR` (default: the temporary folder; /dev/shm keeps the disk out of the figures).
// Release build; medians of `runs` (default 5) repetitions, alternating the variants within
// each repetition so that a change in the machine's load hits them alike. The load average is
// printed: on the shared machine wall time includes waiting for a core.

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "bench_util.h"
#include "corsa/core/diagnostic.h"
#include "corsa/engine/run.h"
#include "corsa/engine/simulation.h"
#include "corsa/xodr/map.h"
#include "corsa/xosc/scenario.h"

namespace {

using corsa::bench::median;
using corsa::bench::process_cpu_ms;
using Clock = std::chrono::steady_clock;

/// What the command line asks for.
struct Settings {
  int runs = 5;
  std::string part = "all";
  uint32_t vehicles = 0;  ///< only this many (on `threads`); 0: every size
  unsigned threads = 1;   ///< with `vehicles`
  double seconds = 10.0;  ///< simulated per traffic run
  uint32_t copies = 1;    ///< with `vehicles`: this many simulations stepped in turn
  std::filesystem::path out = std::filesystem::temp_directory_path();  ///< long runs' files
};

double load_average() {
  double load[1] = {0.0};
  return getloadavg(load, 1) == 1 ? load[0] : -1.0;
}

std::string shared(const std::string& relative) {
  return (std::filesystem::path(CORSA_SHARED_DIR) / relative).lexically_normal().string();
}

// An empty scenario on Town04: the NPCs are the only entities.
const char* kTown04 =
    "<?xml version=\"1.0\"?><OpenSCENARIO><FileHeader revMajor=\"1\" revMinor=\"3\" "
    "date=\"2026-01-01T00:00:00\" description=\"NPC traffic on Town04\" author=\"Corsa\"/>"
    "<ParameterDeclarations/><CatalogLocations/><RoadNetwork><LogicFile filepath=\"%s\"/>"
    "</RoadNetwork><Entities/><Storyboard><Init><Actions/></Init><StopTrigger/></Storyboard>"
    "</OpenSCENARIO>";

struct StepTiming {
  double place_ms = 0.0;  ///< building the Simulation (NPC placement), wall
  double wall_ms = 0.0;   ///< the steps
  double cpu_ms = 0.0;
};

StepTiming step_npcs(const corsa::xosc::Scenario& scenario,
                     const std::shared_ptr<const corsa::xodr::Map>& map, uint32_t vehicles,
                     unsigned threads, double seconds, uint32_t copies) {
  corsa::Diagnostics diagnostics;
  corsa::engine::SimulationOptions options;
  options.duration = seconds;
  options.npc.vehicles = vehicles;
  options.threads = threads;
  StepTiming timing;
  const auto built = Clock::now();
  std::vector<std::unique_ptr<corsa::engine::Simulation>> sims;
  for (uint32_t k = 0; k < copies; ++k) {
    options.seed = k;  // copies place their vehicles apart, over as much of the map as more would
    sims.push_back(
        std::make_unique<corsa::engine::Simulation>(scenario, map, options, diagnostics));
    sims.back()->step();  // tick 0's observers and the first step belong to the run
  }
  timing.place_ms = std::chrono::duration<double, std::milli>(Clock::now() - built).count();
  const auto start = Clock::now();
  const double cpu = process_cpu_ms();
  // Copies take a step each in turn: the memory of copies x vehicles, the density of vehicles.
  bool running = true;
  while (running) {
    for (auto& sim : sims) {
      running = sim->step() && running;
    }
  }
  timing.wall_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  timing.cpu_ms = process_cpu_ms() - cpu;
  for (const auto& sim : sims) {
    if (sim->entity_count() != vehicles) {
      std::fprintf(stderr, "only %zu of %u NPCs placed\n", sim->entity_count(), vehicles);
      std::exit(1);
    }
  }
  return timing;
}

void scale(const Settings& settings) {
  const int runs = settings.runs;
  corsa::Diagnostics diagnostics;
  char text[1024];
  std::snprintf(text, sizeof text, kTown04, shared("data/xodr/Town04.xodr").c_str());
  const auto scenario = corsa::xosc::parse_scenario(
      text, std::filesystem::current_path() / "town04.xosc", {}, diagnostics);
  const auto map = corsa::engine::load_road_network(scenario, diagnostics);
  struct Case {
    uint32_t vehicles;
    unsigned threads;
    std::vector<double> place, wall, cpu;
  };
  std::vector<Case> cases = {{100, 1, {}, {}, {}}, {200, 1, {}, {}, {}}, {400, 1, {}, {}, {}},
                             {800, 1, {}, {}, {}}, {800, 2, {}, {}, {}}, {1000, 1, {}, {}, {}},
                             {1000, 2, {}, {}, {}}};
  if (settings.vehicles > 0) {
    cases = {{settings.vehicles, settings.threads, {}, {}, {}}};
  }
  for (int r = 0; r < runs; ++r) {
    for (Case& c : cases) {
      const StepTiming t = step_npcs(scenario, map, c.vehicles, c.threads, settings.seconds,
                                     settings.vehicles > 0 ? settings.copies : 1);
      c.place.push_back(t.place_ms);
      c.wall.push_back(t.wall_ms);
      c.cpu.push_back(t.cpu_ms);
    }
  }
  std::printf(
      "Town04, --npc vehicles=N (car following), %.0f s simulated, median of %d runs, "
      "load average %.1f\n",
      settings.seconds, runs, load_average());
  std::printf("%9s %8s %11s %13s %12s %17s %14s\n", "vehicles", "threads", "place (ms)",
              "steps wall ms", "steps CPU ms", "real-time factor", "us/vehicle-step");
  const uint32_t copies = settings.vehicles > 0 ? settings.copies : 1;
  if (copies > 1) {
    std::printf("%u simulations of the vehicles below, a step of each in turn\n", copies);
  }
  double wall_100 = 0.0, wall_800 = 0.0, cpu_100 = 0.0, cpu_800 = 0.0;
  for (const Case& c : cases) {
    const double wall = median(c.wall), cpu = median(c.cpu);
    std::printf("%9u %8u %11.1f %13.1f %12.1f %16.1fx %14.3f\n", c.vehicles, c.threads,
                median(c.place), wall, cpu, settings.seconds * 1e3 / wall,
                wall * 1e3 / (settings.seconds * 100.0 * c.vehicles * copies));
    if (c.threads == 1 && c.vehicles == 100) {
      wall_100 = wall, cpu_100 = cpu;
    }
    if (c.threads == 1 && c.vehicles == 800) {
      wall_800 = wall, cpu_800 = cpu;
    }
  }
  if (wall_100 > 0.0 && wall_800 > 0.0) {
    std::printf("800 / 100 vehicles: %.1fx the wall time, %.1fx the CPU time (target <= 10x)\n",
                wall_800 / wall_100, cpu_800 / cpu_100);
  }
  std::printf("\n");
}

/// CPU time of a whole run (ms): all of it, and the system's part.
struct RunCpu {
  double total_ms = 0.0;
  double system_ms = 0.0;
};

// This process's system CPU time so far (ms).
double system_cpu_ms() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return 1e3 * static_cast<double>(usage.ru_stime.tv_sec) +
         1e-3 * static_cast<double>(usage.ru_stime.tv_usec);
}

// CPU time of a whole run (load, simulate, write) of `scenario` recording to `record` (none when
// empty).
RunCpu run_cpu(const std::filesystem::path& scenario, const std::filesystem::path& record) {
  corsa::Diagnostics diagnostics;
  corsa::engine::RunOptions options;
  options.scenario = scenario;
  options.simulation.threads = 1;
  if (!record.empty()) {
    options.record = record;
  }
  const double cpu = process_cpu_ms();
  const double system = system_cpu_ms();
  corsa::engine::run_scenario(options, diagnostics);
  return {process_cpu_ms() - cpu, system_cpu_ms() - system};
}

void long_runs(int runs, const std::filesystem::path& out) {
  const std::filesystem::path dir = out / ("corsa-bench-traffic-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  std::printf(
      "1,200 s scenarios (tests/bench/scenarios), CPU ms of the whole run, median of %d "
      "runs, load average %.1f, files in %s\n",
      runs, load_average(), out.c_str());
  std::printf("%-16s %10s %10s %12s %10s %12s %12s %12s %11s %11s\n", "scenario", "no record",
              "CSV", "CSV share", "binary", "binary share", "CSV bytes", "binary bytes",
              "CSV system", "bin. system");
  for (const char* name : {"long_standstill", "long_motorway"}) {
    const auto scenario = std::filesystem::path(CORSA_SOURCE_DIR) / "tests/bench/scenarios" /
                          (std::string(name) + ".xosc");
    std::vector<double> none, csv, binary, csv_system, binary_system;
    for (int r = 0; r < runs; ++r) {
      none.push_back(run_cpu(scenario, {}).total_ms);
      const RunCpu with_csv = run_cpu(scenario, dir / "run.csv");
      const RunCpu with_binary = run_cpu(scenario, dir / "run.corsatraj");
      csv.push_back(with_csv.total_ms);
      csv_system.push_back(with_csv.system_ms);
      binary.push_back(with_binary.total_ms);
      binary_system.push_back(with_binary.system_ms);
    }
    const double base = median(none), c = median(csv), b = median(binary);
    std::printf("%-16s %10.1f %10.1f %11.1f%% %10.1f %11.1f%% %12ju %12ju %11.1f %11.1f\n", name,
                base, c, 100.0 * (c - base) / c, b, 100.0 * (b - base) / b,
                static_cast<uintmax_t>(std::filesystem::file_size(dir / "run.csv")),
                static_cast<uintmax_t>(std::filesystem::file_size(dir / "run.corsatraj")),
                median(csv_system), median(binary_system));
  }
  std::printf(
      "(share: the recording's part of the run with it, (with - without) / with; system: ms of "
      "the run's CPU time spent in the kernel)\n\n");
  std::filesystem::remove_all(dir);
}

}  // namespace

int main(int argc, char** argv) {
  Settings settings;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--runs") == 0) {
      settings.runs = std::max(1, std::atoi(argv[i + 1]));
    } else if (std::strcmp(argv[i], "--part") == 0) {
      settings.part = argv[i + 1];
    } else if (std::strcmp(argv[i], "--vehicles") == 0) {
      settings.vehicles = static_cast<uint32_t>(std::max(0, std::atoi(argv[i + 1])));
    } else if (std::strcmp(argv[i], "--threads") == 0) {
      settings.threads = static_cast<unsigned>(std::max(1, std::atoi(argv[i + 1])));
    } else if (std::strcmp(argv[i], "--copies") == 0) {
      settings.copies = static_cast<uint32_t>(std::max(1, std::atoi(argv[i + 1])));
    } else if (std::strcmp(argv[i], "--seconds") == 0) {
      settings.seconds = std::max(0.01, std::atof(argv[i + 1]));
    } else if (std::strcmp(argv[i], "--out") == 0) {
      settings.out = argv[i + 1];
    }
  }
  if (settings.part == "scale" || settings.part == "all") {
    scale(settings);
  }
  if (settings.part == "long" || settings.part == "all") {
    long_runs(settings.runs, settings.out);
  }
  return 0;
}
