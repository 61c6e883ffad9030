#include "corsa/sweep/sweep.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <optional>
#include <vector>

#include "corsa/core/atomic_file.h"
#include "corsa/core/json.h"
#include "corsa/core/output_lock.h"
#include "corsa/core/random.h"
#include "corsa/core/strings.h"
#include "corsa/core/version.h"
#include "corsa/sweep/csv.h"
#include "corsa/sweep/parallel.h"
#include "corsa/sweep/summary_table.h"
#include "corsa/xosc/scenario.h"
#include "sweep_folder.h"

namespace corsa::sweep {
namespace {

namespace fs = std::filesystem;

// Variants one process runs: each keeps a summary row in memory and a folder on disk. More than
// this is a mistyped distribution (three 10-million-value ranges multiply to 1e21), not a sweep
// that could finish; it used to end in "out of memory" after sweep.json had been written.
constexpr size_t kMaxVariantsPerProcess = 10'000'000;

void check_variant_count(const VariantPlan& plan, size_t share) {
  if (share <= kMaxVariantsPerProcess) return;
  Diagnostic where = plan.distribution() ? plan.distribution()->source.error("")
                                         : make_error(plan.source().string(), 0, "");
  where.message = "the sweep has " + std::to_string(share) +
                  " variants for this process, more than the " +
                  std::to_string(kMaxVariantsPerProcess) +
                  " one process runs (use fewer values, or --shard K/N over more processes)";
  throw InputError(where);
}

std::string hex(uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
  return text;
}

[[noreturn]] void folder_error(const fs::path& folder, const std::string& message) {
  throw InputError(make_error(folder.string(), 0, message));
}

// The output folder, made if missing and locked for this process (one writer per folder). If
// the sweep is refused before keep(), a folder it made is removed again.
class LockedOutput {
 public:
  explicit LockedOutput(const fs::path& folder) : folder_(folder) {
    std::error_code error;
    if (fs::exists(folder, error) && !fs::is_directory(folder, error)) {
      folder_error(folder, "the sweep output (-o) exists and is not a folder");
    }
    created_ = fs::create_directories(folder, error);
    if (error) {
      folder_error(folder, "cannot create the output folder (" + error.message() + ")");
    }
    try {
      lock_.emplace(folder);
    } catch (...) {
      remove_if_made();
      throw;
    }
  }
  LockedOutput(const LockedOutput&) = delete;
  LockedOutput& operator=(const LockedOutput&) = delete;
  ~LockedOutput() {
    lock_.reset();
    if (!kept_) remove_if_made();
  }
  void keep() { kept_ = true; }

 private:
  void remove_if_made() {
    std::error_code ignored;
    if (created_) fs::remove(folder_, ignored);  // only when still empty
  }

