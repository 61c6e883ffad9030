#pragma once

// The vehicle model of the `dynamics` controller: a single-track (bicycle) model with nonlinear
// tyre forces, integrated by SUNDIALS ARKODE (ERKStep: explicit 4th-order Runge-Kutta at a fixed
// step of at most 10 ms: the inputs change at every engine step, which an adaptive multistep
// method pays for with step-size cuts; the fixed step keeps the cost per engine step constant).
// Below kKinematicSpeed the tyre slip angles are ill defined (they divide by the forward speed, and
// the fastest mode, about -17 g / vx per second, would leave RK4's stability region) and the model
// is the kinematic bicycle instead.
//
// Frames: x forward, y left, yaw counter-clockwise (ISO 8855 / OpenSCENARIO). The pose is the
// vehicle's reference point, the rear axle centre (OpenSCENARIO BoundingBox convention).

#include <memory>

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

class DynamicsIntegrator {
 public:
  explicit DynamicsIntegrator(const VehicleParams& params);
  ~DynamicsIntegrator();
  DynamicsIntegrator(const DynamicsIntegrator&) = delete;
  DynamicsIntegrator& operator=(const DynamicsIntegrator&) = delete;

  /// Starts from `state` (a new vehicle, or one moved from outside: teleport, mode change).
  void reset(const VehicleState& state);
  /// Advances by dt (s) under `inputs`. Returns the new state.
  const VehicleState& step(const VehicleInputs& inputs, double dt);
  const VehicleState& state() const { return state_; }
  const VehicleParams& params() const { return params_; }
  /// Lateral acceleration (m/s^2) at the centre of gravity over the last step.
  double lateral_acceleration() const { return lateral_acceleration_; }

 private:
  struct Solver;
  void step_kinematic(const VehicleInputs& inputs, double dt);
  void step_dynamic(const VehicleInputs& inputs, double dt);

  VehicleParams params_;
  VehicleState state_;
  double lateral_acceleration_ = 0.0;
  bool dynamic_ = false;  ///< the ODE solver holds the current state
  std::unique_ptr<Solver> solver_;
};

}  // namespace corsa::engine::detail
