#pragma once

// The parts of the _corsa extension, each registered by one function (module.cpp).

#include <pybind11/pybind11.h>

#include <cstdint>
#include <filesystem>

#include "py_simulation.h"

namespace corsa::python {

/// corsa.Simulation and corsa.EntityState (simulation_bindings.cpp).
void bind_simulation(pybind11::module_& module);
/// corsa._read_trajectory, the work of corsa.read_trajectory (trajectory.cpp).
void bind_trajectory(pybind11::module_& module);
/// corsa._sweep and corsa._test, the work of corsa.sweep and corsa.test (batch.cpp).
void bind_batch(pybind11::module_& module);

/// Checks what corsa.Simulation was given as `corsa run` checks its options and turns it into a
/// setup. Throws ValueError / TypeError naming the argument (setup.cpp).
SimulationSetup simulation_setup(const std::filesystem::path& path, double dt, uint64_t seed,
                                 const pybind11::object& params, const pybind11::object& controller,
                                 const pybind11::object& npc, const pybind11::object& external,
                                 double duration);

/// The step and duration checks of `corsa run --dt/--duration` (ValueError).
void check_step(double dt, double duration);

}  // namespace corsa::python