  fs::path folder_;
  bool created_ = false;
  bool kept_ = false;
  std::optional<OutputLock> lock_;
};

// Checks what `options.output` holds before anything is written: nothing of a sweep, this sweep
// (--resume), or an earlier sweep to replace (--force), whose own entries are then removed and
// nothing else (a folder holding anything more is refused untouched).
void prepare_output(const SweepOptions& options, const Json& description, const Json& shard) {
  const fs::path& out = options.output;
  std::error_code error;
  if (!fs::exists(out / detail::kDescriptionFile, error)) {
    return;
  }
  if (options.force) {
    const fs::path lock = out / OutputLock::kFileName;  // ours, held
    for (const fs::path& entry : detail::replaceable_entries(out)) {
      if (entry != lock && !fs::remove(entry, error) && error) {
        folder_error(entry, "cannot remove (" + error.message() + ")");
      }
    }
    return;
  }
  if (!options.resume) {
    folder_error(out,
                 "this folder holds a sweep already: pass --resume to finish it, --force to "
                 "replace it, or choose another output folder (-o)");
  }
  detail::check_resumable(out, description, shard);
}

// shard.json: which share of the variants this folder holds; null for the whole sweep (no file).
Json shard_json(const Shard& shard, size_t variants) {
  if (shard.whole()) return nullptr;
  return {{"shard", shard.text()},
          {"index", shard.index},
          {"count", shard.count},
          {"variants", shard.share(variants)}};
}

struct Context {
  const VariantPlan& plan;
  const std::vector<std::string>& unused;  ///< distribution parameters the scenario lacks
  const SweepOptions& options;
  const std::vector<std::string>& header;
  SharedInputs& inputs;
  Diagnostics& diagnostics;
};

std::vector<std::string> run_one(const Context& c, size_t index, bool& resumed) {
  const fs::path relative = fs::path(detail::kVariantsFolder) / std::to_string(index);
  const fs::path folder = c.options.output / relative;
  create_folder_inside(c.options.output, relative);
  if (c.options.resume) {
    remove_stale_temporaries(folder);
    if (auto row = detail::finished_row(folder, index, c.header)) {
      resumed = true;
      return *row;
    }
  }
  VariantSpec spec;
  spec.parameters = c.plan.variant(index);
  const ParameterValues all_values = spec.parameters;
  std::erase_if(spec.parameters, [&](const auto& value) {
    return std::find(c.unused.begin(), c.unused.end(), value.first) != c.unused.end();
  });
  spec.simulation = c.options.simulation;
  spec.ego = c.options.ego;
  VariantOutputs outputs;
  if (c.options.trajectories) outputs.trajectory = folder / detail::kTrajectoryFile;
  outputs.summary = folder / detail::kRunSummaryFile;
  outputs.record_every = c.options.record_every;
  const VariantResult result = run_variant(c.inputs, spec, outputs, c.diagnostics);
  if (!result.ok()) {
    // No output of an earlier, interrupted attempt may pass for this run's.
    std::error_code ignored;
    fs::remove(folder / detail::kTrajectoryFile, ignored);
    fs::remove(folder / detail::kRunSummaryFile, ignored);
  }
  std::vector<std::string> row = summary_row(index, c.plan.parameter_names(), all_values, result);
  write_file_atomic(folder / detail::kResultFile, csv_line(c.header) + csv_line(row));
  return row;
}

// sweep.json's content.
Json description_of(const VariantPlan& plan, const SweepOptions& options) {
  const std::string source_hash = hex(stable_hash(read_file(plan.source())));
  const std::string scenario_hash =
      plan.source() == plan.scenario() ? source_hash : hex(stable_hash(read_file(plan.scenario())));
  Json grid = Json::array();
  for (const auto& axis : plan.grid()) grid.push_back(axis.spec);
  // Everything that decides the variants' results, without the paths (shards may see the same
  // files under other mount points): resume and merge compare this.
  const Json decisive = {{"corsa", version()},
                         {"source_hash", source_hash},
                         {"scenario_hash", scenario_hash},
                         {"grid", std::move(grid)},
                         {"parameters", plan.parameter_names()},
                         {"variants", plan.size()},
                         {"default_seed", plan.default_seed()},
                         {"seed", options.simulation.seed},
                         {"dt", options.simulation.dt},
                         {"duration", options.simulation.duration},
                         {"record_every", options.record_every},
                         {"trajectories", options.trajectories},
                         {"ego", options.ego}};
  // The plan hash covers these members as their lines in sweep.json, each with its comma.
  std::string lines;
  for (auto it = decisive.begin(); it != decisive.end(); ++it) {
    lines += "  " + json_line(it.key()) + ": " + json_line(it.value()) + ",\n";
  }
  Json description = {{"source", plan.source().string()}, {"scenario", plan.scenario().string()}};
  description.update(decisive);
  description["plan"] = hex(stable_hash(lines));
  return description;
}

}  // namespace

std::string sweep_description(const VariantPlan& plan, const SweepOptions& options) {
  return json_document(description_of(plan, options));
}

SweepReport run_sweep(const VariantPlan& plan, const SweepOptions& options,
                      Diagnostics& diagnostics, const SweepProgress& progress) {
  const auto start = std::chrono::steady_clock::now();
  SharedInputs inputs(plan.scenario(), diagnostics);
  const std::vector<std::string> unused =
      plan.check(inputs.load({}, diagnostics, options.simulation.strict,
                             options.simulation.semantics == engine::Semantics::kEsmini),
                 options.simulation.strict, diagnostics);
  check_variant_count(plan, options.shard.share(plan.size()));
  const Json description = description_of(plan, options);
  const Json shard = shard_json(options.shard, plan.size());
  LockedOutput output(options.output);
  prepare_output(options, description, shard);
  create_folder_inside(options.output, detail::kVariantsFolder);
  write_file_atomic(options.output / detail::kDescriptionFile, json_document(description));
  if (!shard.is_null())
    write_file_atomic(options.output / detail::kShardFile, json_document(shard));
  output.keep();

  const std::vector<std::string> header = summary_header(plan.parameter_names());
  const size_t share = options.shard.share(plan.size());
  std::vector<std::vector<std::string>> rows(share);
  std::vector<char> resumed(share, 0);
  const Context context{plan, unused, options, header, inputs, diagnostics};
  std::mutex progress_mutex;
  size_t done = 0;
  std::optional<std::string> interruption;
  std::mutex stop_mutex;
  const auto stopped = [&] {
    if (!options.stop) return false;
    std::lock_guard lock(stop_mutex);
    if (!interruption) interruption = options.stop();
    return interruption.has_value();
  };
  parallel_for(share, options.jobs, [&](size_t k) {
    if (stopped()) return;
    const size_t index = options.shard.index + k * options.shard.count;
    bool was_resumed = false;
    rows[k] = run_one(context, index, was_resumed);
    resumed[k] = was_resumed ? 1 : 0;
    if (progress) {
      std::lock_guard lock(progress_mutex);
      progress(++done, share);
    }
  });

  SweepReport report;
  report.variants = share;
  if (interruption) {
    // The variants done are complete in their folders; without summary.csv the folder is an
    // unfinished sweep, which --resume completes and merge refuses.
    for (size_t k = 0; k < share; ++k) {
      if (rows[k].empty()) continue;
      (resumed[k] != 0 ? report.resumed : report.ran) += 1;
    }
    report.interruption = interruption;
    report.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return report;
  }
  std::string table = csv_line(header);
  const size_t status = status_column(plan.parameter_names().size());
  for (size_t k = 0; k < share; ++k) {
    table += csv_line(rows[k]);
    report.resumed += resumed[k] != 0 ? 1 : 0;
    if (rows[k][status] == "skipped") {
      ++report.skipped;
    } else if (rows[k][status] != "ok") {
      ++report.failed;
      if (report.first_failures.size() < SweepReport::kFailuresListed) {
        report.first_failures.emplace_back(options.shard.index + k * options.shard.count,
                                           rows[k][rows[k].size() - 2]);
      }
    }
  }
  report.ran = share - report.resumed;
  write_file_atomic(options.output / detail::kSummaryFile, table);
  report.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace corsa::sweep
