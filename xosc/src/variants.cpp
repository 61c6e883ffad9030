// Enumeration of the variants of a ParameterValueDistribution (order documented in
// distributions.h). Stochastic draws use corsa::RandomStream, never <random>, so that a seed
// gives the same variants on every platform.

#include <cmath>
#include <limits>

#include "corsa/core/det_math.h"
#include "corsa/core/random.h"
#include "corsa/core/strings.h"
#include "corsa/xosc/distributions.h"
#include "random_seed.h"

namespace corsa::xosc {
namespace {

// Truncated distributions redraw until the value is inside the range; after this many draws
// the last one is clamped into it (only reached for ranges far in a tail).
constexpr int kMaxRedraws = 1000;

[[noreturn]] void unsupported(const UserDefinedDistribution& d) {
  throw InputError(
      d.source.error("UserDefinedDistribution of type '" + d.type + "' cannot be enumerated"));
}

size_t range_steps(const DistributionRange& range) {
  const double span = range.range.upper_limit - range.range.lower_limit;
  return static_cast<size_t>(std::floor(span / range.step_width + 1e-9)) + 1;
}

size_t entry_size(const DeterministicEntry& entry) {
  if (const auto* multi = std::get_if<DeterministicMultiParameterDistribution>(&entry)) {
    return multi->value_sets.size();
  }
  const auto& single = std::get<DeterministicSingleParameterDistribution>(entry);
  if (const auto* set = std::get_if<DistributionSet>(&single.distribution)) {
    return set->values.size();
  }
  if (const auto* range = std::get_if<DistributionRange>(&single.distribution)) {
    return range_steps(*range);
  }
  unsupported(std::get<UserDefinedDistribution>(single.distribution));
}

void append_entry(const DeterministicEntry& entry, size_t k, Variant& variant) {
  if (const auto* multi = std::get_if<DeterministicMultiParameterDistribution>(&entry)) {
    for (const auto& assignment : multi->value_sets[k]) {
      variant.values.emplace_back(assignment.parameter_ref, assignment.value);
    }
    return;
  }
  const auto& single = std::get<DeterministicSingleParameterDistribution>(entry);
  if (const auto* set = std::get_if<DistributionSet>(&single.distribution)) {
    variant.values.emplace_back(single.parameter_name, set->values[k]);
    return;
  }
  const auto& range = std::get<DistributionRange>(single.distribution);
  // lower + k * step, not a running sum, so that rounding does not accumulate.
  const double value = range.range.lower_limit + static_cast<double>(k) * range.step_width;
  variant.values.emplace_back(single.parameter_name, format_double(value));
}

uint64_t seed_of(const Stochastic& stochastic, const VariantOptions& options) {
  if (!stochastic.random_seed || !(std::fabs(*stochastic.random_seed) < kLargestRandomSeed)) {
    return options.default_seed;
  }
  return static_cast<uint64_t>(static_cast<int64_t>(std::trunc(*stochastic.random_seed)));
}

double clamp_to(double value, const Range& range) {
  return value < range.lower_limit ? range.lower_limit
                                   : (value > range.upper_limit ? range.upper_limit : value);
}

template <class Draw>
double truncated(const std::optional<Range>& range, Draw draw) {
  double value = draw();
  if (!range) return value;
  for (int i = 0; i < kMaxRedraws; ++i) {
    if (value >= range->lower_limit && value <= range->upper_limit) return value;
    value = draw();
  }
  return clamp_to(value, *range);
}

std::string draw(const StochasticKind& kind, RandomStream& stream) {
  if (const auto* set = std::get_if<ProbabilityDistributionSet>(&kind)) {
    std::vector<double> weights;
    for (const auto& element : set->elements) weights.push_back(element.weight);
    return set->elements[stream.weighted_index(weights)].value;
  }
  if (const auto* normal = std::get_if<NormalDistribution>(&kind)) {
    const double sigma = std::sqrt(normal->variance);
    return format_double(
        truncated(normal->range, [&] { return stream.normal(normal->expected_value, sigma); }));
  }
  if (const auto* log_normal = std::get_if<LogNormalDistribution>(&kind)) {
    const double mean = log_normal->expected_value;
    const double sigma2 = det::log(1.0 + log_normal->variance / (mean * mean));
    const double mu = det::log(mean) - 0.5 * sigma2;
    const double sigma = std::sqrt(sigma2);
    return format_double(
        truncated(log_normal->range, [&] { return stream.log_normal(mu, sigma); }));
  }
  if (const auto* uniform = std::get_if<UniformDistribution>(&kind)) {
    const Range& r = uniform->range;
    return format_double(r.lower_limit == r.upper_limit
                             ? r.lower_limit
                             : stream.uniform(r.lower_limit, r.upper_limit));
  }
  if (const auto* poisson = std::get_if<PoissonDistribution>(&kind)) {
    const double value = truncated(poisson->range, [&] {
      return static_cast<double>(stream.poisson(poisson->expected_value));
    });
    return std::to_string(static_cast<int64_t>(value));
  }
  if (const auto* histogram = std::get_if<Histogram>(&kind)) {
    std::vector<double> weights;
    for (const auto& bin : histogram->bins) weights.push_back(bin.weight);
    const Range& r = histogram->bins[stream.weighted_index(weights)].range;
    return format_double(r.lower_limit == r.upper_limit
                             ? r.lower_limit
                             : stream.uniform(r.lower_limit, r.upper_limit));
  }
  unsupported(std::get<UserDefinedDistribution>(kind));
}

}  // namespace

size_t variant_count(const ParameterValueDistribution& distribution) {
  if (const auto* stochastic = std::get_if<Stochastic>(&distribution.definition)) {
    return stochastic->number_of_test_runs;
  }
  size_t count = 1;
  for (const auto& entry : std::get<Deterministic>(distribution.definition).entries) {
    const size_t size = entry_size(entry);
    if (size != 0 && count > std::numeric_limits<size_t>::max() / size) {
      throw InputError(distribution.source.error("the distribution has too many variants"));
    }
    count *= size;
  }
  return count;
}

Variant variant_at(const ParameterValueDistribution& distribution, size_t index,
                   const VariantOptions& options) {
  Variant variant;
  if (const auto* stochastic = std::get_if<Stochastic>(&distribution.definition)) {
    const uint64_t seed = seed_of(*stochastic, options);
    for (const auto& d : stochastic->distributions) {
      RandomStream stream =
          RandomStream::derive(seed, d.parameter_name + "#" + std::to_string(index));
      variant.values.emplace_back(d.parameter_name, draw(d.distribution, stream));
    }
    return variant;
  }
  const auto& entries = std::get<Deterministic>(distribution.definition).entries;
  std::vector<size_t> digits(entries.size(), 0);
  size_t rest = index;
  // Row-major: the last entry varies fastest.
  for (size_t i = entries.size(); i-- > 0;) {
    const size_t size = entry_size(entries[i]);
    digits[i] = size == 0 ? 0 : rest % size;
    rest = size == 0 ? rest : rest / size;
  }
  for (size_t i = 0; i < entries.size(); ++i) {
    append_entry(entries[i], digits[i], variant);
  }
  return variant;
}

std::vector<Variant> enumerate_variants(const ParameterValueDistribution& distribution,
                                        const VariantOptions& options) {
  std::vector<Variant> variants;
  const size_t count = variant_count(distribution);
  variants.reserve(count);
  for (size_t i = 0; i < count; ++i) {
    variants.push_back(variant_at(distribution, i, options));
  }
  return variants;
}

}  // namespace corsa::xosc
