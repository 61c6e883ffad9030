// ParameterValueDistribution documents (§10.2-10.4).

#include <cmath>
#include <string>

#include "corsa/core/strings.h"
#include "parsers.h"
#include "random_seed.h"

namespace corsa::xosc {
namespace {

UserDefinedDistribution parse_user_defined(ParseContext& ctx, const Element* e) {
  Children(ctx, e, "UserDefinedDistribution");
  ctx.warn_once(e, "user-defined-distribution",
                "UserDefinedDistribution cannot be enumerated by Corsa");
  return UserDefinedDistribution{ctx.req_str(e, "type"), element_text(e), ctx.source(e)};
}

std::optional<Range> optional_range(ParseContext& ctx, Children& kids) {
  const Element* range = kids.opt("Range");
  if (range == nullptr) return std::nullopt;
  return parse_range(ctx, range);
}

DeterministicSingleParameterDistribution parse_single(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "DeterministicSingleParameterDistribution");
  DeterministicSingleParameterDistribution single;
  single.parameter_name = ctx.parameter_name(e, "parameterName");
  const Element* d = kids.choice();
  const std::string_view name = d->Name();
  if (name == "DistributionSet") {
    Children set_kids(ctx, d, "DistributionSet");
    DistributionSet set;
    for (const Element* element : set_kids.at_least("Element", 1)) {
      Children(ctx, element, "DistributionSetElement");
      set.values.push_back(ctx.req_str(element, "value"));
    }
    set.source = ctx.source(d);
    single.distribution = std::move(set);
  } else if (name == "DistributionRange") {
    Children range_kids(ctx, d, "DistributionRange");
    DistributionRange range{ctx.req_double(d, "stepWidth"),
                            parse_range(ctx, range_kids.one("Range")), ctx.source(d)};
    if (!(range.step_width > 0.0)) {
      ctx.fail(d, "DistributionRange stepWidth must be positive");
    }
    if ((range.range.upper_limit - range.range.lower_limit) / range.step_width > 1e7) {
      ctx.fail(d, "DistributionRange has more than 10 million steps");
    }
    single.distribution = range;
  } else {
    single.distribution = parse_user_defined(ctx, d);
  }
  single.source = ctx.source(e);
  return single;
}

DeterministicMultiParameterDistribution parse_multi(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "DeterministicMultiParameterDistribution");
  DeterministicMultiParameterDistribution multi;
  const Element* set_distribution = kids.one("ValueSetDistribution");
  Children set_kids(ctx, set_distribution, "ValueSetDistribution");
  for (const Element* set : set_kids.at_least("ParameterValueSet", 1)) {
    Children assignment_kids(ctx, set, "ParameterValueSet");
    std::vector<ParameterAssignment> assignments;
    for (const Element* a : assignment_kids.at_least("ParameterAssignment", 1)) {
      Children(ctx, a, "ParameterAssignment");
      assignments.push_back(
          {ctx.parameter_name(a, "parameterRef"), ctx.req_str(a, "value"), ctx.source(a)});
    }
    multi.value_sets.push_back(std::move(assignments));
  }
  multi.source = ctx.source(e);
  return multi;
}

double nonnegative(ParseContext& ctx, const Element* e, const char* name) {
  const double value = ctx.req_double(e, name);
  if (value < 0.0) {
    ctx.fail(e, std::string(name) + " must not be negative");
  }
  return value;
}

