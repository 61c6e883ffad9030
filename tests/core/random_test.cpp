#include "corsa/core/random.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <vector>

using corsa::RandomStream;
using corsa::WeightedTable;

namespace {

struct Moments {
  double mean = 0.0;
  double variance = 0.0;
};

template <typename Draw>
Moments moments(int n, Draw draw) {
  double sum = 0.0;
  double sum_sq = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = draw();
    sum += x;
    sum_sq += x * x;
  }
  const double mean = sum / n;
  return {mean, sum_sq / n - mean * mean};
}

}  // namespace

TEST_CASE("the same seed gives the same sequence, another seed another", "[core][random]") {
  RandomStream a(42);
  RandomStream b(42);
  RandomStream c(43);
  int differences = 0;
  for (int i = 0; i < 1000; ++i) {
    const uint64_t x = a.next_u64();
    REQUIRE(x == b.next_u64());
    differences += x != c.next_u64() ? 1 : 0;
  }
  CHECK(differences > 990);
}

TEST_CASE("draws are pinned so that every platform gives the same numbers", "[core][random]") {
  // The first raw value for seed 12345 was checked against an independent Python transcription
  // of splitmix64 + xoshiro256**. The distribution draws below are this implementation's own
  // output (identical at -O0 and -O2); a change means seeds no longer reproduce earlier runs,
  // which must be a deliberate, announced decision.
  RandomStream stream(12345);
  CHECK(stream.next_u64() == 0xbe6a36374160d49bULL);
  CHECK(stream.next_u64() == 0x214aaa0637a688c6ULL);
  RandomStream draws(2024);
  CHECK(draws.normal(0.0, 1.0) == 0.78777049874583249);
  CHECK(draws.poisson(4.0) == 3);
  CHECK(draws.poisson(100.0) == 114);
  CHECK(draws.log_normal(0.0, 1.0) == 1.7803141273689023);
  CHECK(corsa::stable_hash("") == 0xcbf29ce484222325ULL);
  CHECK(corsa::stable_hash("a") == 0xaf63dc4c8601ec8cULL);  // FNV-1a 64 reference value
}

TEST_CASE("derived streams are independent of each other's names", "[core][random]") {
  CHECK(corsa::derive_seed(1, "ego") != corsa::derive_seed(1, "target"));
  CHECK(corsa::derive_seed(1, "ego") != corsa::derive_seed(2, "ego"));
  CHECK(corsa::derive_seed(1, "ego") == corsa::derive_seed(1, "ego"));
}

TEST_CASE("uniform draws cover their interval with the right moments", "[core][random]") {
  RandomStream stream(1);
  const auto m = moments(200000, [&] { return stream.uniform(2.0, 4.0); });
  CHECK(m.mean == Approx(3.0).margin(0.01));
  CHECK(m.variance == Approx(4.0 / 12.0).margin(0.01));
  for (int i = 0; i < 10000; ++i) {
    const double x = stream.uniform01();
    REQUIRE(x >= 0.0);
    REQUIRE(x < 1.0);
  }
}

TEST_CASE("uniform integers hit every value in range equally", "[core][random]") {
  RandomStream stream(2);
  std::map<int64_t, int> counts;
  for (int i = 0; i < 60000; ++i) {
    const int64_t k = stream.uniform_int(-2, 3);
    REQUIRE(k >= -2);
    REQUIRE(k <= 3);
    ++counts[k];
  }
  REQUIRE(counts.size() == 6);
  for (const auto& [value, count] : counts) {
    CHECK(count == Approx(10000).margin(400));
  }
  CHECK(stream.uniform_int(5, 5) == 5);
  CHECK_THROWS(stream.uniform_int(3, 2));
}

TEST_CASE("normal draws have the requested mean and standard deviation", "[core][random]") {
  RandomStream stream(3);
  const auto m = moments(200000, [&] { return stream.normal(10.0, 2.0); });
  CHECK(m.mean == Approx(10.0).margin(0.02));
  CHECK(std::sqrt(m.variance) == Approx(2.0).margin(0.02));
}

TEST_CASE("log-normal draws have the moments of exp(Normal(mu, sigma))", "[core][random]") {
  RandomStream stream(4);
  const double mu = 0.5;
  const double sigma = 0.25;
  const auto m = moments(200000, [&] { return stream.log_normal(mu, sigma); });
  const double expected_mean = std::exp(mu + sigma * sigma / 2.0);
  const double expected_var = (std::exp(sigma * sigma) - 1.0) * std::exp(2.0 * mu + sigma * sigma);
  CHECK(m.mean == Approx(expected_mean).epsilon(0.01));
  CHECK(m.variance == Approx(expected_var).epsilon(0.03));
}

TEST_CASE("Poisson draws have mean and variance lambda, small and large", "[core][random]") {
  for (const double lambda : {0.5, 4.0, 29.0, 31.0, 250.0}) {
    RandomStream stream(5);
    const auto m = moments(100000, [&] { return static_cast<double>(stream.poisson(lambda)); });
    INFO("lambda = " << lambda);
    CHECK(m.mean == Approx(lambda).epsilon(0.02));
    CHECK(m.variance == Approx(lambda).epsilon(0.05));
  }
  RandomStream stream(6);
  CHECK(stream.poisson(0.0) == 0);
  CHECK_THROWS(stream.poisson(-1.0));
  CHECK_THROWS(stream.poisson(NAN));
}

TEST_CASE("weighted indices follow the weights and skip zero weights", "[core][random]") {
  RandomStream stream(7);
  const std::vector<double> weights{1.0, 0.0, 3.0};
  int counts[3] = {0, 0, 0};
  for (int i = 0; i < 40000; ++i) {
    ++counts[stream.weighted_index(weights)];
  }
  CHECK(counts[1] == 0);
  CHECK(counts[0] == Approx(10000).margin(400));
  CHECK(counts[2] == Approx(30000).margin(400));
  const std::vector<double> zero{0.0, 0.0};
  CHECK_THROWS(stream.weighted_index(zero));
  const std::vector<double> negative{1.0, -1.0};
  CHECK_THROWS(stream.weighted_index(negative));
}

TEST_CASE("a weighted table draws the indices weighted_index draws from the same stream",
          "[core][random]") {
  RandomStream weights_stream(8);
  std::vector<double> weights;
  for (int i = 0; i < 3000; ++i) {
    // Zero weights among them, and a zero weight at the end (the fallback's case).
    weights.push_back(i % 7 == 3 ? 0.0 : weights_stream.uniform(0.0, 250.0));
  }
  weights.push_back(0.0);
  const WeightedTable table(weights);
  RandomStream a(9), b(9);
  for (int i = 0; i < 20000; ++i) {
    REQUIRE(table.draw(a) == b.weighted_index(weights));
  }
  const std::vector<double> zero{0.0, 0.0};
  CHECK_THROWS(WeightedTable(zero));
  const std::vector<double> negative{1.0, -1.0};
  CHECK_THROWS(WeightedTable(negative));
}
