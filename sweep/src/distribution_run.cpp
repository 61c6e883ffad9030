#include "corsa/sweep/distribution_run.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "corsa/core/strings.h"
#include "corsa/sweep/variant_plan.h"
#include "corsa/xosc/distributions.h"
#include "corsa/xosc/scenario.h"

namespace corsa::sweep {

void read_distribution_as_scenario(engine::RunOptions& options, Diagnostics& diagnostics) {
  if (xosc::document_kind(options.scenario) != xosc::DocumentKind::kDistribution) {
    return;
  }
  const xosc::ParameterValueDistribution distribution =
      xosc::load_distribution(options.scenario, diagnostics);
  // No first variant to read it as.
  refuse_distribution_without_variants(distribution);
  const size_t count = xosc::variant_count(distribution);
  xosc::VariantOptions variant_options;
  variant_options.default_seed = options.simulation.seed;
  const xosc::Variant first = xosc::variant_at(distribution, 0, variant_options);
  std::string values;
  for (const auto& [name, value] : first.values) {
    values += (values.empty() ? "" : ", ") + name + "=" + clip(value);
  }
  const std::string message =
      "a parameter value distribution, not a scenario: `corsa sweep` runs its " +
      std::to_string(count) + " variant" + (count == 1 ? "" : "s");
  const std::string read_as = "a run of its scenario '" + distribution.scenario_file.filepath +
                              "' with the first variant" +
                              (values.empty() ? std::string() : ": " + values);
  if (options.simulation.strict) {
    throw InputError(distribution.source.error(
        message + " (an error under --strict; otherwise read as " + read_as + ")"));
  }
  diagnostics.add(distribution.source.warning(message + " (read as " + read_as + ")"));
  // The command line's --param values win over the variant's.
  std::vector<std::pair<std::string, std::string>> parameters;
  for (const auto& [name, value] : first.values) {
    const bool overridden = std::any_of(options.parameters.begin(), options.parameters.end(),
                                        [&](const auto& given) { return given.first == name; });
    if (!overridden) parameters.emplace_back(name, value);
  }
  parameters.insert(parameters.end(), options.parameters.begin(), options.parameters.end());
  options.parameters = std::move(parameters);
  options.scenario = distribution.scenario_path;
}

}  // namespace corsa::sweep
