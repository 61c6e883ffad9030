// Whole `corsa run` processes on the ASAM OpenSCENARIO 1.3 examples (target: each under
// 30 ms on this machine; a widely used peer needs 250-500 ms, mostly loading the map): every
// example is run `runs` times (default 11) with --quiet and no outputs. Printed per example: the
// median and the fastest wall time of the process, and the median CPU time (user + system) it
// used. The machine is shared by several builds: when it is busy the wall times grow while the
// CPU times stay, so read both.
//
//   corsa_bench_engine_runs [runs]

#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench_util.h"

extern char** environ;

namespace {

using corsa::bench::median;

struct Timing {
  double wall = 0.0;  ///< s
  double cpu = 0.0;   ///< s, user + system of the child
};

Timing run_once(const std::string& scenario) {
  const std::string binary = CORSA_BINARY;
  std::vector<std::string> args{binary, "run", scenario, "--quiet"};
  std::vector<char*> argv;
  for (auto& arg : args) {
    argv.push_back(arg.data());
  }
  argv.push_back(nullptr);
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  if (posix_spawn(&pid, binary.c_str(), nullptr, nullptr, argv.data(), environ) != 0) {
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
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::fprintf(stderr, "corsa run %s failed\n", scenario.c_str());
    std::exit(1);
  }
  return timing;
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 11;
  const std::string dir = std::string(CORSA_SHARED_DIR) + "/conformance/asam-osc-1.3/";
  const char* examples[] = {"CutIn.xosc",
                            "DoubleLaneChanger.xosc",
                            "Overtaker.xosc",
                            "SimpleOvertake.xosc",
                            "SequentialEvents_0-100-0kph_Explicit.xosc",
                            "SequentialEvents_0-100-0kph_Implicit.xosc",
                            "SlowPrecedingVehicle.xosc"};
  std::printf("%-44s %14s %11s %13s   (%d runs of a whole corsa run process)\n", "example",
              "median wall ms", "min wall ms", "median CPU ms", runs);
  for (const char* example : examples) {
    std::vector<double> wall, cpu;
    for (int i = 0; i < runs; ++i) {
      const Timing timing = run_once(dir + example);
      wall.push_back(timing.wall * 1e3);
      cpu.push_back(timing.cpu * 1e3);
    }
    std::printf("%-44s %14.1f %11.1f %13.1f\n", example, median(wall),
                *std::min_element(wall.begin(), wall.end()), median(cpu));
  }
  return 0;
}
