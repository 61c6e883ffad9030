#pragma once

// Safety metrics of one run, measured for one entity (the ego) against every other entity, after
// every step. They go into a sweep's summary.csv and are what a suite's metric bounds check.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "corsa/engine/simulation.h"

namespace corsa::sweep {

/// One extreme value of a run: the value, when it happened and against which entity.
struct Extreme {
  std::optional<double> value;  ///< nothing when never measured (e.g. no other entity)
  double time = 0.0;            ///< s, simulation time when it was reached (first time)
  std::string other;            ///< the other entity ("" for the ego's own quantities)
};

struct RunMetrics {
  std::string ego;  ///< the entity measured; "" when the scenario has no entity
  /// Smallest time to collision (s): the time until the ego's and another entity's bounding
  /// boxes (seen from above) would touch if both kept their current velocity and heading; 0 while
  /// they overlap. Nothing when they were never on a collision course.
  Extreme min_ttc;
  /// Smallest free-space distance (m) between the ego's box and another entity's box from
  /// above; 0 while they touch.
  Extreme min_distance;
  /// Largest braking of the ego (m/s^2, positive): the maximum of minus its longitudinal
  /// acceleration over one step. 0 when it never slowed down.
  Extreme max_deceleration;
  /// Largest longitudinal acceleration of the ego (m/s^2).
  Extreme max_acceleration;
  /// Largest speed of the ego (m/s).
  Extreme max_speed;
};

/// The ego of a run: the entity named `requested` when given, otherwise the entity called "Ego"
/// (any case), then "hero", then the first entity. Nothing when the scenario has no entity or
/// `requested` names none (the caller reports that).
std::optional<size_t> choose_ego(const engine::Simulation& simulation, std::string_view requested);

/// Measures RunMetrics while a simulation runs: register it with Simulation::add_observer before
/// the first step. Only entities that have been placed count; invisible ones still do (they are
/// physically there).
class MetricsObserver final : public engine::SimulationObserver {
 public:
  /// `ego`: the entity index to measure (see choose_ego); nothing measures nothing.
  explicit MetricsObserver(std::optional<size_t> ego) : ego_(ego) {}
  void on_step(const engine::Simulation& simulation) override;
  const RunMetrics& metrics() const { return metrics_; }

 private:
  std::optional<size_t> ego_;
  RunMetrics metrics_;
};

}  // namespace corsa::sweep
