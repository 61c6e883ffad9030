#include "corsa/core/det_math.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

namespace {

// Distance in units in the last place between two finite doubles of the same sign.
double ulps(double a, double b) {
  if (a == b) {
    return 0.0;
  }
  return std::fabs(a - b) / std::fabs(std::nextafter(b, INFINITY) - b);
}

}  // namespace

TEST_CASE("deterministic log agrees with the C library within 2 ulp", "[core][det_math]") {
  for (double x = 1e-300; x < 1e300; x *= 1.37) {
    INFO("x = " << x);
    REQUIRE(ulps(corsa::det::log(x), std::log(x)) <= 2.0);
  }
  for (double x = 0.5; x < 2.0; x += 0.0013) {
    INFO("x = " << x);
    // Near 1 the result is tiny; compare absolutely there.
    REQUIRE(std::fabs(corsa::det::log(x) - std::log(x)) <=
            4e-16 * std::fmax(1.0, std::fabs(std::log(x))));
  }
}

TEST_CASE("deterministic log handles the edges like std::log", "[core][det_math]") {
  CHECK(corsa::det::log(1.0) == 0.0);
  CHECK(std::isinf(corsa::det::log(0.0)));
  CHECK(corsa::det::log(0.0) < 0.0);
  CHECK(std::isnan(corsa::det::log(-1.0)));
  CHECK(std::isinf(corsa::det::log(INFINITY)));
  CHECK(std::fabs(corsa::det::log(std::numeric_limits<double>::denorm_min()) -
                  std::log(std::numeric_limits<double>::denorm_min())) < 1e-12);
}

TEST_CASE("deterministic exp agrees with the C library within 2 ulp", "[core][det_math]") {
  for (double x = -700.0; x < 700.0; x += 0.731) {
    INFO("x = " << x);
    REQUIRE(ulps(corsa::det::exp(x), std::exp(x)) <= 2.0);
  }
  CHECK(corsa::det::exp(0.0) == 1.0);
  CHECK(std::isinf(corsa::det::exp(1000.0)));
  CHECK(corsa::det::exp(-1000.0) == 0.0);
}

TEST_CASE("deterministic lgamma matches std::lgamma", "[core][det_math]") {
  for (double x = 0.05; x < 200.0; x *= 1.21) {
    INFO("x = " << x);
    REQUIRE(std::fabs(corsa::det::lgamma(x) - std::lgamma(x)) <=
            1e-12 * std::fmax(1.0, std::fabs(std::lgamma(x))));
  }
  CHECK(std::fabs(corsa::det::lgamma(5.0) - std::log(24.0)) < 1e-13);
}

TEST_CASE("deterministic sin and cos agree with the C library", "[core][det_math]") {
  for (double x = -1000.0; x < 1000.0; x += 0.377) {
    INFO("x = " << x);
    REQUIRE(std::fabs(corsa::det::sin(x) - std::sin(x)) <=
            2e-16 * std::fmax(1.0, std::fabs(x) * 1e-3));
    REQUIRE(std::fabs(corsa::det::cos(x) - std::cos(x)) <=
            2e-16 * std::fmax(1.0, std::fabs(x) * 1e-3));
  }
}
