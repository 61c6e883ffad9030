#include "controllers/dynamics_fleet.h"

#include <arkode/arkode_erkstep.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "controllers/dynamics_model.h"

namespace corsa::engine::detail {
namespace {

constexpr double kGravity = 9.81;     // m/s^2
constexpr int kStates = 8;            // per vehicle: x, y, yaw, vx, vy, r, steer, accel
constexpr double kMaxSubstep = 0.01;  // s

// One vehicle of the system: its parameters in the form the right-hand side uses, and its
// inputs over the step.
struct Slot {
  double lf = 0.0, lr = 0.0;      // m, centre of gravity to front / rear axle
  double inv_mass = 0.0;          // 1/kg
  double inv_inertia = 0.0;       // 1/(kg m^2)
  double slope_front = 0.0;       // 1/rad, cornering stiffness / friction
  double slope_rear = 0.0;        // 1/rad
  double limit_front = 0.0;       // N, friction x axle load
  double limit_rear = 0.0;        // N
  double inv_steering_lag = 0.0;  // 1/s
  double inv_drive_lag = 0.0;     // 1/s
  VehicleInputs inputs;
};

Slot slot_of(const VehicleParams& p, const VehicleInputs& inputs) {
  Slot slot;
  slot.lr = p.cg_to_rear;
  slot.lf = p.wheelbase - p.cg_to_rear;
  slot.inv_mass = 1.0 / p.mass;
  slot.inv_inertia = 1.0 / p.yaw_inertia;
  // Static axle loads from the centre of gravity's position along the wheelbase.
  const double load_front = p.mass * kGravity * slot.lr / p.wheelbase;
  const double load_rear = p.mass * kGravity * slot.lf / p.wheelbase;
  slot.limit_front = p.friction * load_front;
  slot.limit_rear = p.friction * load_rear;
  // C Fz alpha / (mu Fz): the stiffness per unit of load over the friction coefficient.
  slot.slope_front = p.cornering_stiffness / p.friction;
  slot.slope_rear = p.cornering_stiffness / p.friction;
  slot.inv_steering_lag = 1.0 / p.steering_lag;
  slot.inv_drive_lag = 1.0 / p.drive_lag;
  slot.inputs = inputs;
  return slot;
}

struct RhsData {
  std::vector<Slot> slots;  // vehicle i is y[8 i .. 8 i + 7]
};

// dy/dt of one single-track model (e.g. Rajamani, Vehicle Dynamics and Control, §2.3), written
// for the rear-axle reference point: the rear axle moves at (vx, vy - lr r) in the body frame.
// Lateral tyre force per axle: -mu Fz tanh(C alpha / mu), linear in the slip angle for small
// angles (cornering stiffness C Fz) and saturating smoothly at the friction limit (a simplified
// Pacejka curve).
void vehicle_rhs(const Slot& p, const double* y, double* dy) {
  const double yaw = y[2], vx = y[3], vy = y[4], r = y[5], steer = y[6], accel = y[7];
  const double u = std::max(vx, 0.5 * kKinematicSpeed);
  // Slip angles: atan2(v_lateral, u) with u > 0, i.e. atan(v_lateral / u).
  const double slip_front = std::atan((vy + p.lf * r) / u) - steer;
  const double slip_rear = std::atan((vy - p.lr * r) / u);
  const double fy_front = -p.limit_front * std::tanh(p.slope_front * slip_front);
  const double fy_rear = -p.limit_rear * std::tanh(p.slope_rear * slip_rear);
  const double c = std::cos(yaw), s = std::sin(yaw);
  const double cs = std::cos(steer), ss = std::sin(steer);
  const double v_rear = vy - p.lr * r;
  dy[0] = vx * c - v_rear * s;
  dy[1] = vx * s + v_rear * c;
  dy[2] = r;
  double dvx = accel - fy_front * ss * p.inv_mass + vy * r;
  // Braking stops the car; it does not drive it backwards.
  if (vx <= 0.0 && dvx < 0.0 && !p.inputs.reverse) {
    dvx = 0.0;
  }
  dy[3] = dvx;
  dy[4] = (fy_front * cs + fy_rear) * p.inv_mass - vx * r;
  dy[5] = (p.lf * fy_front * cs - p.lr * fy_rear) * p.inv_inertia;
  dy[6] = (p.inputs.steer - steer) * p.inv_steering_lag;
  dy[7] = (p.inputs.accel - accel) * p.inv_drive_lag;
}

int fleet_rhs(sunrealtype /*t*/, N_Vector y_vec, N_Vector dy_vec, void* user) {
  const auto& data = *static_cast<const RhsData*>(user);
  const double* y = N_VGetArrayPointer(y_vec);
  double* dy = N_VGetArrayPointer(dy_vec);
  for (size_t i = 0; i < data.slots.size(); ++i) {
    vehicle_rhs(data.slots[i], y + kStates * i, dy + kStates * i);
  }
  return 0;
}

// The vector operations ARKODE spends its time in, for serial vectors, compiled with the
// engine. The distribution's NVECTOR_SERIAL takes about 14 instructions per element to copy or
// scale and about 20 per element and term for a linear combination, which made ARKODE's own
// work (stage sums, copies for its interpolation module, norms) cost more than the vehicle
// models' right-hand sides. These are the same sums in the same order, one pass each.
void vector_scale(sunrealtype c, N_Vector x, N_Vector z) {
  const sunindextype n = NV_LENGTH_S(x);
  const double* xd = NV_DATA_S(x);
  double* zd = NV_DATA_S(z);
  if (c == 1.0) {
    std::copy(xd, xd + n, zd);  // ARKODE's copies (N_VScale(1, x, z))
    return;
  }
  for (sunindextype j = 0; j < n; ++j) {
    zd[j] = c * xd[j];
  }
}

void vector_linear_sum(sunrealtype a, N_Vector x, sunrealtype b, N_Vector y, N_Vector z) {
  const sunindextype n = NV_LENGTH_S(x);
  const double* xd = NV_DATA_S(x);
  const double* yd = NV_DATA_S(y);
  double* zd = NV_DATA_S(z);
  for (sunindextype j = 0; j < n; ++j) {
    zd[j] = a * xd[j] + b * yd[j];
  }
}

// z = sum of c[i] x[i], summed from i = 0 up for every element. ARKODE's stage and solution
// sums pass z = x[0]; z being a later term takes the slower element-by-element loop.
int vector_linear_combination(int count, sunrealtype* c, N_Vector* x, N_Vector z) {
  constexpr int kMaxTerms = 16;  // RK4's longest sum has 5 (y and 4 stage derivatives)
  if (count < 1 || count > kMaxTerms) {
    return -1;
  }
  const sunindextype n = NV_LENGTH_S(z);
  double* zd = NV_DATA_S(z);
  const double* xd[kMaxTerms];
  bool later_alias = false;
  for (int i = 0; i < count; ++i) {
    xd[i] = NV_DATA_S(x[i]);
    later_alias = later_alias || (i > 0 && xd[i] == zd);
  }
  if (later_alias) {
    for (sunindextype j = 0; j < n; ++j) {
      double sum = c[0] * xd[0][j];
      for (int i = 1; i < count; ++i) {
        sum += c[i] * xd[i][j];
      }
      zd[j] = sum;
    }
    return 0;
  }
  if (xd[0] != zd || c[0] != 1.0) {
    for (sunindextype j = 0; j < n; ++j) {
      zd[j] = c[0] * xd[0][j];
    }
  }
  for (int i = 1; i < count; ++i) {
    const double ci = c[i];
    const double* xi = xd[i];
    for (sunindextype j = 0; j < n; ++j) {
      zd[j] += ci * xi[j];
    }
  }
  return 0;
}

sunrealtype vector_wrms_norm(N_Vector x, N_Vector w) {
  const sunindextype n = NV_LENGTH_S(x);
  const double* xd = NV_DATA_S(x);
  const double* wd = NV_DATA_S(w);
  double sum = 0.0;
  for (sunindextype j = 0; j < n; ++j) {
    const double v = xd[j] * wd[j];
    sum += v * v;
  }
  return std::sqrt(sum / static_cast<double>(n));
}

}  // namespace

struct DynamicsFleet::Solver {
  SUNContext context = nullptr;
  N_Vector y = nullptr;
  void* arkode = nullptr;
  RhsData data;
  double step = 0.0;  ///< the fixed step set, s

