#pragma once

// Integrates the single-track models (dynamics_model.h) of every dynamic vehicle of one engine
// step as one ODE system with SUNDIALS ARKODE (ERKStep, the classic 4th-order Runge-Kutta
// method at a fixed step of at most 10 ms). The vehicles do not interact, so the system is
// block diagonal and every vehicle's result is the same as if it were integrated alone; one
// system per step pays ARKODE's per-step overhead (bookkeeping, norms, vector operations) once
// instead of once per vehicle, which was more than half of a dynamics vehicle's cost.

#include <memory>
#include <vector>

namespace corsa::engine::detail {

class DynamicsIntegrator;

class DynamicsFleet {
 public:
  DynamicsFleet();
  ~DynamicsFleet();
  DynamicsFleet(const DynamicsFleet&) = delete;
  DynamicsFleet& operator=(const DynamicsFleet&) = delete;

  /// Queues a vehicle for the next integrate() (DynamicsIntegrator::begin_step does this).
  void add(DynamicsIntegrator& vehicle) { queued_.push_back(&vehicle); }
  /// Advances every queued vehicle by dt (s) under the inputs of its begin_step, then empties
  /// the queue. Throws std::runtime_error when SUNDIALS fails.
  void integrate(double dt);

 private:
  struct Solver;
  std::vector<DynamicsIntegrator*> queued_;
  std::unique_ptr<Solver> solver_;  ///< made, or remade larger, when more vehicles are queued
};

}  // namespace corsa::engine::detail
