#pragma once

// What a sweep runs: one scenario and the parameter values of each of its variants, numbered
// 0..size()-1. A variant is computed from its index alone, so any shard can take any subset.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/sweep/grid.h"
#include "corsa/xosc/distributions.h"

namespace corsa::xosc {
struct Scenario;
}

namespace corsa::sweep {

/// Parameter name -> value text, in column order.
using ParameterValues = std::vector<std::pair<std::string, std::string>>;

/// Throws InputError, located at the distribution (its Stochastic element for
/// numberOfTestRuns="0"), when `distribution` has no variants: neither a sweep nor a run has
/// one to take.
void refuse_distribution_without_variants(const xosc::ParameterValueDistribution& distribution);

class VariantPlan {
 public:
  /// The variants of a ParameterValueDistribution document (§10), each combined with every
  /// point of `grid` (the grid varies fastest). `default_seed` seeds a Stochastic distribution
  /// without a randomSeed. Throws InputError for a parameter varied twice or no variants at all.
  static VariantPlan from_distribution(std::filesystem::path distribution_file,
                                       xosc::ParameterValueDistribution distribution,
                                       std::vector<GridAxis> grid, uint64_t default_seed = 0);
  /// A grid over a scenario file's parameters: the axes combine as nested loops in order, the
  /// first varying slowest (row-major, like Deterministic entries). No axes: one variant.
  static VariantPlan from_scenario(std::filesystem::path scenario, std::vector<GridAxis> grid);
  /// What `corsa sweep FILE` sweeps: the distribution's variants when `file` is a
  /// ParameterValueDistribution, else the grid over the scenario `file`. Throws InputError for a
  /// file that cannot be read or is a catalog. `strict`: its lenient readings are errors
  /// (xosc::LoadOptions::strict, `corsa sweep --strict`).
  static VariantPlan from_file(const std::filesystem::path& file, std::vector<GridAxis> grid,
                               uint64_t default_seed, Diagnostics& diagnostics,
                               bool strict = false);

  /// The scenario every variant runs.
  const std::filesystem::path& scenario() const { return scenario_; }
  /// The file the plan came from (the distribution, or the scenario).
  const std::filesystem::path& source() const { return source_; }
  size_t size() const { return size_; }
  /// Every parameter some variant sets, in column order (distribution first, then the grid).
  const std::vector<std::string>& parameter_names() const { return names_; }
  const std::vector<GridAxis>& grid() const { return grid_; }
  uint64_t default_seed() const { return default_seed_; }
  const std::optional<xosc::ParameterValueDistribution>& distribution() const {
    return distribution_;
  }

  /// The values of variant `index` (< size()).
  ParameterValues variant(size_t index) const;

  /// Checks the plan against the scenario as loaded with its default values: every varied
  /// parameter must be a declared global parameter, and every value the plan can give (the sets,
  /// value sets, range ends and steps, grid values; the kind of each stochastic distribution)
  /// must suit the parameter's type. Throws InputError located at the distribution element or the
  /// --param option. A distribution parameter the scenario does not declare (ASAM's ALKS
  /// variation files vary a model their scenario does not have) is not varied, with a located
  /// `(read as ...)` warning in `diagnostics`, or an error when `strict`; those names are
  /// returned, to be left out of every variant's values.
  std::vector<std::string> check(const xosc::Scenario& scenario, bool strict,
                                 Diagnostics& diagnostics) const;

 private:
  VariantPlan() = default;
  void add_name(const std::string& name, const Diagnostic& where);
  void add_grid(std::vector<GridAxis> grid);

  std::filesystem::path source_;
  std::filesystem::path scenario_;
  std::optional<xosc::ParameterValueDistribution> distribution_;
  size_t distribution_size_ = 1;
  std::vector<GridAxis> grid_;
  size_t grid_size_ = 1;
  size_t size_ = 1;
  uint64_t default_seed_ = 0;
  std::vector<std::string> names_;
};

}  // namespace corsa::sweep
