#pragma once

// corsa.Simulation: one engine::Simulation with the scenario it runs, its warnings and what
// Python hands it (value providers, custom command handlers). The sensor extension (_sensors)
// reaches the engine simulation through this class, so both extensions compile this header.

#include <pybind11/pybind11.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/engine/simulation.h"

namespace corsa::xosc {
struct Scenario;
}

namespace corsa::python {

/// What `corsa.Simulation(...)` is given, checked.
/// Byte offsets of the fields of a states() record (PySimulation::states_dtype).
struct StateOffsets {
  size_t motion = 0;  ///< x, y, z, h, p, r, speed, acceleration: 8 doubles
  size_t s = 64;
  size_t t = 72;
  size_t lane = 80;
  size_t present = 84;
  size_t road = 88;  ///< UCS-4 text, PySimulation::road_width() characters
};
inline constexpr StateOffsets kStateOffsets{};

struct SimulationSetup {
  std::filesystem::path scenario;
  std::vector<std::pair<std::string, std::string>> parameters;  ///< global parameter values
  engine::SimulationOptions options;
};

class PySimulation {
 public:
  /// Loads the scenario and its map and builds the simulation (Init performed), with the GIL
  /// released while it loads. Throws InputError for bad input.
  explicit PySimulation(const SimulationSetup& setup);
  ~PySimulation();
  PySimulation(const PySimulation&) = delete;
  PySimulation& operator=(const PySimulation&) = delete;

  // Everything the _sensors extension calls is inline here: the class's other members are
  // compiled into _corsa only.

  /// The engine simulation. From another thread while one steps it (the GIL is released then):
  /// RuntimeError rather than a data race.
  engine::Simulation& engine() {
    check_thread();
    return *simulation_;
  }
  const engine::Simulation& engine() const {
    check_thread();
    return *simulation_;
  }

  /// Marks the simulation busy for the GIL-released work on it (step, run, capture) of the
  /// calling thread: callbacks on that thread may use it, other threads get RuntimeError, and
  /// a second step from a callback is refused. Construct and destroy with the GIL held.
  class Busy {
   public:
    explicit Busy(PySimulation& owner) : owner_(owner) {
      if (owner_.busy_) {
        throw std::runtime_error(
            owner_.busy_thread_ == std::this_thread::get_id()
                ? "this corsa.Simulation is already stepping (step, run or capture called from a "
                  "callback of its own step)"
                : "this corsa.Simulation is busy in another thread (step, run or capture)");
      }
      owner_.busy_ = true;
      owner_.busy_thread_ = std::this_thread::get_id();
    }
    ~Busy() { owner_.busy_ = false; }
    Busy(const Busy&) = delete;
    Busy& operator=(const Busy&) = delete;

   private:
    PySimulation& owner_;
  };
  const xosc::Scenario& scenario() const { return *scenario_; }
  Diagnostics& diagnostics() { return diagnostics_; }
  const SimulationSetup& setup() const { return setup_; }

  /// One step with the GIL released; false once the run has ended. A Python exception raised by
  /// a callback (value, command handler) or an error of the engine propagates, and the
  /// simulation refuses further steps (its state may be half-way through a step).
  bool step();
  /// Steps to the end (GIL released; Ctrl-C is noticed every few hundred steps and raises
  /// KeyboardInterrupt between steps).
  void run();
  /// Issues the warnings added since the last call as Python warnings (needs the GIL).
  void warn();

  /// The entity index of `name`; ValueError naming the entities when there is none.
  size_t index_of(const std::string& name) const;

  /// UserDefinedValueCondition values: `name` -> a bool, int, float or str, or a callable
  /// returning one (or None for "no value").
  void set_value(const std::string& name, pybind11::object value);
  /// CustomCommandAction handler of `type`: called with the action's text content.
  void on_command(const std::string& type, pybind11::object handler);

  /// The entity names in index order (a tuple, rebuilt when traffic added entities).
  pybind11::tuple entity_names();
  /// The numpy dtype of states() and each road's id as UCS-4 text (built on first use).
  const pybind11::object& states_dtype();
  const std::u32string& road_text(uint32_t road) const { return road_text_[road]; }
  size_t road_width() const { return road_width_; }
  /// Bytes per states() record: the road text after the fixed fields, rounded up to 8.
  size_t states_itemsize() const { return (kStateOffsets.road + 4 * road_width_ + 7) / 8 * 8; }

 private:
  void check_usable() const;
  void fail(const std::exception& error);
  void check_thread() const {
    if (busy_ && std::this_thread::get_id() != busy_thread_) {
      throw std::runtime_error(
          "this corsa.Simulation is busy in another thread (step, run or capture); use one "
          "simulation from one thread at a time");
    }
  }

  bool busy_ = false;
  std::thread::id busy_thread_;

  SimulationSetup setup_;
  Diagnostics diagnostics_;
  std::unique_ptr<xosc::Scenario> scenario_;
  std::unique_ptr<engine::Simulation> simulation_;
  size_t warned_ = 0;
  std::string failure_;  ///< why the run cannot go on, "" while it can
  pybind11::dict values_;
  pybind11::dict handlers_;
  pybind11::tuple names_;
  size_t names_count_ = 0;
  pybind11::object dtype_;
  std::vector<std::u32string> road_text_;
  size_t road_width_ = 1;
};

}  // namespace corsa::python
