#include "corsa/sweep/variant_plan.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>

#include "corsa/core/strings.h"
#include "corsa/xosc/scenario.h"

namespace corsa::sweep {
namespace {

size_t checked_product(size_t a, size_t b, const Diagnostic& where) {
  if (b != 0 && a > std::numeric_limits<size_t>::max() / b) {
    Diagnostic d = where;
    d.message = "the sweep has too many variants";
    throw InputError(d);
  }
  return a * b;
}

Diagnostic grid_error(const GridAxis& axis, std::string message) {
  return make_error("--param " + axis.spec, 0, std::move(message));
}

std::string type_name(xosc::ParameterType type) { return std::string(xosc::to_string(type)); }

// The declared parameter `name`, or a located error saying the scenario has none.
const xosc::ParameterDeclaration& declared(const xosc::Scenario& scenario, const std::string& name,
                                           Diagnostic where) {
  const xosc::ParameterDeclaration* p = scenario.find_parameter(name);
  if (p == nullptr) {
    where.message = "parameter '" + name + "' is not declared in scenario '" +
                    scenario.path.string() + "' (its ParameterDeclarations)";
    throw InputError(where);
  }
  return *p;
}

void check_value(const xosc::ParameterDeclaration& p, const std::string& value, Diagnostic where) {
  if (!xosc::parse_value(p.type, value)) {
    where.message = "value '" + value + "' is not a valid " + type_name(p.type) +
                    " for parameter '" + p.name + "'";
    throw InputError(where);
  }
}

// The checks of one check() call: which distribution parameters the scenario lacks.
struct Unused {
  bool strict;
  Diagnostics& diagnostics;
  std::vector<std::string> names;

  // Whether `name` is declared; if not, warned about (once) and remembered, or an error.
  bool declared(const xosc::Scenario& scenario, const std::string& name, const xosc::Source& at) {
    if (scenario.find_parameter(name) != nullptr) return true;
    const std::string message = "parameter '" + name + "' is not declared in scenario '" +
                                scenario.path.string() + "' (its ParameterDeclarations)";
    if (strict) {
      throw InputError(at.error(message + " (an error under --strict; otherwise read as not "
                                          "varied)"));
    }
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      names.push_back(name);
      diagnostics.add(at.warning(message + " (read as not varied: its values are left out)"));
    }
    return false;
  }
};

void check_single(const xosc::Scenario& scenario,
                  const xosc::DeterministicSingleParameterDistribution& single, Unused& unused) {
  if (!unused.declared(scenario, single.parameter_name, single.source)) return;
  const auto& p = declared(scenario, single.parameter_name, single.source.error(""));
  if (const auto* set = std::get_if<xosc::DistributionSet>(&single.distribution)) {
    for (const auto& value : set->values) check_value(p, value, set->source.error(""));
    return;
  }
  if (const auto* range = std::get_if<xosc::DistributionRange>(&single.distribution)) {
    // First, second and last value: enough to catch a fractional start or step for an integer
    // parameter and an end beyond an unsignedShort.
    const double low = range->range.lower_limit;
    const double span = range->range.upper_limit - low;
    const double last = std::floor(span / range->step_width + 1e-9);
    for (const double k : {0.0, std::min(1.0, last), last}) {
      check_value(p, format_double(low + k * range->step_width + 0.0), range->source.error(""));
    }
  }
}

bool integer_type(xosc::ParameterType type) {
  return type == xosc::ParameterType::kInt || type == xosc::ParameterType::kUnsignedInt ||
         type == xosc::ParameterType::kUnsignedShort;
}

void check_stochastic(const xosc::Scenario& scenario, const xosc::StochasticDistribution& d,
                      Unused& unused) {
  if (!unused.declared(scenario, d.parameter_name, d.source)) return;
  const auto& p = declared(scenario, d.parameter_name, d.source.error(""));
  if (const auto* set = std::get_if<xosc::ProbabilityDistributionSet>(&d.distribution)) {
    for (const auto& element : set->elements) check_value(p, element.value, set->source.error(""));
    return;
  }
  if (std::holds_alternative<xosc::UserDefinedDistribution>(d.distribution)) {
    return;  // variant_at reports it, located
  }
  const bool draws_integers = std::holds_alternative<xosc::PoissonDistribution>(d.distribution);
  const bool fits = p.type == xosc::ParameterType::kDouble ||
                    p.type == xosc::ParameterType::kString ||
                    (draws_integers && integer_type(p.type));
  if (!fits) {
    Diagnostic where = d.source.error("");
    where.message = std::string(draws_integers ? "PoissonDistribution draws integers"
                                               : "this distribution draws real numbers") +
                    ", which do not suit parameter '" + p.name + "' of type " + type_name(p.type);
    throw InputError(where);
  }
}

}  // namespace

void refuse_distribution_without_variants(const xosc::ParameterValueDistribution& distribution) {
  if (xosc::variant_count(distribution) != 0) {
    return;
  }
  if (const auto* stochastic = std::get_if<xosc::Stochastic>(&distribution.definition)) {
    throw InputError(
        stochastic->source.error("numberOfTestRuns is 0: the distribution has no variants"));
  }
  throw InputError(distribution.source.error("the distribution has no variants"));
}

