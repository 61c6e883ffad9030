#include "controllers/dynamics_model.h"

#include <arkode/arkode_erkstep.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

#include <algorithm>
#include <cmath>

#include "corsa/core/diagnostic.h"

namespace corsa::engine::detail {
namespace {

constexpr double kGravity = 9.81;     // m/s^2
constexpr int kStates = 8;            // x, y, yaw, vx, vy, r, steer, accel
constexpr double kMaxSubstep = 0.01;  // s

struct RhsData {
  const VehicleParams* params = nullptr;
  VehicleInputs inputs;
};

// Tyre lateral force (N) of one axle: linear in the slip angle for small angles (cornering
// stiffness), saturating smoothly at the friction limit (tanh, a simplified Pacejka curve).
double tyre_force(double slip, double stiffness, double limit) {
  return -limit * std::tanh(stiffness * slip / limit);
}

// dy/dt of the single-track model (e.g. Rajamani, Vehicle Dynamics and Control, §2.3), written
// for the rear-axle reference point: the rear axle moves at (vx, vy - lr r) in the body frame.
int rhs(sunrealtype /*t*/, N_Vector y_vec, N_Vector dy_vec, void* user) {
  const auto& data = *static_cast<const RhsData*>(user);
  const VehicleParams& p = *data.params;
  const double* y = N_VGetArrayPointer(y_vec);
  double* dy = N_VGetArrayPointer(dy_vec);
  const double yaw = y[2], vx = y[3], vy = y[4], r = y[5], steer = y[6], accel = y[7];
  const double lr = p.cg_to_rear, lf = p.wheelbase - p.cg_to_rear;
  const double load_front = p.mass * kGravity * lr / p.wheelbase;
  const double load_rear = p.mass * kGravity * lf / p.wheelbase;
  const double u = std::max(vx, 0.5 * kKinematicSpeed);
  const double slip_front = std::atan2(vy + lf * r, u) - steer;
  const double slip_rear = std::atan2(vy - lr * r, u);
  const double fy_front =
      tyre_force(slip_front, p.cornering_stiffness * load_front, p.friction * load_front);
  const double fy_rear =
      tyre_force(slip_rear, p.cornering_stiffness * load_rear, p.friction * load_rear);
  const double c = std::cos(yaw), s = std::sin(yaw);
  const double v_rear = vy - lr * r;
  dy[0] = vx * c - v_rear * s;
  dy[1] = vx * s + v_rear * c;
  dy[2] = r;
  double dvx = accel - fy_front * std::sin(steer) / p.mass + vy * r;
  // Braking stops the car; it does not drive it backwards.
  if (vx <= 0.0 && dvx < 0.0 && !data.inputs.reverse) {
    dvx = 0.0;
  }
  dy[3] = dvx;
  dy[4] = (fy_front * std::cos(steer) + fy_rear) / p.mass - vx * r;
  dy[5] = (lf * fy_front * std::cos(steer) - lr * fy_rear) / p.yaw_inertia;
  dy[6] = (data.inputs.steer - steer) / p.steering_lag;
  dy[7] = (data.inputs.accel - accel) / p.drive_lag;
  return 0;
}

}  // namespace

struct DynamicsIntegrator::Solver {
  SUNContext context = nullptr;
  N_Vector y = nullptr;
  void* arkode = nullptr;
  RhsData data;
  double t = 0.0;
  double step = 0.0;  ///< the fixed step set, s

  explicit Solver(const VehicleParams& params) {
    data.params = &params;
    if (SUNContext_Create(nullptr, &context) != 0) {
      throw std::runtime_error("SUNDIALS: cannot create a context");
    }
    y = N_VNew_Serial(kStates, context);
    if (y != nullptr) {
      N_VConst(0.0, y);
      arkode = ERKStepCreate(rhs, 0.0, y, context);
    }
    // The classic 4th-order Runge-Kutta tableau, without an embedded method: at a fixed step
    // no error estimate is needed, and it takes 4 stages where ARKODE's default order-4 method
    // (with its embedding) takes 5.
    const double c[4] = {0.0, 0.5, 0.5, 1.0};
    const double a[16] = {0.0, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0,
                          0.0, 0.5, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0};
    const double b[4] = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};
    ARKodeButcherTable table = ARKodeButcherTable_Create(
        4, 4, 0, const_cast<double*>(c), const_cast<double*>(a), const_cast<double*>(b), nullptr);
    const bool table_set =
        arkode != nullptr && table != nullptr && ERKStepSetTable(arkode, table) == ARK_SUCCESS;
    if (table != nullptr) {
      ARKodeButcherTable_Free(table);  // ERKStep keeps its own copy
    }
    if (!table_set || ERKStepSetUserData(arkode, &data) != ARK_SUCCESS) {
      release();
      throw std::runtime_error("SUNDIALS: cannot set up ARKODE");
    }
  }
  ~Solver() { release(); }
  Solver(const Solver&) = delete;
  Solver& operator=(const Solver&) = delete;

