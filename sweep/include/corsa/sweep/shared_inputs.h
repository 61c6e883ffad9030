#pragma once

// What the variants of a sweep share, read-only: the scenario's text (read once), its catalog
// files (parsed once) and its road networks (each loaded once, on first use). Loading a variant
// then only parses the scenario document with the variant's parameter values, which is what
// changes between variants. Thread-safe: the variants run on several threads.

#include <filesystem>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "corsa/core/diagnostic.h"
#include "corsa/sweep/variant_plan.h"
#include "corsa/xosc/catalog_cache.h"

namespace corsa::xodr {
class Map;
}
namespace corsa::xosc {
struct Scenario;
}

namespace corsa::sweep {

class SharedInputs {
 public:
  /// Reads the scenario file (InputError when it cannot be read). Maps and catalogs load later,
  /// when the first variant needs them; their warnings go to `diagnostics`, once.
  SharedInputs(std::filesystem::path scenario, Diagnostics& diagnostics);
  SharedInputs(const SharedInputs&) = delete;
  SharedInputs& operator=(const SharedInputs&) = delete;
  ~SharedInputs();

  const std::filesystem::path& scenario_path() const { return scenario_path_; }
  const std::string& scenario_text() const { return scenario_text_; }

  /// The scenario with `parameters` overriding its global parameter values (xosc::LoadOptions),
  /// parsed from the shared text with the shared catalogs; `strict` refuses lenient readings,
  /// `esmini_booleans` reads capitalised booleans as esmini (xosc::LoadOptions). Throws
  /// InputError.
  xosc::Scenario load(const ParameterValues& parameters, Diagnostics& diagnostics,
                      bool strict = false, bool esmini_booleans = false) const;

  /// The scenario's road network (null when it has none), loaded once per LogicFile path and
  /// then shared; a map that failed to load fails every variant that uses it, with the same
  /// located error.
  std::shared_ptr<const xodr::Map> road_network(const xosc::Scenario& scenario);

  /// How many maps were actually loaded (for tests: 1 for a whole sweep over one map).
  size_t maps_loaded() const;
  /// How many catalog files were parsed (each once, whatever the number of variants).
  size_t catalog_files() const { return catalogs_->file_count(); }

 private:
  std::filesystem::path scenario_path_;
  std::string scenario_text_;
  Diagnostics& diagnostics_;
  std::shared_ptr<xosc::CatalogCache> catalogs_;
  mutable std::mutex mutex_;
  std::map<std::filesystem::path, std::shared_future<std::shared_ptr<const xodr::Map>>> maps_;
};

}  // namespace corsa::sweep
