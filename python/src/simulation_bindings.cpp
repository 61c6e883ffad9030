// corsa.Simulation's Python face (the class is PySimulation, py_simulation.h): construction from
// the same options as `corsa run`, stepping, the state of the run, control from outside.

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>

#include "bindings.h"
#include "corsa/engine/outputs.h"
#include "corsa/xosc/scenario.h"
#include "py_simulation.h"
#include "values.h"

namespace corsa::python {
namespace py = pybind11;
namespace {

/// What state(name) returns: one entity now.
struct StateView {
  std::string name;
  double x = 0.0, y = 0.0, z = 0.0, h = 0.0, p = 0.0, r = 0.0;
  double speed = 0.0, acceleration = 0.0, lateral_speed = 0.0, yaw_rate = 0.0, odometer = 0.0;
  std::optional<std::string> road;
  std::optional<int> lane;
  std::optional<double> s, t;
  bool present = false;
};

StateView state_view(const engine::Simulation& sim, size_t index) {
  const engine::EntityState& e = sim.state(index);
  StateView v;
  v.name = sim.entity(index).name;
  v.x = e.pose.x;
  v.y = e.pose.y;
  v.z = e.pose.z;
  v.h = e.pose.h;
  v.p = e.pose.p;
  v.r = e.pose.r;
  v.speed = e.speed;
  v.acceleration = e.acceleration;
  v.lateral_speed = e.lateral_speed;
  v.yaw_rate = e.yaw_rate;
  v.odometer = e.odometer;
  if (e.road) {
    v.road = sim.road_id(e.road->road);
    v.lane = e.road->lane;
    v.s = e.road->s;
    v.t = e.road->t;
  }
  v.present = e.placed;
  return v;
}

py::dict state_dict(const StateView& v) {
  py::dict d;
  d["name"] = v.name;
  d["x"] = v.x;
  d["y"] = v.y;
  d["z"] = v.z;
  d["h"] = v.h;
  d["p"] = v.p;
  d["r"] = v.r;
  d["speed"] = v.speed;
  d["acceleration"] = v.acceleration;
  d["road"] = v.road;
  d["lane"] = v.lane;
  d["s"] = v.s;
  d["t"] = v.t;
  d["lateral_speed"] = v.lateral_speed;
  d["yaw_rate"] = v.yaw_rate;
  d["odometer"] = v.odometer;
  d["present"] = v.present;
  return d;
}

// Every entity as one record of states_dtype(), filled without a Python object per entity.
py::array states(PySimulation& self) {
  const auto dtype = py::reinterpret_borrow<py::dtype>(self.states_dtype());
  const engine::Simulation& sim = self.engine();
  const size_t count = sim.entity_count();
  const size_t itemsize = self.states_itemsize();
  py::array out(dtype, std::vector<py::ssize_t>{static_cast<py::ssize_t>(count)});
  auto* base = static_cast<char*>(out.mutable_data());
  std::memset(base, 0, count * itemsize);
  constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
  for (size_t i = 0; i < count; ++i) {
    char* row = base + i * itemsize;
    const engine::EntityState& e = sim.state(i);
    const double motion[8] = {e.pose.x, e.pose.y, e.pose.z, e.pose.h,
                              e.pose.p, e.pose.r, e.speed,  e.acceleration};
    std::memcpy(row + kStateOffsets.motion, motion, sizeof motion);
    const double s = e.road ? e.road->s : kNan;
    const double t = e.road ? e.road->t : kNan;
    const int32_t lane = e.road ? e.road->lane : 0;
    std::memcpy(row + kStateOffsets.s, &s, sizeof s);
    std::memcpy(row + kStateOffsets.t, &t, sizeof t);
    std::memcpy(row + kStateOffsets.lane, &lane, sizeof lane);
    row[kStateOffsets.present] = e.placed ? 1 : 0;
    if (e.road) {
      const std::u32string& road = self.road_text(e.road->road);
      std::memcpy(row + kStateOffsets.road, road.data(), road.size() * sizeof(char32_t));
    }
  }
  return out;
}

py::object summary(PySimulation& self, double wall_seconds) {
  const std::string text = engine::summary_json(self.engine(), wall_seconds);
  return py::module_::import("json").attr("loads")(text);
}

py::list event_log(const engine::Simulation& sim) {
  py::list out;
  for (const engine::TransitionRecord& record : sim.transitions()) {
    py::dict row;
    row["time"] = record.time;
    row["tick"] = record.tick;
    row["type"] = std::string(engine::to_string(record.type));
    row["element"] = record.path;
    row["transition"] = std::string(engine::to_string(record.transition));
    row["state"] = std::string(engine::to_string(record.state));
    out.append(std::move(row));
  }
  return out;
}

py::list collisions(const engine::Simulation& sim) {
  py::list out;
  for (const engine::CollisionRecord& c : sim.collisions()) {
    py::dict row;
    row["time"] = c.time;
    row["tick"] = c.tick;
    row["entities"] = py::make_tuple(sim.entity(c.first).name, sim.entity(c.second).name);
    out.append(std::move(row));
  }
  return out;
}

py::dict values_of(const engine::Simulation& sim, bool variables) {
  py::dict out;
  const xosc::Scenario& scenario = sim.scenario();
  const auto add = [&](const std::string& name) {
    const auto value = variables ? sim.variable(name) : sim.parameter(name);
    out[py::str(name)] = value ? to_python(*value) : py::none();
  };
  if (variables) {
    for (const auto& v : scenario.variables) add(v.name);
  } else {
    for (const auto& p : scenario.parameters) add(p.name);
  }
  return out;
}

void set_command(PySimulation& self, const std::string& name, const engine::ExternalCommand& c) {
  try {
    self.engine().command(self.index_of(name), c);
  } catch (const std::invalid_argument& error) {
    throw py::value_error(std::string(error.what()) + " (entity '" + name + "')");
  }
}

using SimulationClass = py::class_<PySimulation>;

/// corsa.EntityState, what Simulation.state(name) returns.
void bind_entity_state(py::module_& m) {
  py::class_<StateView>(m, "EntityState",
                        "One entity now: map frame (m, rad; heading counter-clockwise from +x), "
                        "speed along the heading (m/s), longitudinal acceleration over the last "
                        "step (m/s^2); road, lane, s, t are None off every lane.")
      .def_readonly("name", &StateView::name)
      .def_readonly("x", &StateView::x)
      .def_readonly("y", &StateView::y)
      .def_readonly("z", &StateView::z)
      .def_readonly("h", &StateView::h)
      .def_readonly("p", &StateView::p)
      .def_readonly("r", &StateView::r)
      .def_readonly("speed", &StateView::speed)
      .def_readonly("acceleration", &StateView::acceleration)
      .def_readonly("road", &StateView::road, "OpenDRIVE road id")
      .def_readonly("lane", &StateView::lane, "lane id (> 0 left of the reference line)")
      .def_readonly("s", &StateView::s)
      .def_readonly("t", &StateView::t)
      .def_readonly("lateral_speed", &StateView::lateral_speed, "m/s across the heading, left +")
      .def_readonly("yaw_rate", &StateView::yaw_rate, "rad/s over the last step")
      .def_readonly("odometer", &StateView::odometer, "m driven since the start")
      .def_readonly("present", &StateView::present,
                    "placed and not deleted (an absent entity keeps its last pose)")
      .def("as_dict", &state_dict, "The state as a dict.")
      .def("__repr__", [](const StateView& v) {
        return "EntityState(" + v.name + ": x=" + std::to_string(v.x) +
               ", y=" + std::to_string(v.y) + ", h=" + std::to_string(v.h) +
               ", speed=" + std::to_string(v.speed) +
               (v.road ? ", road=" + *v.road + ", lane=" + std::to_string(*v.lane) : "") + ")";
      });
}

/// Construction from the options of `corsa run`, stepping, the clock.
void bind_run(SimulationClass& c) {
  c.def(py::init([](const std::filesystem::path& path, double dt, uint64_t seed,
                    const py::object& params, const py::object& controller, const py::object& npc,
                    const py::object& external, double duration, const py::object& values,
                    const std::string& semantics) {
          SimulationSetup setup =
              simulation_setup(path, dt, seed, params, controller, npc, external, duration);
          if (semantics == "esmini") {
            setup.options.semantics = engine::Semantics::kEsmini;
          } else if (semantics != "standard") {
            throw py::value_error("semantics expects 'standard' or 'esmini', not '" + semantics +
                                  "'");
          }
          auto simulation = std::make_unique<PySimulation>(setup);
          if (!values.is_none()) {
            for (const auto& [name, value] : values.cast<py::dict>()) {
              simulation->set_value(py::str(name), py::reinterpret_borrow<py::object>(value));
            }
          }
          simulation->warn();
          return simulation;
        }),
        py::arg("path"), py::kw_only(), py::arg("dt") = 0.01, py::arg("seed") = 0,
        py::arg("params") = py::none(), py::arg("controller") = py::none(),
        py::arg("npc") = py::none(), py::arg("external") = py::none(), py::arg("duration") = 3600.0,
        py::arg("values") = py::none(), py::arg("semantics") = "standard")
      .def("step", &PySimulation::step,
           "Advances one step (triggers, actions, controllers); False once the run has ended.")
      .def(
          "run",
          [](PySimulation& self) {
            const auto start = std::chrono::steady_clock::now();
            self.run();
            const double wall =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            return summary(self, wall);
          },
          "Steps to the end and returns the run summary (the dict `corsa run --summary` writes).")
      .def(
          "summary", [](PySimulation& self) { return summary(self, 0.0); },
          "The run summary now (wall_time 0).")
      .def_property_readonly("time", [](const PySimulation& s) { return s.engine().time(); })
      .def_property_readonly("tick", [](const PySimulation& s) { return s.engine().tick(); })
      .def_property_readonly(
          "start_time",
          [](const PySimulation& s) { return s.engine().time_of(s.engine().start_tick()); },
          "Seconds the run started at: 0, or minus esmini's followGhost head start.")
      .def_property_readonly(
          "steps", [](const PySimulation& s) { return s.engine().steps(); },
          "Steps taken so far (from start_time).")
      .def_property_readonly("dt", [](const PySimulation& s) { return s.engine().dt(); })
      .def_property_readonly("seed",
                             [](const PySimulation& s) { return s.engine().options().seed; })
      .def_property_readonly("ended", [](const PySimulation& s) { return s.engine().ended(); })
      .def_property_readonly(
          "end_reason",
          [](const PySimulation& s) -> py::object {
            if (!s.engine().ended()) return py::none();
            return py::str(std::string(engine::to_string(s.engine().end_reason())));
          },
          "'stop trigger', 'stories complete' or 'duration'; None while running")
      .def_property_readonly("scenario",
                             [](const PySimulation& s) { return s.setup().scenario.string(); });
}

/// Reading the run: entities, states, storyboard, parameters, log, collisions, warnings.
void bind_reading(SimulationClass& c) {
  c.def_property_readonly("entities", &PySimulation::entity_names,
                          "Entity names in index order (the rows of states()).")
      .def(
          "state",
          [](PySimulation& self, const std::string& name) {
            return state_view(self.engine(), self.index_of(name));
          },
          py::arg("name"))
      .def("states", &states,
           "Every entity now as a numpy structured array (fields x, y, z, h, p, r, speed, "
           "acceleration, road, lane, s, t, present), rows in the order of `entities`.")
      .def(
          "element_state",
          [](const PySimulation& self, const std::string& path) -> py::object {
            const auto state = self.engine().element_state(path);
            if (!state) return py::none();
            return py::str(std::string(engine::to_string(*state)));
          },
          py::arg("path"),
          "'standbyState', 'runningState' or 'completeState' of the storyboard element with this "
          "'::' path (e.g. 'MyStory::Act1'); None for an unknown path.")
      .def(
          "elements",
          [](const PySimulation& self) {
            py::dict out;
            for (const auto& e : self.engine().elements()) {
              out[py::str(std::string(e.path))] = std::string(engine::to_string(e.state));
            }
            return out;
          },
          "Every storyboard element's '::' path -> its state, in document order ('' is the "
          "storyboard).")
      .def_property_readonly(
          "parameters", [](const PySimulation& s) { return values_of(s.engine(), false); },
          "Global parameter values now (after ParameterActions).")
      .def_property_readonly(
          "variables", [](const PySimulation& s) { return values_of(s.engine(), true); },
          "Variable values now (after VariableActions).")
      .def(
          "log", [](const PySimulation& s) { return event_log(s.engine()); },
          "The event log: every storyboard transition so far as a dict (time, tick, type, "
          "element, transition, state), as `corsa run --log` writes it.")
      .def(
          "collisions", [](const PySimulation& s) { return collisions(s.engine()); },
          "Every contact so far: dicts with time, tick and the two entities.")
      .def_property_readonly(
          "warnings",
          [](PySimulation& s) {
            py::list out;
            for (const Diagnostic& d : s.diagnostics().all()) out.append(d.format());
            return out;
          },
          "Every warning of the load and the run so far, as the command line prints them.");
}

/// Control from outside: commands, user values, custom-command handlers.
void bind_control(SimulationClass& c) {
  c.def(
       "set_speed",
       [](PySimulation& self, const std::string& name, double speed) {
         engine::ExternalCommand c;
         c.speed = speed;
         set_command(self, name, c);
       },
       py::arg("name"), py::arg("speed"),
       "Moves the entity along its lane at `speed` (m/s) over the next step, in place of its "
       "controller.")
      .def(
          "set_pose",
          [](PySimulation& self, const std::string& name, double x, double y, double h,
             std::optional<double> z, std::optional<double> p, std::optional<double> r,
             std::optional<double> speed) {
            const engine::Pose now = self.engine().state(self.index_of(name)).pose;
            engine::ExternalCommand c;
            c.pose = engine::Pose{x, y, z.value_or(now.z), h, p.value_or(now.p), r.value_or(now.r)};
            c.speed = speed;
            set_command(self, name, c);
          },
          py::arg("name"), py::arg("x"), py::arg("y"), py::arg("h"), py::kw_only(),
          py::arg("z") = py::none(), py::arg("p") = py::none(), py::arg("r") = py::none(),
          py::arg("speed") = py::none(),
          "Puts the entity at this pose (m, rad; z, p, r default to the current ones) at the end "
          "of the next step, with `speed` (m/s; default: the speed it has).")
      .def(
          "set_controls",
          [](PySimulation& self, const std::string& name, double throttle, double brake,
             double steering) {
            engine::ExternalCommand c;
            c.controls = engine::VehicleControls{throttle, brake, steering};
            set_command(self, name, c);
          },
          py::arg("name"), py::arg("throttle") = 0.0, py::arg("brake") = 0.0,
          py::arg("steering") = 0.0,
          "Drives the entity's vehicle model over the next step: throttle and brake 0..1 (shares "
          "of maxAcceleration and maxDeceleration), steering the front wheel angle in rad (left "
          "+).")
      .def(
          "is_external",
          [](const PySimulation& self, const std::string& name) {
            return self.engine().external(self.index_of(name));
          },
          py::arg("name"), "Whether the entity moves only by set_speed/set_pose/set_controls.")
      .def("set_value", &PySimulation::set_value, py::arg("name"), py::arg("value"),
           "The value of UserDefinedValueConditions named `name`: a bool, int, float or str, or "
           "a callable returning one (None: no value, the condition does not hold).")
      .def("on_command", &PySimulation::on_command, py::arg("type"), py::arg("handler"),
           "Calls handler(text) for every CustomCommandAction of this type, with its text.");
}

}  // namespace

void bind_simulation(py::module_& m) {
  bind_entity_state(m);
  SimulationClass c(m, "Simulation", "One run of one scenario (see docs/python.md).");
  bind_run(c);
  bind_reading(c);
  bind_control(c);
  c.def("__repr__", [](PySimulation& self) {
    return "<corsa.Simulation " + self.setup().scenario.string() +
           " t=" + std::to_string(self.engine().time()) + " s" +
           (self.engine().ended()
                ? ", ended by " + std::string(engine::to_string(self.engine().end_reason()))
                : std::string()) +
           ">";
  });
}

}  // namespace corsa::python
