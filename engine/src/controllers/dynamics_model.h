#pragma once

// The vehicle model of the `dynamics` controller: a single-track (bicycle) model with nonlinear
// tyre forces. Above kKinematicSpeed it is an ODE that DynamicsFleet (dynamics_fleet.h)
// integrates with SUNDIALS ARKODE, every vehicle of a step in one system. Below kKinematicSpeed
// the tyre slip angles are ill defined (they divide by the forward speed, and the fastest mode,
// about -17 g / vx per second, would leave the explicit method's stability region) and the model
// is the kinematic bicycle instead, stepped in closed form here.
//
// Frames: x forward, y left, yaw counter-clockwise (ISO 8855 / OpenSCENARIO). The pose is the
// vehicle's reference point, the rear axle centre (OpenSCENARIO BoundingBox convention).

namespace corsa::engine::detail {

/// Mass, geometry and tyres of one vehicle (SI units).
struct VehicleParams {
  double mass = 1500.0;               ///< kg
  double yaw_inertia = 2500.0;        ///< kg m^2
  double wheelbase = 2.8;             ///< m, rear to front axle
  double cg_to_rear = 1.4;            ///< m, centre of gravity ahead of the rear axle
  double cornering_stiffness = 17.0;  ///< per axle, N/rad per N of axle load
  double friction = 1.0;              ///< tyre-road friction coefficient
  double max_steering = 0.5;          ///< rad, front wheels
  double steering_lag = 0.08;         ///< s, first-order steering actuator
  double drive_lag = 0.15;            ///< s, first-order drive/brake actuator
};

/// The model state: rear-axle pose, body velocities at the centre of gravity, actuators.
struct VehicleState {
  double x = 0.0, y = 0.0, yaw = 0.0;  ///< m, m, rad
  double vx = 0.0, vy = 0.0;           ///< m/s, body frame at the centre of gravity
  double yaw_rate = 0.0;               ///< rad/s
  double steer = 0.0;                  ///< rad, front wheel angle
  double accel = 0.0;                  ///< m/s^2, longitudinal force / mass
};

/// Inputs held over one step.
struct VehicleInputs {
  double steer = 0.0;  ///< rad, demanded front wheel angle
  double accel = 0.0;  ///< m/s^2, demanded longitudinal acceleration (negative: braking)
  bool reverse = false;
};

/// Speed (m/s) below which the kinematic bicycle is used.
inline constexpr double kKinematicSpeed = 2.0;

class DynamicsFleet;

/// One vehicle's model. A step has two halves: begin_step (the kinematic bicycle steps at once;
/// a dynamic vehicle is queued on a DynamicsFleet), then DynamicsFleet::integrate.
class DynamicsIntegrator {
 public:
  explicit DynamicsIntegrator(const VehicleParams& params) : params_(params) {}

  /// Starts from `state` (a new vehicle, or one moved from outside: teleport, mode change).
  void reset(const VehicleState& state);
  /// Begins a step of dt (s) under `inputs` (steering clamped to max_steering). Below
  /// kKinematicSpeed the step is done on return; otherwise the vehicle is added to `fleet`, and
  /// its state is the new one after the fleet's next integrate().
  void begin_step(const VehicleInputs& inputs, double dt, DynamicsFleet& fleet);
  const VehicleState& state() const { return state_; }
  const VehicleParams& params() const { return params_; }
  /// Lateral acceleration (m/s^2) at the centre of gravity over the last step.
  double lateral_acceleration() const { return lateral_acceleration_; }

 private:
  friend class DynamicsFleet;
  void step_kinematic(const VehicleInputs& inputs, double dt);

  VehicleParams params_;
  VehicleState state_;
  VehicleInputs inputs_;  ///< of the step under way
  double lateral_acceleration_ = 0.0;
};

}  // namespace corsa::engine::detail
