// The LiDAR return model's own random draws and exponential (sensors/src/lidar_random.h).

#include "lidar_random.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <set>
#include <vector>

using corsa::sensors::detail::BeamRandom;
using corsa::sensors::detail::exp_nonpositive;
using corsa::sensors::detail::Ziggurat;

namespace {

/// Standard normal CDF (std::erfc is only used to check, never to draw).
double phi(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

/// Binomial standard deviation of a share p over n draws.
double share_sigma(double p, double n) { return std::sqrt(p * (1.0 - p) / n); }

}  // namespace

TEST_CASE("ziggurat normal deviates follow the standard normal distribution",
          "[sensors][lidar][random]") {
  const Ziggurat& normal = Ziggurat::get();
  const int n = 400000;
  std::vector<double> z;
  z.reserve(n);
  // One deviate per beam, as the LiDAR draws them, over many beams of one frame.
  const uint64_t key = BeamRandom::frame_key(2024);
  for (int b = 0; b < n; ++b) {
    BeamRandom random(key, static_cast<uint64_t>(b));
    z.push_back(normal(random));
  }
  double sum = 0.0, sum2 = 0.0, sum4 = 0.0;
  for (double v : z) {
    sum += v;
    sum2 += v * v;
    sum4 += v * v * v * v;
  }
  const double dn = n;
  CHECK(std::fabs(sum / dn) < 4.0 / std::sqrt(dn));
  CHECK(std::fabs(sum2 / dn - 1.0) < 4.0 * std::sqrt(2.0 / dn));
  CHECK(sum4 / dn == Approx(3.0).margin(4.0 * std::sqrt(96.0 / dn)));  // kurtosis of a normal
  // The CDF at points in every part of the ziggurat: inner rectangles, wedges and the tail
  // beyond kR = 3.44.
  for (const double x : {-3.8, -2.5, -1.0, -0.3, 0.0, 0.4, 1.5, 2.9, 3.6}) {
    double below = 0.0;
    for (double v : z) {
      below += v < x ? 1.0 : 0.0;
    }
    INFO("x = " << x);
    CHECK(std::fabs(below / dn - phi(x)) < 5.0 * share_sigma(phi(x), dn) + 1e-6);
  }
  double tail = 0.0;
  for (double v : z) {
    tail += std::fabs(v) > Ziggurat::kR ? 1.0 : 0.0;
  }
  const double p_tail = 2.0 * (1.0 - phi(Ziggurat::kR));
  CHECK(std::fabs(tail / dn - p_tail) < 5.0 * share_sigma(p_tail, dn));
  CHECK(tail > 0.0);
}

TEST_CASE("the ziggurat's layers shrink to zero and each has the same area",
          "[sensors][lidar][random]") {
  const auto& x = Ziggurat::get().edges();
  CHECK(x[1] == Ziggurat::kR);
  CHECK(x[0] * std::exp(-0.5 * x[1] * x[1]) == Approx(Ziggurat::kArea).epsilon(1e-9));
  for (int i = 1; i < Ziggurat::kLayers; ++i) {
    REQUIRE(x[i + 1] < x[i]);
  }
  CHECK(x[Ziggurat::kLayers] == 0.0);
  // The top layer [0, x_127] x [f(x_127), 1] closes the curve with the same area.
  const double f127 = std::exp(-0.5 * x[127] * x[127]);
  CHECK(x[127] * (1.0 - f127) == Approx(Ziggurat::kArea).epsilon(1e-6));
}

TEST_CASE("a beam's draws depend only on the frame seed and the beam index",
          "[sensors][lidar][random]") {
  const uint64_t key = BeamRandom::frame_key(7);
  BeamRandom a(key, 1234);
  BeamRandom b(key, 1234);
  BeamRandom other_beam(key, 1235);
  BeamRandom other_frame(BeamRandom::frame_key(8), 1234);
  std::set<uint64_t> seen;
  for (int i = 0; i < 8; ++i) {
    const uint64_t v = a.next_u64();
    CHECK(v == b.next_u64());
    CHECK(v != other_beam.next_u64());
    CHECK(v != other_frame.next_u64());
    seen.insert(v);
  }
  CHECK(seen.size() == 8);
  // Uniforms of consecutive beams are uniform on [0, 1): mean 1/2, variance 1/12.
  double sum = 0.0, sum2 = 0.0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const double u = BeamRandom(key, static_cast<uint64_t>(i)).uniform01();
    REQUIRE(u >= 0.0);
    REQUIRE(u < 1.0);
    sum += u;
    sum2 += u * u;
  }
  CHECK(std::fabs(sum / n - 0.5) < 4.0 * std::sqrt(1.0 / 12.0 / n));
  CHECK(sum2 / n - (sum / n) * (sum / n) == Approx(1.0 / 12.0).epsilon(0.01));
}

TEST_CASE("the return model's exponential matches e^x to 3e-10 for x <= 0",
          "[sensors][lidar][random]") {
  double worst = 0.0;
  for (int i = 0; i <= 200000; ++i) {
    const double x = -700.0 * i / 200000.0;
    const double expected = std::exp(x);
    worst = std::max(worst, std::fabs(exp_nonpositive(x) - expected) / expected);
  }
  CHECK(worst < 3e-10);
  CHECK(exp_nonpositive(0.0) == 1.0);
  CHECK(exp_nonpositive(-1e-300) == 1.0);
  CHECK(exp_nonpositive(-750.0) == 0.0);
  CHECK(exp_nonpositive(-INFINITY) == 0.0);
}
