#pragma once

// `corsa run` (and Python's corsa.run) given a ParameterValueDistribution instead of a
// scenario: the run of its first variant.

#include "corsa/core/diagnostic.h"
#include "corsa/engine/run.h"

namespace corsa::sweep {

/// When `options.scenario` is a ParameterValueDistribution (a variation file, e.g. esmini's
/// cut-in_parameter_set.xosc) rather than a scenario: the run is of the scenario it names with its
/// first variant's parameter values (`--param` given on the command line still wins), warned at
/// the distribution's line as a lenient reading; under `--strict` (options.simulation.strict) an
/// InputError, as is a distribution without variants (refuse_distribution_without_variants).
/// Any other document is left alone.
void read_distribution_as_scenario(engine::RunOptions& options, Diagnostics& diagnostics);

}  // namespace corsa::sweep