  void release() {
    if (arkode != nullptr) ERKStepFree(&arkode);
    if (y != nullptr) N_VDestroy(y);
    if (context != nullptr) SUNContext_Free(&context);
    arkode = nullptr;
    y = nullptr;
    context = nullptr;
  }
};

DynamicsIntegrator::DynamicsIntegrator(const VehicleParams& params)
    : params_(params), solver_(std::make_unique<Solver>(params_)) {}

DynamicsIntegrator::~DynamicsIntegrator() = default;

void DynamicsIntegrator::reset(const VehicleState& state) {
  state_ = state;
  dynamic_ = false;
  lateral_acceleration_ = 0.0;
}

const VehicleState& DynamicsIntegrator::step(const VehicleInputs& inputs, double dt) {
  VehicleInputs in = inputs;
  in.steer = std::clamp(in.steer, -params_.max_steering, params_.max_steering);
  if (state_.vx < kKinematicSpeed) {
    step_kinematic(in, dt);
  } else {
    step_dynamic(in, dt);
  }
  return state_;
}

// Below kKinematicSpeed: the kinematic bicycle (no tyre slip), rear-axle reference, with the
// same first-order actuators (exact exponential update over the step).
void DynamicsIntegrator::step_kinematic(const VehicleInputs& inputs, double dt) {
  dynamic_ = false;
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

void DynamicsIntegrator::step_dynamic(const VehicleInputs& inputs, double dt) {
  Solver& solver = *solver_;
  solver.data.inputs = inputs;
  double* y = N_VGetArrayPointer(solver.y);
  if (!dynamic_) {
    // (Re)start from the current state: the history of the multistep method is not valid
    // across a mode change or an outside move.
    y[0] = state_.x;
    y[1] = state_.y;
    y[2] = state_.yaw;
    y[3] = state_.vx;
    y[4] = state_.vy;
    y[5] = state_.yaw_rate;
    y[6] = state_.steer;
    y[7] = state_.accel;
    solver.t = 0.0;
    if (ERKStepReInit(solver.arkode, rhs, 0.0, solver.y) != ARK_SUCCESS) {
      throw std::runtime_error("SUNDIALS: ERKStepReInit failed");
    }
    dynamic_ = true;
  }
  // Fixed steps of at most kMaxSubstep: explicit RK4 is stable there above kKinematicSpeed
  // (the fastest mode, about -17 g / vx per second, times h stays inside RK4's region).
  const int substeps = std::max(1, static_cast<int>(std::ceil(dt / kMaxSubstep - 1e-9)));
  if (solver.step != dt / substeps) {
    solver.step = dt / substeps;
    ERKStepSetFixedStep(solver.arkode, solver.step);
  }
  const double vy0 = y[4];
  const double target = solver.t + dt;
  // One internal step per substep (no interpolation to the output time: the steps end on it).
  sunrealtype reached = solver.t;
  for (int i = 0; i < substeps; ++i) {
    if (ERKStepEvolve(solver.arkode, target, solver.y, &reached, ARK_ONE_STEP) < 0) {
      throw std::runtime_error("SUNDIALS: ARKODE failed to integrate the vehicle model");
    }
  }
  solver.t = target;
  y = N_VGetArrayPointer(solver.y);
  state_ = VehicleState{y[0], y[1], y[2], std::max(y[3], inputs.reverse ? y[3] : 0.0),
                        y[4], y[5], y[6], y[7]};
  // a_y = dvy/dt + vx r (body frame, centre of gravity).
  lateral_acceleration_ = (state_.vy - vy0) / dt + state_.vx * state_.yaw_rate;
  // Time keeps growing in the solver; restart now and then so that it stays exact.
  if (solver.t > 1.0e5) {
    dynamic_ = false;
  }
}

}  // namespace corsa::engine::detail
