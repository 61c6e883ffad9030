#pragma once

// ParameterValueDistribution documents (§10): deterministic and stochastic parameter variation
// of a scenario, and the reproducible enumeration of their variants.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/xosc/common.h"
#include "corsa/xosc/parameters.h"

namespace corsa::xosc {

struct DistributionSet {
  std::vector<std::string> values;
  Source source;
};
/// Values lower, lower + step, ... up to upper (inclusive, within 1e-9 of a step).
struct DistributionRange {
  double step_width = 0.0;
  Range range;
  Source source;
};
struct UserDefinedDistribution {
  std::string type;
  std::string content;
  Source source;
};
struct DeterministicSingleParameterDistribution {
  std::string parameter_name;
  std::variant<DistributionSet, DistributionRange, UserDefinedDistribution> distribution;
  Source source;
};
/// ValueSetDistribution: each set assigns several parameters together.
struct DeterministicMultiParameterDistribution {
  std::vector<std::vector<ParameterAssignment>> value_sets;
  Source source;
};
using DeterministicEntry =
    std::variant<DeterministicSingleParameterDistribution, DeterministicMultiParameterDistribution>;
struct Deterministic {
  std::vector<DeterministicEntry> entries;
  Source source;
};

struct ProbabilityDistributionSetElement {
  std::string value;
  double weight = 0.0;
};
struct ProbabilityDistributionSet {
  std::vector<ProbabilityDistributionSetElement> elements;
  Source source;
};
/// Normal distribution with the given mean and variance, truncated to `range` when given.
struct NormalDistribution {
  double expected_value = 0.0;
  double variance = 0.0;
  std::optional<Range> range;
  Source source;
};
/// Log-normal distribution whose own mean and variance are expected_value and variance (so
/// sigma^2 = ln(1 + variance / mean^2), mu = ln(mean) - sigma^2 / 2); truncated to `range`.
struct LogNormalDistribution {
  double expected_value = 0.0;
  double variance = 0.0;
  std::optional<Range> range;
  Source source;
};
struct UniformDistribution {
  Range range;
  Source source;
};
struct PoissonDistribution {
  double expected_value = 0.0;
  std::optional<Range> range;
  Source source;
};
struct HistogramBin {
  double weight = 0.0;
  Range range;
};
/// Histogram: a bin drawn by weight, then a value uniform within the bin.
struct Histogram {
  std::vector<HistogramBin> bins;
  Source source;
};
using StochasticKind =
    std::variant<ProbabilityDistributionSet, NormalDistribution, LogNormalDistribution,
                 UniformDistribution, PoissonDistribution, Histogram, UserDefinedDistribution>;
struct StochasticDistribution {
  std::string parameter_name;
  StochasticKind distribution;
  Source source;
};
struct Stochastic {
  uint32_t number_of_test_runs = 0;
  std::optional<double> random_seed;
  std::vector<StochasticDistribution> distributions;
  Source source;
};

struct ParameterValueDistribution {
  FileHeader header;
  File scenario_file;                   ///< as written
  std::filesystem::path scenario_path;  ///< resolved against the distribution file's folder
  std::variant<Deterministic, Stochastic> definition;
  Source source;
};

/// Reads and checks a ParameterValueDistribution file (the scenario it names must exist).
ParameterValueDistribution load_distribution(const std::filesystem::path& path,
                                             Diagnostics& diagnostics);

/// One variant: parameter name -> value text, in the order the distribution names them.
struct Variant {
  std::vector<std::pair<std::string, std::string>> values;
};

struct VariantOptions {
  /// Seed for stochastic distributions without a randomSeed attribute.
  uint64_t default_seed = 0;
};

/// Number of variants: for Deterministic the product of the sizes of its entries (1 when it has
/// none); for Stochastic numberOfTestRuns.
size_t variant_count(const ParameterValueDistribution& distribution);

/// Variant `index` (0-based, < variant_count), computed on its own so that shards of a sweep can
/// draw any subset.
///
/// Order: Deterministic entries combine as nested loops in document order, the first entry
/// varying slowest (row-major). Stochastic run i draws each parameter from its own stream,
/// RandomStream::derive(seed, name + "#" + i), so a run never depends on another; seed is
/// randomSeed converted to a 64-bit integer (fraction dropped, negative values wrap), or
/// options.default_seed when the document gives none. Throws InputError for a
/// UserDefinedDistribution (not supported) or impossible parameters (negative variance, empty set,
/// non-positive step).
Variant variant_at(const ParameterValueDistribution& distribution, size_t index,
                   const VariantOptions& options = {});

/// All variants in order (variant_at for 0..variant_count-1).
std::vector<Variant> enumerate_variants(const ParameterValueDistribution& distribution,
                                        const VariantOptions& options = {});

}  // namespace corsa::xosc
