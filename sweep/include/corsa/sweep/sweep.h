#pragma once

// A whole sweep (or one shard of it): every variant of a plan on a few threads, each writing
// its own folder, then the summary table. The output folder:
//   sweep.json              what was swept (source, scenario, parameters, variant count, options,
//                           content hashes); identical for every shard of one sweep
//   shard.json              which shard this folder holds (only for a sharded run)
//   variants/<index>/       trajectory.csv, summary.json (engine formats) and result.csv (the
//                           variant's summary.csv row, written last: it marks the variant done)
//   summary.csv             every variant of this folder, by index (see summary_table.h)
// Outputs do not depend on the thread count: variant i always gets the same parameter values,
// seed and files.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/engine/simulation.h"
#include "corsa/sweep/shard.h"
#include "corsa/sweep/variant_plan.h"

namespace corsa::sweep {

struct SweepOptions {
  std::filesystem::path output;
  size_t jobs = 0;  ///< threads; 0: every core
  Shard shard;
  /// Keep the variants already done in `output` (their result.csv) and run the rest; the folder
  /// must hold the same sweep (sweep.json) and shard.
  bool resume = false;
  /// Replace an earlier sweep in `output` (its sweep.json, shard.json, summary.csv, variants/).
  bool force = false;
  /// Every variant's simulation options; the same seed for all, so that a variant reruns alone
  /// with `corsa run SCENARIO --param ... --seed N` and gives the same trajectory.
  engine::SimulationOptions simulation;
  int64_t record_every = 1;  ///< ticks between trajectory rows
  bool trajectories = true;  ///< write variants/<i>/trajectory.csv
  std::string ego;           ///< entity the metrics are measured for; "" chooses
  /// Asked before each variant starts (from worker threads); a value, the reason (e.g.
  /// "interrupted by SIGINT"), stops the sweep once the variants in progress are done. Their
  /// folders are complete; summary.csv is not written, so `--resume` finishes the sweep.
  std::function<std::optional<std::string>()> stop;
};

struct SweepReport {
  size_t variants = 0;  ///< in this shard
  size_t ran = 0;
  size_t resumed = 0;  ///< taken from an earlier run (--resume)
  size_t failed = 0;   ///< rows whose status is neither ok nor skipped (ran or resumed)
  size_t skipped = 0;  ///< variants whose values violate the scenario's value constraints
  /// Set when SweepOptions::stop stopped the sweep: why. `ran + resumed` variants are done.
  std::optional<std::string> interruption;
  double wall_seconds = 0.0;
  /// The first few failures by index: variant index and error text.
  std::vector<std::pair<size_t, std::string>> first_failures;
  static constexpr size_t kFailuresListed = 5;
};

/// Called after each variant with (done, total) of this shard; from worker threads.
using SweepProgress = std::function<void(size_t done, size_t total)>;

/// Checks the plan against its scenario (VariantPlan::check), prepares `output` and runs the
/// shard's variants. Throws InputError, before writing anything, for a bad plan or an output
/// folder holding another sweep, written by another process at the moment (the folder is locked
/// for one writer, see corsa/core/output_lock.h) or holding a symbolic link where Corsa writes; a
/// failing variant is recorded in its row and never stops the others. With `resume`, the
/// temporaries a killed run left in a variant's folder are removed before it is looked at.
SweepReport run_sweep(const VariantPlan& plan, const SweepOptions& options,
                      Diagnostics& diagnostics, const SweepProgress& progress = {});

/// The text of sweep.json for a plan and options (deterministic).
std::string sweep_description(const VariantPlan& plan, const SweepOptions& options);

}  // namespace corsa::sweep
