// Throughput of the seeded random streams (sweeps draw millions of values).
#include <benchmark/benchmark.h>

#include "corsa/core/random.h"

static void BM_Uniform(benchmark::State& state) {
  corsa::RandomStream stream(1);
  for (auto _ : state) {
    benchmark::DoNotOptimize(stream.uniform01());
  }
}
BENCHMARK(BM_Uniform);

static void BM_Normal(benchmark::State& state) {
  corsa::RandomStream stream(1);
  for (auto _ : state) {
    benchmark::DoNotOptimize(stream.normal(0.0, 1.0));
  }
}
BENCHMARK(BM_Normal);

static void BM_Poisson(benchmark::State& state) {
  corsa::RandomStream stream(1);
  const double lambda = static_cast<double>(state.range(0));
  for (auto _ : state) {
    benchmark::DoNotOptimize(stream.poisson(lambda));
  }
}
BENCHMARK(BM_Poisson)->Arg(5)->Arg(100);

BENCHMARK_MAIN();
