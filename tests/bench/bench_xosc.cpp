// Loading times of the ASAM OpenSCENARIO 1.3 examples (with their catalogs and every check),
// of distribution enumeration, and of the expression evaluator. Release build; report medians:
//   build/tests/bench/corsa_bench_xosc --benchmark_repetitions=5 --benchmark_report_aggregates_only

#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "corsa/core/atomic_file.h"
#include "corsa/xosc/expression.h"
#include "corsa/xosc/scenario.h"

namespace {

namespace fs = std::filesystem;
const fs::path kConformance = fs::path(CORSA_SHARED_DIR) / "conformance" / "asam-osc-1.3";

// Whole load from disk: read, parse, resolve, expand catalogs (their files read too), check.
void load_from_disk(benchmark::State& state, const fs::path& path) {
  for (auto _ : state) {
    corsa::Diagnostics diagnostics;
    auto document = corsa::xosc::load_document(path, {}, diagnostics);
    benchmark::DoNotOptimize(document);
  }
}

void expression(benchmark::State& state) {
  const corsa::xosc::ParameterLookup lookup =
      [](std::string_view) -> std::optional<corsa::xosc::ExprValue> {
    return corsa::xosc::ExprValue::of(12.0);
  };
  for (auto _ : state) {
    auto value = corsa::xosc::evaluate_expression(
        "0.25 * 2.0 * 3.141592 * $TrajRadius + max($a, pow(2, 3)) / sqrt(16)", lookup);
    benchmark::DoNotOptimize(value);
  }
}

void stochastic_variants(benchmark::State& state) {
  corsa::Diagnostics diagnostics;
  const auto distribution = corsa::xosc::load_distribution(
      kConformance / "SlowPrecedingVehicleStochasticParameterSet.xosc", diagnostics);
  for (auto _ : state) {
    auto variants = corsa::xosc::enumerate_variants(distribution);
    benchmark::DoNotOptimize(variants);
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(kConformance)) {
    if (entry.path().extension() == ".xosc") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  for (const auto& file : files) {
    benchmark::RegisterBenchmark(("load/" + file.stem().string()).c_str(), load_from_disk, file)
        ->Unit(benchmark::kMicrosecond);
  }
  benchmark::RegisterBenchmark("expression", expression);
  benchmark::RegisterBenchmark("stochastic_variants/100", stochastic_variants)
      ->Unit(benchmark::kMicrosecond);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
