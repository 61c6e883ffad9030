#pragma once

// One variant of a sweep (or one test of a suite): load the scenario with the variant's parameter
// values from the shared inputs, simulate to the end while measuring the metrics, write its
// outputs. Bad input and internal errors are caught and reported in the result, never thrown: a
// failing variant must not stop the others.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "corsa/engine/simulation.h"
#include "corsa/sweep/metrics.h"
#include "corsa/sweep/shared_inputs.h"

namespace corsa::sweep {

struct VariantSpec {
  ParameterValues parameters;
  engine::SimulationOptions simulation;
  std::string ego;  ///< entity the metrics are measured for; "" chooses (see choose_ego)
};

struct VariantOutputs {
  std::optional<std::filesystem::path> trajectory;  ///< trajectory CSV (engine format)
  std::optional<std::filesystem::path> summary;     ///< run summary JSON (engine format)
  int64_t record_every = 1;                         ///< ticks between trajectory rows
  /// Keep the trajectory CSV text (every `record_every` ticks, first and last always) in
  /// VariantResult::trajectory_text, e.g. to compare with a golden file.
  bool keep_trajectory_text = false;
};

/// How a variant ended, as exit statuses of `corsa run` say it.
enum class VariantStatus : uint8_t {
  kOk,        ///< ran to its end (collisions or not)
  kBadInput,  ///< the variant's scenario, parameters or map are bad input (exit status 2)
  kInternal,  ///< an unexpected error, a bug in Corsa (exit status 3)
  /// Not run: the variant's values violate the scenario's value constraints (a combination the
  /// scenario does not allow; exit status 0, not a failure of the sweep).
  kSkipped,
};
int exit_status(VariantStatus status);
/// "ok", "error", "internal error", "skipped"
std::string_view to_string(VariantStatus status);

struct VariantResult {
  VariantStatus status = VariantStatus::kOk;
  std::string error;  ///< the located message when not ok
  engine::EndReason end_reason = engine::EndReason::kRunning;
  double sim_time = 0.0;  ///< s
  int64_t steps = 0;
  size_t collisions = 0;  ///< all contacts between any two entities
  /// Collisions that involve the ego.
  size_t ego_collisions = 0;
  /// The first contact as text, "Ego and A1 at t=12.34 s"; "" when none.
  std::string first_collision;
  RunMetrics metrics;
  /// The scenario's monitors (MonitorDeclarations) and their values at the end, by name.
  std::vector<std::pair<std::string, bool>> monitors;
  double wall_seconds = 0.0;
  std::string trajectory_text;  ///< with VariantOutputs::keep_trajectory_text

  bool ok() const { return status == VariantStatus::kOk; }
};

/// Runs one variant. Warnings go to `diagnostics` (shared by all variants, so warn-once kinds
/// print once per sweep). Outputs are written only for a run that completed.
VariantResult run_variant(SharedInputs& inputs, const VariantSpec& spec,
                          const VariantOutputs& outputs, Diagnostics& diagnostics);

}  // namespace corsa::sweep
