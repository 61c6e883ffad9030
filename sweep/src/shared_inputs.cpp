#include "corsa/sweep/shared_inputs.h"

#include "corsa/core/atomic_file.h"
#include "corsa/engine/run.h"
#include "corsa/xodr/map.h"
#include "corsa/xosc/scenario.h"

namespace corsa::sweep {

SharedInputs::SharedInputs(std::filesystem::path scenario, Diagnostics& diagnostics)
    : scenario_path_(std::move(scenario)),
      scenario_text_(read_file(scenario_path_)),
      diagnostics_(diagnostics),
      catalogs_(std::make_shared<xosc::CatalogCache>()) {}

SharedInputs::~SharedInputs() = default;

xosc::Scenario SharedInputs::load(const ParameterValues& parameters, Diagnostics& diagnostics,
                                  bool strict, bool esmini_booleans) const {
  xosc::LoadOptions options;
  options.parameters = parameters;
  options.strict = strict;
  options.esmini_booleans = esmini_booleans;
  options.catalog_cache = catalogs_;
  return xosc::parse_scenario(scenario_text_, scenario_path_, options, diagnostics);
}

std::shared_ptr<const xodr::Map> SharedInputs::road_network(const xosc::Scenario& scenario) {
  const xosc::RoadNetwork& network = scenario.road_network;
  if (!network.logic_file || network.logic_file_path.empty()) {
    return nullptr;
  }
  std::shared_future<std::shared_ptr<const xodr::Map>> future;
  std::promise<std::shared_ptr<const xodr::Map>> promise;
  bool load_here = false;
  {
    std::lock_guard lock(mutex_);
    const auto found = maps_.find(network.logic_file_path);
    if (found != maps_.end()) {
      future = found->second;
    } else {
      future = promise.get_future().share();
      maps_.emplace(network.logic_file_path, future);
      load_here = true;
    }
  }
  if (load_here) {
    // Loaded outside the lock: other threads needing this map wait on the future, threads
    // needing another map do not wait at all.
    try {
      promise.set_value(engine::load_road_network(scenario, diagnostics_));
    } catch (...) {
      promise.set_exception(std::current_exception());
    }
  }
  return future.get();
}

size_t SharedInputs::maps_loaded() const {
  std::lock_guard lock(mutex_);
  return maps_.size();
}

}  // namespace corsa::sweep
