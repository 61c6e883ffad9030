#pragma once

// Longitudinal limits for the actions that plan their own speed (SpeedProfileAction,
// LongitudinalDistanceAction, SynchronizeAction): DynamicConstraints (OpenSCENARIO 1.3 §7.4.1)
// first, else the entity's Performance, else moderate defaults.

#include <algorithm>
#include <limits>
#include <optional>

#include "corsa/xosc/private_actions.h"
#include "state/entity.h"

namespace corsa::engine::detail {

struct SpeedLimits {
  double acceleration = 3.0;                               ///< m/s^2, > 0
  double deceleration = 6.0;                               ///< m/s^2, > 0 (a magnitude)
  double speed = std::numeric_limits<double>::infinity();  ///< m/s

  /// `target` (m/s) reached from `current` within one step of `dt` seconds under the limits.
  double step_toward(double current, double target, double dt) const {
    target = std::min(target, speed);
    return std::clamp(target, current - deceleration * dt, current + acceleration * dt);
  }
};

inline SpeedLimits speed_limits(const Entity& entity,
                                const std::optional<xosc::DynamicConstraints>& constraints) {
  SpeedLimits limits;
  if (entity.info.max_acceleration > 0.0) {
    limits.acceleration = entity.info.max_acceleration;
  }
  if (entity.info.max_deceleration > 0.0) {
    limits.deceleration = entity.info.max_deceleration;
  }
  if (entity.info.max_speed > 0.0) {
    limits.speed = entity.info.max_speed;
  }
  if (constraints) {
    if (constraints->max_acceleration && *constraints->max_acceleration > 0.0) {
      limits.acceleration = *constraints->max_acceleration;
    }
    if (constraints->max_deceleration && *constraints->max_deceleration > 0.0) {
      limits.deceleration = *constraints->max_deceleration;
    }
    if (constraints->max_speed && *constraints->max_speed > 0.0) {
      limits.speed = *constraints->max_speed;
    }
  }
  return limits;
}

}  // namespace corsa::engine::detail
