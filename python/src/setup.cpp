// corsa.Simulation's arguments, checked as the command line checks `corsa run`'s options.

#include <cmath>
#include <string>

#include "bindings.h"
#include "corsa/geo/crs_transform.h"
#include "values.h"

namespace corsa::python {
namespace py = pybind11;

void check_step(double dt, double duration) {
  // At least 0.1 ms: a step of 1e-300 s is endless steps, a hang rather than a run.
  if (!(dt >= 1e-4) || dt > 10.0) {
    throw py::value_error("dt expects a step in seconds, 0.0001 <= dt <= 10, not " +
                          std::to_string(dt));
  }
  if (!(duration >= 0.0) || !std::isfinite(duration)) {
    throw py::value_error("duration expects a finite number of seconds >= 0");
  }
}

namespace {

void read_npc(const py::handle& npc, engine::SimulationOptions& options) {
  if (!py::isinstance<py::dict>(npc)) {
    throw py::type_error("npc expects a dict such as {'vehicles': 10, 'pedestrians': 5}");
  }
  for (const auto& [key, value] : npc.cast<py::dict>()) {
    const std::string name = py::str(key);
    if (!py::isinstance<py::int_>(value) || py::isinstance<py::bool_>(value) ||
        value.cast<int64_t>() < 0 || value.cast<int64_t>() > 10000) {
      throw py::value_error("npc['" + name + "'] expects a count 0..10000");
    }
    const auto count = static_cast<uint32_t>(value.cast<int64_t>());
    if (name == "vehicles") {
      options.npc.vehicles = count;
    } else if (name == "pedestrians") {
      options.npc.pedestrians = count;
    } else {
      throw py::value_error("npc: unknown key '" + name + "' (keys: vehicles, pedestrians)");
    }
  }
}

}  // namespace

SimulationSetup simulation_setup(const std::filesystem::path& path, double dt, uint64_t seed,
                                 const py::object& params, const py::object& controller,
                                 const py::object& npc, const py::object& external,
                                 double duration) {
  check_step(dt, duration);
  SimulationSetup setup;
  setup.scenario = path;
  setup.options.dt = dt;
  setup.options.duration = duration;
  setup.options.seed = seed;
  setup.options.geo_projection = geo::geographic_to_projected;  // GeoPositions (PROJ)
  if (!params.is_none()) {
    for (const auto& [name, value] : params.cast<py::dict>()) {
      const std::string key = py::str(name);
      setup.parameters.emplace_back(key, parameter_text(value, "params['" + key + "']"));
    }
  }
  if (!controller.is_none()) {
    const std::string name = controller.cast<std::string>();
    if (name != "default" && name != "acc" && name != "dynamics") {
      throw py::value_error("controller expects 'default', 'acc' or 'dynamics', not '" + name +
                            "'");
    }
    setup.options.controller = name;
  }
  if (!npc.is_none()) {
    read_npc(npc, setup.options);
  }
  // An ExternalController of the scenario is always Python's to drive; `external` names more.
  setup.options.external_controllers.emplace_back("ExternalController");
  if (!external.is_none()) {
    if (py::isinstance<py::str>(external)) {
      throw py::type_error("external expects a list of controller names, not a str");
    }
    for (const auto& name : external) {
      setup.options.external_controllers.push_back(name.cast<std::string>());
    }
  }
  return setup;
}

}  // namespace corsa::python
