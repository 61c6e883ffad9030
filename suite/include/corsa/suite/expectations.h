#pragma once

// Checking a run against a test's expectations.

#include <optional>
#include <string>
#include <vector>

#include "corsa/suite/suite.h"
#include "corsa/sweep/variant_run.h"

namespace corsa::suite {

/// The value of a metric for a run. A minimum TTC or distance never measured (never on a
/// collision course, no other entity) is +infinity: it satisfies any lower bound. Nothing when
/// the run has no ego to measure.
std::optional<double> metric_value(Metric metric, const sweep::VariantResult& run);

/// Every expectation the run misses, one sentence each with the measured value, the bound and,
/// for metrics, when and against whom the extreme happened. Empty when all hold.
std::vector<std::string> check_expectations(const Expectations& expect,
                                            const sweep::VariantResult& run);

}  // namespace corsa::suite
