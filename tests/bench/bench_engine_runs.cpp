// Whole `corsa run` processes on every ASAM OpenSCENARIO 1.3 example (target: each under 30 ms
// on this machine; a widely used peer needs 250-500 ms, mostly loading the map) and on the two
// 1,200 s scenarios of tests/bench/scenarios: each is run `runs` times (default 11) with --quiet
// and no outputs. Printed per scenario: the median and the fastest wall time of the process, the
// median CPU time (user + system) it used, and its peak memory (the largest resident set of the
// runs: the ru_maxrss of wait4, which is what `/usr/bin/time -v` reports as "Maximum resident
// set size"). The machine is shared by several builds: when it is busy the wall times grow
// while the CPU times stay, so read both.
//
//   corsa_bench_engine_runs [runs] [BASELINE_CORSA]
//
// With a second corsa binary (e.g. one built from an earlier commit) each scenario is also run
// with it, alternating with this build's, and printed on a second line (`base`).

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "bench_util.h"

extern char** environ;

namespace {

using corsa::bench::median;

struct Timing {
  double wall = 0.0;  ///< s
  double cpu = 0.0;   ///< s, user + system of the child
  long peak_kb = 0;   ///< largest resident set of the child, KiB
};

Timing run_once(const std::string& binary, const std::string& scenario) {
  std::vector<std::string> args{binary, "run", scenario, "--quiet"};
  std::vector<char*> argv;
  for (auto& arg : args) {
    argv.push_back(arg.data());
  }
  argv.push_back(nullptr);
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  // The scenarios' warnings (one set per run) are not the benchmark's output.
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  const int spawned = posix_spawn(&pid, binary.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) {
    std::fprintf(stderr, "cannot start %s\n", binary.c_str());
    std::exit(1);
  }
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  Timing timing;
  timing.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  timing.cpu = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
               1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  timing.peak_kb = usage.ru_maxrss;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::fprintf(stderr, "corsa run %s failed\n", scenario.c_str());
    std::exit(1);
  }
  return timing;
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 11;
  std::vector<std::pair<std::string, std::string>> binaries = {{"", CORSA_BINARY}};
  if (argc > 2) {
    binaries.emplace_back(" (base)", argv[2]);
  }
  const std::string dir = std::string(CORSA_SHARED_DIR) + "/conformance/asam-osc-1.3/";
  const std::string own = std::string(CORSA_SOURCE_DIR) + "/tests/bench/scenarios/";
  const std::vector<std::string> scenarios = {dir + "CloseVehicleCrossing.xosc",
                                              dir + "CutIn.xosc",
                                              dir + "DoubleLaneChanger.xosc",
                                              dir + "EndOfTrafficJam.xosc",
                                              dir + "EndofTrafficJamNeighboringLaneOccupied.xosc",
                                              dir + "FastOvertakeWithReInitialization.xosc",
                                              dir + "Overtaker.xosc",
                                              dir + "SequentialEvents_0-100-0kph_Explicit.xosc",
                                              dir + "SequentialEvents_0-100-0kph_Implicit.xosc",
                                              dir + "SimpleOvertake.xosc",
                                              dir + "SlowPrecedingVehicle.xosc",
                                              dir + "SynchronizedArrivalToIntersection.xosc",
                                              dir + "TrafficJam.xosc",
                                              dir + "TrailerConnect.xosc",
                                              own + "long_standstill.xosc",
                                              own + "long_motorway.xosc"};
  std::printf("%-44s %14s %11s %13s %12s   (%d runs of a whole corsa run process)\n", "scenario",
              "median wall ms", "min wall ms", "median CPU ms", "peak memory", runs);
  for (const std::string& scenario : scenarios) {
    std::vector<std::vector<double>> wall(binaries.size()), cpu(binaries.size());
    std::vector<long> peak(binaries.size(), 0);
    for (int i = 0; i < runs; ++i) {
      for (size_t b = 0; b < binaries.size(); ++b) {
        const Timing timing = run_once(binaries[b].second, scenario);
        wall[b].push_back(timing.wall * 1e3);
        cpu[b].push_back(timing.cpu * 1e3);
        peak[b] = std::max(peak[b], timing.peak_kb);
      }
    }
    for (size_t b = 0; b < binaries.size(); ++b) {
      const std::string name = scenario.substr(scenario.find_last_of('/') + 1) + binaries[b].first;
      std::printf("%-44s %14.1f %11.1f %13.1f %9.1f MB\n", name.c_str(), median(wall[b]),
                  *std::min_element(wall[b].begin(), wall[b].end()), median(cpu[b]),
                  static_cast<double>(peak[b]) / 1024.0);
    }
  }
  return 0;
}
