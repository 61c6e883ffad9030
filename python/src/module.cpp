// _corsa: the engine, sweeps and suites for Python (the `corsa` package, python/corsa/, wraps it).
// It links no sensor library (Embree, OpenCV, assimp, PROJ), so that `import corsa` stays quick;
// the sensors are the separate extension _sensors, loaded when a rig is used.

#include <pybind11/pybind11.h>

#include <string>

#include "bindings.h"
#include "corsa/core/version.h"
#include "errors.h"

PYBIND11_MODULE(_corsa, module) {
  module.doc() = "Corsa's engine, sweeps and suites (use the corsa package).";
  module.attr("__version__") = std::string(corsa::version());
  corsa::python::bind_errors(module);
  corsa::python::bind_simulation(module);
  corsa::python::bind_batch(module);
  corsa::python::bind_trajectory(module);
}
