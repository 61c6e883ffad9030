#include "corsa/suite/expectations.h"

#include <catch2/catch.hpp>
#include <cmath>

using corsa::engine::EndReason;
using corsa::suite::check_expectations;
using corsa::suite::Expectations;
using corsa::suite::Metric;
using corsa::suite::metric_value;
using corsa::sweep::VariantResult;

namespace {

VariantResult run() {
  VariantResult r;
  r.end_reason = EndReason::kStopTrigger;
  r.sim_time = 12.5;
  r.metrics.ego = "Ego";
  r.metrics.min_ttc = {1.2, 8.25, "A1"};
  r.metrics.min_distance = {3.5, 9.0, "A1"};
  r.metrics.max_deceleration = {6.0, 8.3, ""};
  r.metrics.max_acceleration = {0.0, 0.0, ""};
  r.metrics.max_speed = {30.0, 0.0, ""};
  return r;
}

}  // namespace

TEST_CASE("a run meeting every expectation has no failures", "[suite][expect]") {
  Expectations expect;
  expect.end_reason = EndReason::kStopTrigger;
  expect.collision = false;
  expect.metrics = {{Metric::kMinTtc, 1.0, std::nullopt},
                    {Metric::kMaxDeceleration, std::nullopt, 6.0},
                    {Metric::kSimTime, 12.0, 13.0},
                    {Metric::kCollisions, std::nullopt, 0.0}};
  CHECK(check_expectations(expect, run()).empty());
}

TEST_CASE("missed expectations say what was measured, when and against whom", "[suite][expect]") {
  Expectations expect;
  expect.end_reason = EndReason::kDuration;
  expect.collision = true;
  expect.metrics = {{Metric::kMinTtc, 1.5, std::nullopt},
                    {Metric::kMaxDeceleration, std::nullopt, 4.0}};
  const auto failures = check_expectations(expect, run());
  REQUIRE(failures.size() == 4);
  CHECK(failures[0] == "the run ended by stopTrigger at t=12.5 s, expected duration");
  CHECK(failures[1] == "no collision happened, one was expected");
  CHECK(failures[2] == "min_ttc is 1.2 s (at t=8.25 s, with A1), below the minimum 1.5 s");
  CHECK(failures[3] == "max_deceleration is 6 m/s^2 (at t=8.3 s), above the maximum 4 m/s^2");
}

TEST_CASE("an unexpected collision is named", "[suite][expect]") {
  VariantResult crashed = run();
  crashed.collisions = 1;
  crashed.first_collision = "Ego and A1 at t=9.1 s";
  Expectations expect;
  expect.collision = false;
  const auto failures = check_expectations(expect, crashed);
  REQUIRE(failures.size() == 1);
  CHECK(failures[0] ==
        "1 collision happened (the first: Ego and A1 at t=9.1 s), none was expected");
}

TEST_CASE("a TTC never measured is infinite and a run without ego has no metrics",
          "[suite][expect]") {
  VariantResult apart = run();
  apart.metrics.min_ttc = {};
  CHECK(std::isinf(*metric_value(Metric::kMinTtc, apart)));
  Expectations expect;
  expect.metrics = {{Metric::kMinTtc, 2.0, std::nullopt}};
  CHECK(check_expectations(expect, apart).empty());
  expect.metrics = {{Metric::kMinTtc, std::nullopt, 2.0}};
  CHECK(check_expectations(expect, apart).at(0) ==
        "min_ttc is none (never on a collision course), above the maximum 2 s");
  VariantResult empty;
  CHECK_FALSE(metric_value(Metric::kMaxSpeed, empty));
  CHECK(metric_value(Metric::kSimTime, empty) == 0.0);
  expect.metrics = {{Metric::kMaxSpeed, std::nullopt, 10.0}};
  CHECK(check_expectations(expect, empty).at(0) ==
        "max_speed cannot be measured: the scenario has no ego entity");
}
