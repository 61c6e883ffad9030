#include "corsa/suite/expectations.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "corsa/core/strings.h"

namespace corsa::suite {
namespace {

const sweep::Extreme* extreme_of(Metric metric, const sweep::RunMetrics& m) {
  switch (metric) {
    case Metric::kMinTtc:
      return &m.min_ttc;
    case Metric::kMinDistance:
      return &m.min_distance;
    case Metric::kMaxDeceleration:
      return &m.max_deceleration;
    case Metric::kMaxAcceleration:
      return &m.max_acceleration;
    case Metric::kMaxSpeed:
      return &m.max_speed;
    case Metric::kSimTime:
    case Metric::kCollisions:
      return nullptr;
  }
  return nullptr;
}

std::string with_unit(double value, Metric metric) {
  if (!std::isfinite(value)) return "none (never on a collision course)";
  const std::string_view u = unit(metric);
  return format_double(value) + (u.empty() ? "" : " " + std::string(u));
}

std::string_view end_reason_token(engine::EndReason reason) {
  switch (reason) {
    case engine::EndReason::kStopTrigger:
      return "stopTrigger";
    case engine::EndReason::kDuration:
      return "duration";
    case engine::EndReason::kStoriesComplete:
      return "storiesComplete";
    case engine::EndReason::kInterrupted:
      return "interrupted";
    case engine::EndReason::kRunning:
      break;
  }
  return "running";
}

std::string check_bound(const MetricBound& bound, const sweep::VariantResult& run) {
  const std::string name(to_string(bound.metric));
  const auto value = metric_value(bound.metric, run);
  if (!value) return name + " cannot be measured: the scenario has no ego entity";
  std::string where;
  if (const sweep::Extreme* extreme = extreme_of(bound.metric, run.metrics);
      extreme != nullptr && extreme->value) {
    where = " (at t=" + format_double(extreme->time) + " s" +
            (extreme->other.empty() ? std::string() : ", with " + extreme->other) + ")";
  }
  if (bound.min && *value < *bound.min) {
    return name + " is " + with_unit(*value, bound.metric) + where + ", below the minimum " +
           with_unit(*bound.min, bound.metric);
  }
  if (bound.max && *value > *bound.max) {
    return name + " is " + with_unit(*value, bound.metric) + where + ", above the maximum " +
           with_unit(*bound.max, bound.metric);
  }
  return {};
}

}  // namespace

std::optional<double> metric_value(Metric metric, const sweep::VariantResult& run) {
  if (metric == Metric::kSimTime) return run.sim_time;
  if (metric == Metric::kCollisions) return static_cast<double>(run.collisions);
  if (run.metrics.ego.empty()) return std::nullopt;
  const sweep::Extreme* extreme = extreme_of(metric, run.metrics);
  if (extreme->value) return *extreme->value;
  if (metric == Metric::kMinTtc || metric == Metric::kMinDistance) {
    return std::numeric_limits<double>::infinity();
  }
  return 0.0;
}

std::vector<std::string> check_expectations(const Expectations& expect,
                                            const sweep::VariantResult& run) {
  std::vector<std::string> failures;
  if (expect.end_reason && run.end_reason != *expect.end_reason) {
    failures.push_back("the run ended by " + std::string(end_reason_token(run.end_reason)) +
                       " at t=" + format_double(run.sim_time) + " s, expected " +
                       std::string(end_reason_token(*expect.end_reason)));
  }
  if (expect.collision) {
    if (*expect.collision && run.collisions == 0) {
      failures.push_back("no collision happened, one was expected");
    } else if (!*expect.collision && run.collisions > 0) {
      failures.push_back(std::to_string(run.collisions) + " collision" +
                         (run.collisions == 1 ? "" : "s") +
                         " happened (the first: " + run.first_collision + "), none was expected");
    }
  }
  for (const MetricBound& bound : expect.metrics) {
    std::string failure = check_bound(bound, run);
    if (!failure.empty()) failures.push_back(std::move(failure));
  }
  // Monitors are the scenario's own verdicts: each must end true unless the test says otherwise.
  for (const auto& [name, value] : run.monitors) {
    bool wanted = true;
    for (const auto& [expected_name, expected] : expect.monitors) {
      if (expected_name == name) wanted = expected;
    }
    if (value != wanted) {
      failures.push_back("monitor '" + name + "' ended " + (value ? "true" : "false") +
                         ", expected " + (wanted ? "true" : "false"));
    }
  }
  for (const auto& [name, value] : expect.monitors) {
    const bool known = std::any_of(run.monitors.begin(), run.monitors.end(),
                                   [&](const auto& monitor) { return monitor.first == name; });
    if (!known) failures.push_back("the scenario declares no monitor '" + name + "'");
  }
  return failures;
}

}  // namespace corsa::suite
