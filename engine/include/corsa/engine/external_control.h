#pragma once

// Control from outside the scenario: a driver model, a planner or a system under test that runs
// beside the engine (the Python module, a co-simulation) and moves entities, and the values a
// scenario's UserDefinedValueConditions compare (OpenSCENARIO 1.3 §8.3.2: values "provided by the
// simulator or user"). Everything here is handed to a Simulation (simulation.h); nothing is
// global.

#include <functional>
#include <optional>
#include <string_view>

#include "corsa/engine/world_snapshot.h"
#include "corsa/xosc/parameters.h"

namespace corsa::engine {

/// Driver inputs, applied through the single-track vehicle model of the `dynamics` controller
/// (docs/engine.md, "The dynamics controller") whatever controller the entity has.
struct VehicleControls {
  double throttle = 0.0;  ///< 0..1: demanded acceleration = throttle x maxAcceleration
  double brake = 0.0;     ///< 0..1: demanded deceleration = brake x maxDeceleration
  /// Demanded front wheel angle, rad, positive to the left; limited to the front axle's
  /// maxSteering (0.5 rad when the vehicle gives none).
  double steering = 0.0;
};

/// One command for one entity and one step (Simulation::command). It takes the place of the
/// entity's controller for the step that follows; at most one of `pose` and `controls` is set.
struct ExternalCommand {
  /// Where the entity is at the end of the step (map frame). Its speed is `speed` when given,
  /// otherwise the speed it had.
  std::optional<Pose> pose;
  /// m/s along the heading: the entity moves along its lane (or straight ahead off the lanes) at
  /// this speed, as the default controller moves it.
  std::optional<double> speed;
  /// Throttle, brake and steering through the vehicle model.
  std::optional<VehicleControls> controls;
};

/// The value of a UserDefinedValueCondition's `name` now, or nothing when there is none (the
/// condition then does not hold). Called while the triggers are evaluated, from the thread that
/// steps the simulation.
using UserValueProvider = std::function<std::optional<xosc::Value>(std::string_view name)>;

}  // namespace corsa::engine