VariantPlan VariantPlan::from_distribution(std::filesystem::path distribution_file,
                                           xosc::ParameterValueDistribution distribution,
                                           std::vector<GridAxis> grid, uint64_t default_seed) {
  VariantPlan plan;
  plan.source_ = std::move(distribution_file);
  plan.scenario_ = distribution.scenario_path;
  plan.default_seed_ = default_seed;
  refuse_distribution_without_variants(distribution);
  plan.distribution_size_ = xosc::variant_count(distribution);
  if (const auto* stochastic = std::get_if<xosc::Stochastic>(&distribution.definition)) {
    for (const auto& d : stochastic->distributions)
      plan.add_name(d.parameter_name, d.source.error(""));
  } else {
    for (const auto& entry : std::get<xosc::Deterministic>(distribution.definition).entries) {
      if (const auto* single =
              std::get_if<xosc::DeterministicSingleParameterDistribution>(&entry)) {
        plan.add_name(single->parameter_name, single->source.error(""));
        continue;
      }
      const auto& multi = std::get<xosc::DeterministicMultiParameterDistribution>(entry);
      // Every value set should assign the same parameters; the columns are their union, and a
      // parameter of another entry may not appear here.
      const size_t before = plan.names_.size();
      for (const auto& set : multi.value_sets) {
        std::vector<std::string> in_set;
        for (const auto& a : set) {
          if (std::find(in_set.begin(), in_set.end(), a.parameter_ref) != in_set.end()) {
            throw InputError(a.source.error("parameter '" + a.parameter_ref +
                                            "' is assigned twice in one ParameterValueSet"));
          }
          in_set.push_back(a.parameter_ref);
          const auto known = std::find(plan.names_.begin(), plan.names_.end(), a.parameter_ref);
          if (known == plan.names_.end()) {
            plan.add_name(a.parameter_ref, a.source.error(""));
          } else if (static_cast<size_t>(known - plan.names_.begin()) < before) {
            plan.add_name(a.parameter_ref, a.source.error(""));  // reports the duplicate
          }
        }
      }
    }
  }
  plan.distribution_ = std::move(distribution);
  plan.add_grid(std::move(grid));
  return plan;
}

VariantPlan VariantPlan::from_scenario(std::filesystem::path scenario, std::vector<GridAxis> grid) {
  VariantPlan plan;
  plan.source_ = scenario;
  plan.scenario_ = std::move(scenario);
  plan.add_grid(std::move(grid));
  return plan;
}

VariantPlan VariantPlan::from_file(const std::filesystem::path& file, std::vector<GridAxis> grid,
                                   uint64_t default_seed, Diagnostics& diagnostics, bool strict) {
  xosc::LoadOptions load;
  load.strict = strict;
  xosc::Document document = xosc::load_document(file, load, diagnostics);
  if (auto* distribution = std::get_if<xosc::ParameterValueDistribution>(&document)) {
    return from_distribution(file, std::move(*distribution), std::move(grid), default_seed);
  }
  if (std::holds_alternative<xosc::Catalog>(document)) {
    throw InputError(make_error(file.string(), 0,
                                "this is a catalog; sweep a scenario or a parameter distribution"));
  }
  return from_scenario(file, std::move(grid));
}

void VariantPlan::add_name(const std::string& name, const Diagnostic& where) {
  if (std::find(names_.begin(), names_.end(), name) != names_.end()) {
    Diagnostic d = where;
    d.message = "parameter '" + name + "' is varied twice in this sweep";
    throw InputError(d);
  }
  names_.push_back(name);
}

void VariantPlan::add_grid(std::vector<GridAxis> grid) {
  grid_ = std::move(grid);
  grid_size_ = 1;
  for (const auto& axis : grid_) {
    add_name(axis.name, grid_error(axis, ""));
    grid_size_ = checked_product(grid_size_, axis.values.size(), grid_error(axis, ""));
  }
  const Diagnostic where =
      grid_.empty() ? make_error(source_.string(), 0, "") : grid_error(grid_.back(), "");
  size_ = checked_product(distribution_size_, grid_size_, where);
}

ParameterValues VariantPlan::variant(size_t index) const {
  ParameterValues values;
  if (distribution_) {
    xosc::VariantOptions options;
    options.default_seed = default_seed_;
    values = xosc::variant_at(*distribution_, index / grid_size_, options).values;
  }
  size_t rest = index % grid_size_;
  std::vector<size_t> digits(grid_.size(), 0);
  // Row-major: the last axis varies fastest.
  for (size_t i = grid_.size(); i-- > 0;) {
    digits[i] = rest % grid_[i].values.size();
    rest /= grid_[i].values.size();
  }
  for (size_t i = 0; i < grid_.size(); ++i) {
    values.emplace_back(grid_[i].name, grid_[i].values[digits[i]]);
  }
  return values;
}

std::vector<std::string> VariantPlan::check(const xosc::Scenario& scenario, bool strict,
                                            Diagnostics& diagnostics) const {
  Unused unused{strict, diagnostics, {}};
  if (distribution_) {
    if (const auto* stochastic = std::get_if<xosc::Stochastic>(&distribution_->definition)) {
      for (const auto& d : stochastic->distributions) check_stochastic(scenario, d, unused);
    } else {
      for (const auto& entry : std::get<xosc::Deterministic>(distribution_->definition).entries) {
        if (const auto* single =
                std::get_if<xosc::DeterministicSingleParameterDistribution>(&entry)) {
          check_single(scenario, *single, unused);
          continue;
        }
        for (const auto& set :
             std::get<xosc::DeterministicMultiParameterDistribution>(entry).value_sets) {
          for (const auto& a : set) {
            if (!unused.declared(scenario, a.parameter_ref, a.source)) continue;
            check_value(declared(scenario, a.parameter_ref, a.source.error("")), a.value,
                        a.source.error(""));
          }
        }
      }
    }
  }
  for (const auto& axis : grid_) {
    const auto& p = declared(scenario, axis.name, grid_error(axis, ""));
    for (const auto& value : axis.values) check_value(p, value, grid_error(axis, ""));
  }
  return unused.names;
}

}  // namespace corsa::sweep
