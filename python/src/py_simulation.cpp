#include "py_simulation.h"

#include <stdexcept>

#include "corsa/engine/run.h"
#include "corsa/xodr/map.h"
#include "corsa/xosc/scenario.h"
#include "errors.h"
#include "values.h"

namespace corsa::python {
namespace py = pybind11;
namespace {

// A road id as numpy's UCS-4 text (states()["road"]): UTF-8 decoded, a broken byte kept as
// U+FFFD.
std::u32string ucs4(const std::string& text) {
  std::u32string out;
  for (size_t i = 0; i < text.size();) {
    const auto byte = static_cast<unsigned char>(text[i]);
    const int extra = byte < 0x80 ? 0 : byte >= 0xF0 ? 3 : byte >= 0xE0 ? 2 : byte >= 0xC0 ? 1 : -1;
    if (extra < 0 || i + static_cast<size_t>(extra) >= text.size()) {
      out.push_back(U'\uFFFD');
      ++i;
      continue;
    }
    char32_t code = extra == 0 ? byte : byte & (0x3F >> extra);
    for (int k = 1; k <= extra; ++k) {
      code = (code << 6) | (static_cast<unsigned char>(text[i + static_cast<size_t>(k)]) & 0x3F);
    }
    out.push_back(code);
    i += static_cast<size_t>(extra) + 1;
  }
  return out;
}

}  // namespace

PySimulation::PySimulation(const SimulationSetup& setup) : setup_(setup) {
  {
    py::gil_scoped_release nogil;
    xosc::LoadOptions load;
    load.parameters = setup_.parameters;
    load.esmini_booleans = setup_.options.semantics == engine::Semantics::kEsmini;
    scenario_ =
        std::make_unique<xosc::Scenario>(xosc::load_scenario(setup_.scenario, load, diagnostics_));
    simulation_ = std::make_unique<engine::Simulation>(
        *scenario_, engine::load_road_network(*scenario_, diagnostics_), setup_.options,
        diagnostics_);
  }
  simulation_->set_user_value_provider([this](std::string_view name) -> std::optional<xosc::Value> {
    py::gil_scoped_acquire gil;
    const py::str key(name.data(), name.size());
    if (!values_.contains(key)) {
      return std::nullopt;
    }
    py::object value = values_[key];
    if (PyCallable_Check(value.ptr())) {
      value = value();
    }
    return from_python(value, "the value of UserDefinedValueCondition '" + std::string(name) + "'");
  });
}

PySimulation::~PySimulation() = default;

void PySimulation::check_usable() const {
  if (!failure_.empty()) {
    throw std::runtime_error("the simulation stopped at an error and cannot go on (" + failure_ +
                             "); start a new corsa.Simulation");
  }
}

void PySimulation::fail(const std::exception& error) {
  failure_ = "at t=" + std::to_string(simulation_->time()) + " s: " + error.what();
}

bool PySimulation::step() {
  check_usable();
  const Busy busy(*this);
  bool more = false;
  try {
    py::gil_scoped_release nogil;
    more = simulation_->step();
  } catch (const std::exception& error) {
    fail(error);
    throw;
  }
  warn();
  return more;
}

void PySimulation::run() {
  check_usable();
  const Busy busy(*this);
  // Steps in batches with the GIL released; between batches Python may handle a signal.
  constexpr int kBatch = 256;
  bool more = true;
  while (more) {
    try {
      py::gil_scoped_release nogil;
      for (int i = 0; i < kBatch && more; ++i) {
        more = simulation_->step();
      }
    } catch (const std::exception& error) {
      fail(error);
      throw;
    }
    warn();
    if (PyErr_CheckSignals() != 0) {
      throw py::error_already_set();
    }
  }
}

void PySimulation::warn() { warned_ = warn_new(diagnostics_, warned_); }

size_t PySimulation::index_of(const std::string& name) const {
  check_thread();
  if (const auto index = simulation_->find_entity(name)) {
    return *index;
  }
  std::string names;
  for (size_t i = 0; i < simulation_->entity_count() && i < 20; ++i) {
    names += (i ? ", " : "") + simulation_->entity(i).name;
  }
  if (simulation_->entity_count() > 20) {
    names += ", ...";
  }
  throw py::value_error("the scenario has no entity '" + name + "' (entities: " + names + ")");
}

void PySimulation::set_value(const std::string& name, py::object value) {
  if (!PyCallable_Check(value.ptr())) {
    from_python(value, "the value of '" + name + "'");  // refused now rather than mid-run
  }
  values_[py::str(name)] = std::move(value);
}

void PySimulation::on_command(const std::string& type, py::object handler) {
  check_thread();
  if (!PyCallable_Check(handler.ptr())) {
    throw py::type_error("the handler of CustomCommandAction type '" + type + "' must be callable");
  }
  handlers_[py::str(type)] = std::move(handler);
  simulation_->set_custom_command_handler(
      type, [this, type](const xosc::UserDefinedAction& action, const engine::Simulation&) {
        py::gil_scoped_acquire gil;
        handlers_[py::str(type)](action.content);
      });
}

py::tuple PySimulation::entity_names() {
  check_thread();
  const size_t count = simulation_->entity_count();
  if (names_count_ != count || !names_) {
    py::tuple names(count);
    for (size_t i = 0; i < count; ++i) {
      names[i] = py::str(simulation_->entity(i).name);
    }
    names_ = std::move(names);
    names_count_ = count;
  }
  return names_;
}

const py::object& PySimulation::states_dtype() {
  if (dtype_) {
    return dtype_;
  }
  if (const xodr::Map* map = simulation_->map()) {
    road_text_.reserve(map->road_count());
    for (size_t i = 0; i < map->road_count(); ++i) {
      road_text_.push_back(ucs4(map->road(i).id));
      road_width_ = std::max(road_width_, road_text_.back().size());
    }
  }
  py::list names, formats, offsets;
  const auto field = [&](const char* name, const std::string& format, size_t offset) {
    names.append(name);
    formats.append(format);
    offsets.append(offset);
  };
  // The fields in the order of state(); in memory the doubles first, then the lane and the flag,
  // the road text last, so that every field is aligned.
  const char* motion[] = {"x", "y", "z", "h", "p", "r", "speed", "acceleration"};
  for (size_t i = 0; i < 8; ++i) {
    field(motion[i], "<f8", kStateOffsets.motion + 8 * i);
  }
  field("road", "<U" + std::to_string(road_width_), kStateOffsets.road);
  field("lane", "<i4", kStateOffsets.lane);
  field("s", "<f8", kStateOffsets.s);
  field("t", "<f8", kStateOffsets.t);
  field("present", "?", kStateOffsets.present);
  py::dict spec;
  spec["names"] = names;
  spec["formats"] = formats;
  spec["offsets"] = offsets;
  spec["itemsize"] = states_itemsize();
  dtype_ = py::module_::import("numpy").attr("dtype")(spec);
  return dtype_;
}

}  // namespace corsa::python