StochasticKind parse_stochastic_kind(ParseContext& ctx, const Element* d) {
  const std::string_view name = d->Name();
  if (name == "ProbabilityDistributionSet") {
    Children kids(ctx, d, "ProbabilityDistributionSet");
    ProbabilityDistributionSet set;
    double total = 0.0;
    for (const Element* element : kids.at_least("Element", 1)) {
      Children(ctx, element, "ProbabilityDistributionSetElement");
      set.elements.push_back({ctx.req_str(element, "value"), nonnegative(ctx, element, "weight")});
      total += set.elements.back().weight;
    }
    if (!(total > 0.0)) ctx.fail(d, "ProbabilityDistributionSet weights must not all be zero");
    set.source = ctx.source(d);
    return set;
  }
  if (name == "NormalDistribution" || name == "LogNormalDistribution") {
    Children kids(ctx, d,
                  name == "NormalDistribution" ? "NormalDistribution" : "LogNormalDistribution");
    const double mean = ctx.req_double(d, "expectedValue");
    const double variance = nonnegative(ctx, d, "variance");
    auto range = optional_range(ctx, kids);
    if (name == "NormalDistribution") {
      return NormalDistribution{mean, variance, range, ctx.source(d)};
    }
    if (!(mean > 0.0)) ctx.fail(d, "LogNormalDistribution expectedValue must be positive");
    return LogNormalDistribution{mean, variance, range, ctx.source(d)};
  }
  if (name == "UniformDistribution") {
    Children kids(ctx, d, "UniformDistribution");
    return UniformDistribution{parse_range(ctx, kids.one("Range")), ctx.source(d)};
  }
  if (name == "PoissonDistribution") {
    Children kids(ctx, d, "PoissonDistribution");
    const double mean = nonnegative(ctx, d, "expectedValue");
    if (mean > 1e9) ctx.fail(d, "PoissonDistribution expectedValue above 1e9 is not supported");
    return PoissonDistribution{mean, optional_range(ctx, kids), ctx.source(d)};
  }
  if (name == "Histogram") {
    Children kids(ctx, d, "Histogram");
    Histogram histogram;
    double total = 0.0;
    for (const Element* bin : kids.at_least("Bin", 1)) {
      Children bin_kids(ctx, bin, "HistogramBin");
      histogram.bins.push_back(
          {nonnegative(ctx, bin, "weight"), parse_range(ctx, bin_kids.one("Range"))});
      total += histogram.bins.back().weight;
    }
    if (!(total > 0.0)) ctx.fail(d, "Histogram weights must not all be zero");
    histogram.source = ctx.source(d);
    return histogram;
  }
  return parse_user_defined(ctx, d);
}

}  // namespace

ParameterValueDistribution parse_parameter_value_distribution(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "ParameterValueDistribution");
  ParameterValueDistribution distribution;
  distribution.scenario_file = parse_file(ctx, kids.one("ScenarioFile"));
  distribution.scenario_path =
      (ctx.file().directory / distribution.scenario_file.filepath).lexically_normal();
  std::error_code error;
  if (ctx.options().check_files &&
      !std::filesystem::is_regular_file(distribution.scenario_path, error)) {
    ctx.fail(kids.one("ScenarioFile"), "scenario file '" + distribution.scenario_file.filepath +
                                           "' not found (looked for " +
                                           distribution.scenario_path.string() + ")");
  }
  const Element* deterministic = kids.opt("Deterministic");
  const Element* stochastic = kids.opt("Stochastic");
  if ((deterministic != nullptr) == (stochastic != nullptr)) {
    ctx.fail(e, "<ParameterValueDistribution> needs exactly one of Deterministic and Stochastic");
  }
  if (deterministic != nullptr) {
    Children det_kids(ctx, deterministic, "Deterministic");
    det_kids.consume_all();
    Deterministic value;
    for (const Element* child = deterministic->FirstChildElement(); child != nullptr;
         child = child->NextSiblingElement()) {
      if (std::string_view(child->Name()) == "DeterministicSingleParameterDistribution") {
        value.entries.push_back(parse_single(ctx, child));
      } else {
        value.entries.push_back(parse_multi(ctx, child));
      }
    }
    value.source = ctx.source(deterministic);
    distribution.definition = std::move(value);
  } else {
    Children sto_kids(ctx, stochastic, "Stochastic");
    Stochastic value;
    value.number_of_test_runs = static_cast<uint32_t>(
        ctx.req_int(stochastic, "numberOfTestRuns", ParameterType::kUnsignedInt));
    value.random_seed = ctx.opt_double(stochastic, "randomSeed");
    // The schema types randomSeed as a double; a seed is a 64-bit integer (variants.cpp
    // seed_of): a value beyond one is read as the run's seed, a fraction as its whole part, both
    // lenient readings said here, where they stand (errors under --strict).
    if (value.random_seed && !(std::fabs(*value.random_seed) < kLargestRandomSeed)) {
      ctx.lenient(stochastic,
                  "randomSeed " + format_double(*value.random_seed) +
                      " is beyond a 64-bit seed (|randomSeed| < 9.2e18)",
                  "the run's seed: sweep --seed, default 0");
    } else if (value.random_seed && std::trunc(*value.random_seed) != *value.random_seed) {
      ctx.lenient(stochastic,
                  "randomSeed " + format_double(*value.random_seed) + " is not a whole number",
                  format_double(std::trunc(*value.random_seed)));
    }
    for (const Element* d : sto_kids.at_least("StochasticDistribution", 1)) {
      Children d_kids(ctx, d, "StochasticDistribution");
      value.distributions.push_back({ctx.parameter_name(d, "parameterName"),
                                     parse_stochastic_kind(ctx, d_kids.choice()), ctx.source(d)});
    }
    value.source = ctx.source(stochastic);
    distribution.definition = std::move(value);
  }
  distribution.source = ctx.source(e);
  return distribution;
}

}  // namespace corsa::xosc
