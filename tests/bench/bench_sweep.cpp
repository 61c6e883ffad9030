// Sweep throughput: variants per second of `corsa sweep` (corsa::sweep::run_sweep, the
// same code, with its default outputs: every step's trajectory, the run summary and the result
// row of each variant) at -j1 and -j2, for
//   - the ASAM SlowPrecedingVehicle deterministic parameter set (2 variants of a ~35 s scenario;
//     swept repeatedly to get a measurable time), and
//   - the 1,000-variant cut-in grid (scenarios/suites/sweeps/cut_in_grid.xosc, 20 s each).
// Target: above 100 variants/s on this 2-core machine.
//
// Reported per case: the median over --runs runs of wall-clock variants/s, and the process CPU
// time per variant. The machine is shared: when other jobs hold the cores, wall-clock throughput
// at -j2 drops while CPU time per variant stays put, so the CPU figure is also turned into the
// rate two idle cores would give (2000 / CPU ms per variant).
//
//   corsa_bench_sweep [--runs N] [--repeat-small N] [--case slow|cut-in]   (default: both cases)

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_util.h"
#include "corsa/core/diagnostic.h"
#include "corsa/core/strings.h"
#include "corsa/sweep/sweep.h"
#include "corsa/sweep/variant_plan.h"
#include "corsa/xosc/distributions.h"

namespace {

using corsa::bench::median;

namespace fs = std::filesystem;

double cpu_seconds() { return 1e-3 * corsa::bench::process_cpu_ms(); }

struct Figures {
  double variants_per_second = 0.0;
  double cpu_ms_per_variant = 0.0;
};

// Sweeps `plan` `repeat` times into a fresh folder and returns the throughput.
Figures measure(const corsa::sweep::VariantPlan& plan, size_t jobs, int repeat,
                const fs::path& scratch) {
  corsa::Diagnostics diagnostics;
  corsa::sweep::SweepOptions options;
  options.output = scratch;
  options.jobs = jobs;
  options.force = true;
  size_t variants = 0;
  const double cpu0 = cpu_seconds();
  const auto wall0 = std::chrono::steady_clock::now();
  for (int r = 0; r < repeat; ++r) {
    const auto report = corsa::sweep::run_sweep(plan, options, diagnostics);
    if (report.failed > 0) {
      std::fprintf(stderr, "%zu variants failed, e.g. %s\n", report.failed,
                   report.first_failures.front().second.c_str());
      std::exit(1);
    }
    variants += report.ran;
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  const double cpu = cpu_seconds() - cpu0;
  return {static_cast<double>(variants) / wall, 1e3 * cpu / static_cast<double>(variants)};
}

void report(const char* name, const corsa::sweep::VariantPlan& plan, int runs, int repeat,
            const fs::path& scratch) {
  for (const size_t jobs : {size_t{1}, size_t{2}}) {
    std::vector<double> rates;
    std::vector<double> cpu;
    for (int run = 0; run < runs; ++run) {
      const Figures f = measure(plan, jobs, repeat, scratch);
      rates.push_back(f.variants_per_second);
      cpu.push_back(f.cpu_ms_per_variant);
    }
    const double cpu_ms = median(cpu);
    std::printf(
        "%-34s -j%zu  %8.1f variants/s wall   %7.2f ms CPU/variant   (%6.1f variants/s "
        "on 2 idle cores)\n",
        name, jobs, median(rates), cpu_ms, 2000.0 / cpu_ms);
    std::fflush(stdout);
  }
}

corsa::sweep::VariantPlan distribution(const fs::path& file) {
  corsa::Diagnostics diagnostics;
  return corsa::sweep::VariantPlan::from_distribution(
      file, corsa::xosc::load_distribution(file, diagnostics), {});
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 3;
  int repeat_small = 50;
  std::string only;  // one case, for quicker before/after comparisons
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string option = argv[i];
    const std::string text = argv[i + 1];
    if (option == "--case" && (text == "slow" || text == "cut-in")) {
      only = text;
      continue;
    }
    const auto value = corsa::parse_int(text);
    if (option == "--case" || !value || *value < 1) {
      std::fprintf(stderr,
                   "usage: corsa_bench_sweep [--runs N] [--repeat-small N] [--case slow|cut-in]\n");
      return 2;
    }
    (option == "--runs" ? runs : repeat_small) = static_cast<int>(*value);
  }
  const fs::path scratch =
      fs::temp_directory_path() / ("corsa-bench-sweep-" + std::to_string(::getpid()));
  try {
    if (only != "cut-in") {
      const auto slow = distribution(fs::path(CORSA_SHARED_DIR) / "conformance" / "asam-osc-1.3" /
                                     "SlowPrecedingVehicleDeterministicParameterSet.xosc");
      std::printf("SlowPrecedingVehicle deterministic set: %zu variants, swept %d times per run\n",
                  slow.size(), repeat_small);
      report("SlowPrecedingVehicle (ASAM)", slow, runs, repeat_small, scratch);
    }
    if (only != "slow") {
      const auto cut_in = distribution(fs::path(CORSA_SOURCE_DIR) / "scenarios" / "suites" /
                                       "sweeps" / "cut_in_grid.xosc");
      std::printf("cut-in grid: %zu variants\n", cut_in.size());
      report("cut-in grid (1,000 variants)", cut_in, runs, 1, scratch);
    }
  } catch (const corsa::InputError& error) {
    std::fprintf(stderr, "%s\n", error.diagnostic().format().c_str());
    fs::remove_all(scratch);
    return 2;
  }
  fs::remove_all(scratch);
  return 0;
}
