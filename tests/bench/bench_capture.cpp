// Data collection: the demo dataset — scenarios/demo/cut_in_city.xosc, 20 s of
// scenario, 1280x720 RGB + depth + semantic + instance cameras, 32-channel LiDAR and a 720x720
// bird's-eye view at 10 Hz (LiDAR 20 Hz during the cut-in) — written by the corsa executable
// exactly as a user runs it. Target: under 60 s on the 2-core build machine.
//
// A timing program: corsa_bench_capture [RUNS] (default 3) prints every run's wall time and CPU
// time (user + system of the child, which is what the shared machine's load does not inflate)
// and their medians.

#include <sys/resource.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_util.h"

namespace {

using corsa::bench::median;

double child_cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_CHILDREN, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  const std::filesystem::path out =
      std::filesystem::temp_directory_path() / "corsa_bench_capture_dataset";
  const std::string command = std::string("cd '") + CORSA_SOURCE_DIR + "' && '" + CORSA_BINARY +
                              "' run scenarios/demo/cut_in_city.xosc --rig scenarios/demo/rig.xml"
                              " --quiet --force -o '" +
                              out.string() + "'";
  std::vector<double> walls;
  std::vector<double> cpus;
  for (int i = 0; i < runs; ++i) {
    const double cpu_before = child_cpu_seconds();
    const auto start = std::chrono::steady_clock::now();
    const int status = std::system(command.c_str());
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      std::fprintf(stderr, "corsa_bench_capture: the run failed: %s\n", command.c_str());
      return 1;
    }
    const double cpu = child_cpu_seconds() - cpu_before;
    walls.push_back(wall);
    cpus.push_back(cpu);
    std::printf("run %d: %.2f s wall, %.2f s CPU\n", i + 1, wall, cpu);
  }
  std::printf(
      "demo dataset (20 s scenario, 10 Hz 1280x720 cameras, 32-channel LiDAR): median "
      "%.2f s wall, %.2f s CPU over %d runs (target: under 60 s)\n",
      median(walls), median(cpus), runs);
  std::filesystem::remove_all(out);
  return 0;
}
