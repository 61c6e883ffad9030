// _sensors: sensors in the loop and data collection for Python (Embree, assimp, PROJ and OpenCV
// live here, not in _corsa, so that `import corsa` does not load them; corsa.Simulation imports
// this extension when it is given a rig). A capture renders every sensor of the rig at the
// simulation's current state into numpy arrays, in memory; corsa.collect writes a dataset as
// `corsa run --rig` does.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bindings.h"
#include "corsa/collect/dataset_run.h"
#include "corsa/collect/run_scene.h"
#include "corsa/core/atomic_file.h"
#include "corsa/engine/environment_override.h"
#include "corsa/sensors/rig.h"
#include "corsa/sensors/scene.h"
#include "corsa/sensors/sensor_system.h"
#include "corsa/sensors/writers.h"
#include "py_simulation.h"
#include "sensor_arrays.h"

namespace corsa::python {
namespace py = pybind11;
namespace {

// Warnings of the sensors as corsa.CorsaWarning (the category lives in _corsa).
void warn_all(const Diagnostics& diagnostics, size_t from) {
  const std::vector<Diagnostic> all = diagnostics.all();
  if (all.size() <= from) return;
  const py::object category = py::module_::import("corsa._corsa").attr("CorsaWarning");
  for (size_t i = from; i < all.size(); ++i) {
    if (PyErr_WarnEx(category.ptr(), all[i].format().c_str(), 2) != 0) {
      throw py::error_already_set();
    }
  }
}

engine::EnvironmentOverride environment_override(const std::optional<std::string>& time_of_day,
                                                 const std::optional<std::string>& weather) {
  engine::EnvironmentOverride out;
  try {
    if (time_of_day) out.time_of_day = engine::parse_time_of_day(*time_of_day);
    if (weather) engine::parse_weather(*weather, out);
  } catch (const std::invalid_argument& error) {
    throw py::value_error(error.what());
  }
  return out;
}

std::vector<collect::ModelSpec> model_specs(const std::vector<std::string>& models) {
  std::vector<collect::ModelSpec> out;
  for (const std::string& text : models) {
    try {
      out.push_back(collect::parse_model_spec(text));
    } catch (const std::invalid_argument& error) {
      throw py::value_error("models: '" + text + "': " + error.what());
    }
  }
  return out;
}

std::vector<collect::EntityModelSpec> entity_model_specs(
    const std::vector<std::string>& entity_models) {
  std::vector<collect::EntityModelSpec> out;
  for (const std::string& text : entity_models) {
    try {
      out.push_back(collect::parse_entity_model_spec(text));
    } catch (const std::invalid_argument& error) {
      throw py::value_error(std::string("entity_models: ") + error.what());
    }
  }
  return out;
}

/// A rig bound to one corsa.Simulation: its scene and sensor system, rendering on demand.
class SensorSession {
 public:
  SensorSession(py::object simulation, const std::filesystem::path& rig_file,
                const std::vector<std::string>& models,
                const std::vector<std::string>& entity_models,
                const std::optional<std::string>& time_of_day,
                const std::optional<std::string>& weather)
      : owner_(std::move(simulation)), simulation_(owner_.cast<PySimulation&>()) {
    environment_ = environment_override(time_of_day, weather);
    const std::vector<collect::ModelSpec> specs = model_specs(models);
    const std::vector<collect::EntityModelSpec> entity_specs = entity_model_specs(entity_models);
    const PySimulation::Busy busy(simulation_);
    const engine::Simulation& sim = simulation_.engine();
    {
      py::gil_scoped_release nogil;
      sensors::SensorRig rig = sensors::load_rig(rig_file);
      std::vector<std::string> names;
      for (size_t i = 0; i < sim.entity_count(); ++i) names.push_back(sim.entity(i).name);
      sensors::bind_rig(rig, names);
      // The caller's entity models first, so that they win over the rig's (as `corsa run`).
      std::vector<sensors::EntityModel> chosen;
      for (const collect::EntityModelSpec& spec : entity_specs) {
        chosen.push_back(collect::resolve_entity_model(spec, names));
      }
      chosen.insert(chosen.end(), rig.entity_models.begin(), rig.entity_models.end());
      rig.entity_models = std::move(chosen);
      scene_ = collect::build_run_scene(sim, specs, rig, diagnostics_);
      sensors::SensorSystemOptions options;
      options.seed = sim.options().seed;
      options.location = collect::run_location(sim, scene_->options().origin, diagnostics_);
      system_ = std::make_unique<sensors::SensorSystem>(std::move(rig), *scene_, options);
      engine::WorldSnapshot initial;
      sim.fill_snapshot(initial);
      start_time_of_day_ = initial.environment.time_of_day;
    }
    warn_all(diagnostics_, 0);
    warned_ = diagnostics_.size();
    for (const sensors::SensorSpec& s : system_->rig().sensors) {
      calibration_[py::str(s.name)] = py::module_::import("json").attr("loads")(
          sensors::calibration_json(s, system_->camera_model(s.name)));
    }
  }