  explicit Solver(size_t capacity) {
    data.slots.resize(capacity);
    if (SUNContext_Create(nullptr, &context) != 0) {
      throw std::runtime_error("SUNDIALS: cannot create a context");
    }
    y = N_VNew_Serial(static_cast<sunindextype>(kStates * capacity), context);
    if (y != nullptr) {
      // One pass over the vectors for a linear combination of several (the stage sums) instead
      // of one N_VLinearSum per term, and the engine's own kernels for the busiest operations;
      // ARKODE's work vectors are clones and inherit the operations.
      N_VEnableFusedOps_Serial(y, SUNTRUE);
      y->ops->nvscale = vector_scale;
      y->ops->nvlinearsum = vector_linear_sum;
      y->ops->nvlinearcombination = vector_linear_combination;
      y->ops->nvwrmsnorm = vector_wrms_norm;
      N_VConst(0.0, y);
      arkode = ERKStepCreate(fleet_rhs, 0.0, y, context);
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

DynamicsFleet::DynamicsFleet() = default;
DynamicsFleet::~DynamicsFleet() = default;

void DynamicsFleet::integrate(double dt) {
  const size_t count = queued_.size();
  if (count == 0) {
    return;
  }
  if (!solver_ || solver_->data.slots.size() != count) {
    // Exactly as large as needed: every vector operation of a step runs over the whole system
    // (remaking it costs about as much as one step, and the count changes rarely).
    solver_ = std::make_unique<Solver>(count);
  }
  Solver& solver = *solver_;
  double* y = N_VGetArrayPointer(solver.y);
  for (size_t i = 0; i < count; ++i) {
    const DynamicsIntegrator& vehicle = *queued_[i];
    solver.data.slots[i] = slot_of(vehicle.params_, vehicle.inputs_);
    const VehicleState& s = vehicle.state_;
    double* yi = y + kStates * i;
    yi[0] = s.x;
    yi[1] = s.y;
    yi[2] = s.yaw;
    yi[3] = s.vx;
    yi[4] = s.vy;
    yi[5] = s.yaw_rate;
    yi[6] = s.steer;
    yi[7] = s.accel;
  }
  // Fixed steps of at most kMaxSubstep: explicit RK4 is stable there above kKinematicSpeed
  // (the fastest mode, about -17 g / vx per second, times h stays inside RK4's region).
  const int substeps = std::max(1, static_cast<int>(std::ceil(dt / kMaxSubstep - 1e-9)));
  if (solver.step != dt / substeps) {
    solver.step = dt / substeps;
    ERKStepSetFixedStep(solver.arkode, solver.step);
  }
  for (int i = 0; i < substeps; ++i) {
    // Every step starts afresh from y (time 0): the vehicles of a step change from step to
    // step, and some were moved from outside. It also keeps RK4 correct: SUNDIALS 6.4's ERKStep
    // takes a tableau whose last node is c = 1 for "first same as last" and would start the
    // next step from the last stage's derivative (not the one at the new state), which lowers
    // the order to about 3; after a reset the first stage is evaluated at the step's start.
    sunrealtype reached = 0.0;
    if (ERKStepReset(solver.arkode, 0.0, solver.y) != ARK_SUCCESS ||
        ERKStepEvolve(solver.arkode, solver.step, solver.y, &reached, ARK_ONE_STEP) < 0) {
      queued_.clear();
      throw std::runtime_error("SUNDIALS: ARKODE failed to integrate the vehicle models");
    }
  }
  y = N_VGetArrayPointer(solver.y);
  for (size_t i = 0; i < count; ++i) {
    DynamicsIntegrator& vehicle = *queued_[i];
    const double* yi = y + kStates * i;
    const double vy0 = vehicle.state_.vy;
    const bool reverse = vehicle.inputs_.reverse;
    vehicle.state_ = VehicleState{yi[0], yi[1], yi[2], std::max(yi[3], reverse ? yi[3] : 0.0),
                                  yi[4], yi[5], yi[6], yi[7]};
    // a_y = dvy/dt + vx r (body frame, centre of gravity).
    vehicle.lateral_acceleration_ =
        (vehicle.state_.vy - vy0) / dt + vehicle.state_.vx * vehicle.state_.yaw_rate;
  }
  queued_.clear();
}

}  // namespace corsa::engine::detail
