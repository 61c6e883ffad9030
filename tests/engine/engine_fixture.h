#pragma once

// Runs the focused scenarios of tests/engine/fixtures and answers questions about the run: when
// an element took a transition, where an entity was at some time.

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "corsa/engine/run.h"
#include "corsa/engine/simulation.h"
#include "corsa/geo/crs_transform.h"
#include "corsa/xodr/map.h"
#include "corsa/xosc/scenario.h"

namespace Catch {
/// Optional times print as their value (or "none") in failed checks.
template <>
struct StringMaker<std::optional<double>> {
  static std::string convert(const std::optional<double>& value) {
    return value ? StringMaker<double>::convert(*value) : std::string("none");
  }
};
}  // namespace Catch

namespace corsa::test {

inline std::filesystem::path engine_fixture(const std::string& name) {
  return std::filesystem::path(CORSA_SOURCE_DIR) / "tests/engine/fixtures" / name;
}

/// An ASAM OpenSCENARIO 1.3 example of the shared conformance set.
inline std::filesystem::path asam(const std::string& name) {
  return std::filesystem::path(CORSA_SHARED_DIR) / "conformance/asam-osc-1.3" / name;
}

/// Default options with a longer duration cap (s).
inline engine::SimulationOptions with_duration(double duration) {
  engine::SimulationOptions options;
  options.duration = duration;
  return options;
}

/// Every diagnostic as `file:line: severity: message`, one a line.
inline std::string all_text(const Diagnostics& diagnostics) {
  std::ostringstream out;
  for (const Diagnostic& d : diagnostics.all()) {
    out << d << "\n";
  }
  return out.str();
}

/// The state of every entity at every tick of a run.
class TraceRecorder final : public engine::SimulationObserver {
 public:
  void on_step(const engine::Simulation& sim) override {
    std::vector<engine::EntityState> states;
    for (size_t i = 0; i < sim.entity_count(); ++i) {
      states.push_back(sim.state(i));
    }
    ticks_[sim.tick()] = std::move(states);
  }
  /// The state of entity `index` at `tick` (fails the test when it was not recorded).
  const engine::EntityState& at(int64_t tick, size_t index) const {
    const auto it = ticks_.find(tick);
    REQUIRE(it != ticks_.end());
    return it->second.at(index);
  }
  const std::map<int64_t, std::vector<engine::EntityState>>& ticks() const { return ticks_; }

 private:
  std::map<int64_t, std::vector<engine::EntityState>> ticks_;
};

class FixtureRun {
 public:
  explicit FixtureRun(const std::filesystem::path& file, engine::SimulationOptions options = {},
                      std::vector<std::pair<std::string, std::string>> parameters = {}) {
    if (!options.geo_projection) {
      options.geo_projection = geo::geographic_to_projected;  // PROJ, for GeoPositions
    }
    xosc::LoadOptions load;
    load.parameters = std::move(parameters);
    scenario_ = std::make_unique<xosc::Scenario>(xosc::load_scenario(file, load, diagnostics_));
    sim_ = std::make_unique<engine::Simulation>(
        *scenario_, engine::load_road_network(*scenario_, diagnostics_), options, diagnostics_);
    sim_->add_observer(trace_);
  }

  engine::Simulation& sim() { return *sim_; }
  const TraceRecorder& trace() const { return trace_; }
  Diagnostics& diagnostics() { return diagnostics_; }
  FixtureRun& run() {
    sim_->run();
    return *this;
  }

  size_t entity(const std::string& name) const {
    const auto index = sim_->find_entity(name);
    REQUIRE(index);
    return *index;
  }
  /// State of an entity at a time (s) of the run.
  const engine::EntityState& at(double time, const std::string& name) const {
    return trace_.at(std::llround(time / sim_->dt()), entity(name));
  }
  const engine::EntityState& now(const std::string& name) const {
    return sim_->state(entity(name));
  }

  /// Time of the first `transition` of the element whose path ends with `suffix`.
  std::optional<double> first(const std::string& suffix, engine::TransitionKind transition) const {
    for (const auto& record : sim_->transitions()) {
      if (record.transition == transition && ends_with(record.path, suffix)) {
        return record.time;
      }
    }
    return std::nullopt;
  }
  /// Number of `transition`s of the element whose path ends with `suffix`.
  size_t count(const std::string& suffix, engine::TransitionKind transition) const {
    size_t n = 0;
    for (const auto& record : sim_->transitions()) {
      n += record.transition == transition && ends_with(record.path, suffix) ? 1 : 0;
    }
    return n;
  }
  std::optional<engine::ElementState> state_of(const std::string& suffix) const {
    std::optional<engine::ElementState> state;
    for (const auto& record : sim_->transitions()) {
      if (ends_with(record.path, suffix)) {
        state = record.state;
      }
    }
    return state;
  }

 private:
  static bool ends_with(const std::string& path, const std::string& suffix) {
    return path.size() >= suffix.size() &&
           path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0 &&
           (path.size() == suffix.size() || path[path.size() - suffix.size() - 1] == ':');
  }

  Diagnostics diagnostics_;
  std::unique_ptr<xosc::Scenario> scenario_;
  std::unique_ptr<engine::Simulation> sim_;
  TraceRecorder trace_;
};

}  // namespace corsa::test