  /// Renders `names` (every sensor when empty) at the simulation's current state.
  py::dict capture(const std::vector<std::string>& names) {
    for (const std::string& name : names) {
      if (system_->rig().find(name) == nullptr) {
        throw py::value_error("the rig has no sensor '" + name + "'");
      }
    }
    engine::WorldSnapshot world;
    std::vector<sensors::SensorFrame> frames;
    const PySimulation::Busy busy(simulation_);
    const engine::Simulation& sim = simulation_.engine();
    {
      py::gil_scoped_release nogil;
      sim.fill_snapshot(world);
      if (!environment_.empty()) {
        engine::apply_override(environment_, start_time_of_day_, world.environment);
      }
      frames = system_->capture(world, names);
    }
    warn_all(diagnostics_, warned_);
    warned_ = diagnostics_.size();
    py::dict data, labels, poses, calibration;
    const py::object loads = py::module_::import("json").attr("loads");
    for (const sensors::SensorFrame& frame : frames) {
      const py::str key(frame.sensor);
      data[key] = frame_array(frame);
      poses[key] = rigid_array(frame.world_from_sensor);
      calibration[key] = calibration_[key];
      if (frame.kind != sensors::SensorKind::kBirdsEyeCamera) {
        labels[key] =
            loads(sensors::labels_json(frame.labels, frame.kind != sensors::SensorKind::kLidar));
      }
    }
    py::dict out;
    out["tick"] = world.tick;
    out["time"] = world.time;
    out["data"] = data;
    out["labels"] = labels;
    out["poses"] = poses;
    out["calibration"] = calibration;
    out["entities"] = entity_dicts(world);
    return out;
  }

  py::list sensors() const {
    py::list out;
    for (const sensors::SensorSpec& s : system_->rig().sensors) {
      out.append(py::make_tuple(s.name, std::string(sensors::sensor_kind_name(s.kind)), s.entity,
                                s.rate_hz));
    }
    return out;
  }

 private:
  py::object owner_;  ///< keeps the simulation alive as long as its sensors
  PySimulation& simulation_;
  Diagnostics diagnostics_;
  size_t warned_ = 0;
  engine::EnvironmentOverride environment_;
  double start_time_of_day_ = 0.0;
  std::unique_ptr<sensors::Scene> scene_;
  std::unique_ptr<sensors::SensorSystem> system_;
  py::dict calibration_;
};

py::dict collect_dataset(const std::filesystem::path& scenario, const std::filesystem::path& rig,
                         const std::filesystem::path& output, const std::string& format, bool force,
                         bool preview, double dt, uint64_t seed, const py::object& params,
                         const py::object& controller, const py::object& npc, double duration,
                         const std::vector<std::string>& models,
                         const std::vector<std::string>& entity_models,
                         const std::optional<std::string>& time_of_day,
                         const std::optional<std::string>& weather) {
  const SimulationSetup setup =
      simulation_setup(scenario, dt, seed, params, controller, npc, py::none(), duration);
  collect::DatasetRunOptions options;
  options.run.scenario = scenario;
  options.run.parameters = setup.parameters;
  options.run.simulation = setup.options;
  options.rig = rig;
  options.output = output;
  if (format == "kitti") {
    options.format = sensors::DatasetFormat::kKitti;
  } else if (format != "corsa") {
    throw py::value_error("format expects 'corsa' or 'kitti', not '" + format + "'");
  }
  options.replace = force;
  options.preview = preview;
  options.environment = environment_override(time_of_day, weather);
  options.time_of_day_text = time_of_day.value_or("");
  options.weather_text = weather.value_or("");
  options.models = model_specs(models);
  options.entity_models = entity_model_specs(entity_models);
  Diagnostics diagnostics;
  collect::DatasetRunHooks hooks;
  bool interrupted = false;
  // Ctrl-C: Python's handler only notes the signal; the run ends after the capture in progress
  // with an "interrupted" dataset, and KeyboardInterrupt is raised once it is consistent.
  hooks.stop = [&interrupted]() -> std::optional<std::string> {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) {
      interrupted = true;
      return std::string("interrupted by SIGINT");
    }
    return std::nullopt;
  };
  collect::DatasetRunReport report;
  {
    py::gil_scoped_release nogil;
    check_output_folder(output);
    report = collect::run_dataset(options, diagnostics, hooks);
  }
  warn_all(diagnostics, 0);
  if (interrupted) throw py::error_already_set();
  py::dict d;
  d["end_reason"] = std::string(engine::to_string(report.run.end_reason));
  d["sim_time"] = report.run.sim_time;
  d["steps"] = report.run.steps;
  d["captures"] = report.captures;
  d["files"] = report.files;
  d["wall_time"] = report.run.wall_seconds;
  return d;
}

}  // namespace

}  // namespace corsa::python

PYBIND11_MODULE(_sensors, module) {
  namespace py = pybind11;
  using corsa::python::SensorSession;
  module.doc() =
      "Corsa's sensors in the loop and data collection (use corsa.Simulation(rig=...) "
      "and corsa.collect).";
  py::class_<SensorSession>(module, "SensorSession")
      .def(py::init<py::object, const std::filesystem::path&, const std::vector<std::string>&,
                    const std::vector<std::string>&, const std::optional<std::string>&,
                    const std::optional<std::string>&>(),
           py::arg("simulation"), py::arg("rig"), py::arg("models"), py::arg("entity_models"),
           py::arg("time_of_day"), py::arg("weather"))
      .def("capture", &SensorSession::capture, py::arg("sensors"))
      .def_property_readonly("sensors", &SensorSession::sensors);
  module.def("collect", &corsa::python::collect_dataset, py::arg("scenario"), py::arg("rig"),
             py::arg("output"), py::arg("format"), py::arg("force"), py::arg("preview"),
             py::arg("dt"), py::arg("seed"), py::arg("params"), py::arg("controller"),
             py::arg("npc"), py::arg("duration"), py::arg("models"), py::arg("entity_models"),
             py::arg("time_of_day"), py::arg("weather"));
}
