#include "controllers/dynamics_model.h"

#include <algorithm>
#include <cmath>

#include "controllers/dynamics_fleet.h"

namespace corsa::engine::detail {

void DynamicsIntegrator::reset(const VehicleState& state) {
  state_ = state;
  lateral_acceleration_ = 0.0;
}

void DynamicsIntegrator::begin_step(const VehicleInputs& inputs, double dt, DynamicsFleet& fleet) {
  inputs_ = inputs;
  inputs_.steer = std::clamp(inputs_.steer, -params_.max_steering, params_.max_steering);
  if (state_.vx < kKinematicSpeed) {
    step_kinematic(inputs_, dt);
  } else {
    fleet.add(*this);
  }
}

// Below kKinematicSpeed: the kinematic bicycle (no tyre slip), rear-axle reference, with the
// same first-order actuators (exact exponential update over the step).
void DynamicsIntegrator::step_kinematic(const VehicleInputs& inputs, double dt) {
  VehicleState& s = state_;
  s.steer += (inputs.steer - s.steer) * (1.0 - std::exp(-dt / params_.steering_lag));
  s.accel += (inputs.accel - s.accel) * (1.0 - std::exp(-dt / params_.drive_lag));
  const double v0 = s.vx;
  double v1 = v0 + s.accel * dt;
  if (!inputs.reverse && v0 >= 0.0 && v1 < 0.0) {
    v1 = 0.0;
  }
  const double v = 0.5 * (v0 + v1);
  const double r = v * std::tan(s.steer) / params_.wheelbase;
  const double yaw_mid = s.yaw + 0.5 * r * dt;
  s.x += v * std::cos(yaw_mid) * dt;
  s.y += v * std::sin(yaw_mid) * dt;
  s.yaw += r * dt;
  // Without slip the centre of gravity moves sideways at lr r relative to the rear axle.
  s.vx = v1;
  s.yaw_rate = v1 * std::tan(s.steer) / params_.wheelbase;
  s.vy = params_.cg_to_rear * s.yaw_rate;
  lateral_acceleration_ = v * r;
}

}  // namespace corsa::engine::detail
