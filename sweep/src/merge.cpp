#include "corsa/sweep/merge.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "corsa/core/atomic_file.h"
#include "corsa/core/diagnostic.h"
#include "corsa/core/json.h"
#include "corsa/core/output_lock.h"
#include "corsa/core/strings.h"
#include "corsa/sweep/csv.h"
#include "corsa/sweep/summary_table.h"
#include "sweep_folder.h"

namespace corsa::sweep {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const fs::path& where, const std::string& message) {
  throw InputError(make_error(where.string(), 0, message));
}

struct ShardOutput {
  fs::path folder;
  std::string description;  ///< sweep.json as written
  Json described;           ///< ... and as read
  detail::Table table;
};

ShardOutput read_shard(const fs::path& folder) {
  std::error_code error;
  if (!fs::is_directory(folder, error)) fail(folder, "not a folder");
  if (!fs::exists(folder / detail::kDescriptionFile, error)) {
    fail(folder, "not a sweep output folder (it has no sweep.json)");
  }
  const fs::path described = folder / detail::kDescriptionFile;
  ShardOutput shard{folder, read_file(described), {}, {}};
  shard.described = parse_json(shard.description, described.string());
  auto table = detail::read_table(folder / detail::kSummaryFile);
  if (!table) {
    fail(folder,
         "the shard has not finished (no readable summary.csv): run it again with "
         "--resume");
  }
  shard.table = std::move(*table);
  return shard;
}

// Hard links where the file system allows (merging is then instant and takes no space), copies
// otherwise (another file system, or links not supported).
void link_or_copy(const fs::path& from, const fs::path& to) {
  std::error_code error;
  fs::create_hard_link(from, to, error);
  if (error) {
    fs::copy_file(from, to, fs::copy_options::overwrite_existing);
  }
}

// Fails when `path` (inside a shard) is a symbolic link: a sweep folder is made of real files and
// folders, and following a link would merge what it points at, from anywhere.
void refuse_link(const fs::path& path) {
  std::error_code error;
  if (fs::is_symlink(fs::symlink_status(path, error))) {
    fail(path, "is a symbolic link; a sweep folder holds real files and folders only");
  }
}

// The files of a finished variant, taken into the merge: exactly those a sweep writes (so no
// temporary a killed run left, nor anything else put there), each a regular file.
void merge_variant(const fs::path& shard_variant, const fs::path& merged_variant) {
  refuse_link(shard_variant);
  std::error_code error;
  if (!fs::is_directory(shard_variant, error)) return;
  fs::create_directory(merged_variant);
  for (const char* name : {detail::kTrajectoryFile, detail::kRunSummaryFile, detail::kResultFile}) {
    const fs::path file = shard_variant / name;
    refuse_link(file);
    if (fs::is_regular_file(file, error)) link_or_copy(file, merged_variant / name);
  }
}

// Staging folders of merges into `out` whose process is gone (killed before the rename): the pid
// in the name is not running here, and no live merge holds the folder's lock.
void remove_stale_staging(const fs::path& out) {
  const std::string prefix = "." + out.filename().string() + ".merge.";
  std::error_code error;
  const fs::path parent = out.parent_path().empty() ? fs::path(".") : out.parent_path();
  for (fs::directory_iterator it(parent, error), end; !error && it != end; it.increment(error)) {
    const std::string name = it->path().filename().string();
    if (!name.starts_with(prefix)) continue;
    const auto pid = parse_int(name.substr(prefix.size()));
    std::error_code ignored;
    if (!pid || *pid <= 0 || ::kill(static_cast<pid_t>(*pid), 0) == 0 || errno != ESRCH ||
        fs::is_symlink(it->symlink_status(ignored))) {
      continue;
    }
    try {
      const OutputLock lock(it->path());
    } catch (const InputError&) {
      continue;  // held: a live merge elsewhere
    }
    fs::remove_all(it->path(), ignored);
  }
}

// The variant count a sweep.json states.
size_t variant_count(const ShardOutput& shard) {
  const auto count = detail::variant_count_of(shard.described);
  if (!count) fail(shard.folder / detail::kDescriptionFile, "no variant count in sweep.json");
  return *count;
}

// A variant's summary row and the shard it came from, by variant index.
using Rows = std::map<size_t, std::pair<const ShardOutput*, const std::vector<std::string>*>>;

// Every variant's row from `shards`, checked: one sweep (same plan and columns), indices below
// `total`, a variant in two shards the same but for its wall time, none missing.
Rows merged_rows(const fs::path& out, const std::vector<ShardOutput>& shards, size_t total) {
  const ShardOutput& first = shards.front();
  const std::string plan = detail::plan_of(first.described);
  Rows rows;
  if (first.table.header.size() < kFixedColumnCount) {
    fail(first.folder, "summary.csv does not have the columns of a sweep summary");
  }
  for (const ShardOutput& shard : shards) {
    if (detail::plan_of(shard.described) != plan) {
      fail(shard.folder, "holds another sweep than " + first.folder.string() +
                             " (their sweep.json files differ)");
    }
    if (shard.table.header != first.table.header) {
      fail(shard.folder, "its summary.csv columns differ from " + first.folder.string());
    }
    for (const auto& row : shard.table.rows) {
      const auto index = detail::row_index(row);
      if (!index || *index >= total) fail(shard.folder, "summary.csv has a bad variant index");
      const auto [it, added] = rows.emplace(*index, std::make_pair(&shard, &row));
      if (!added && without_wall_time(*it->second.second) != without_wall_time(row)) {
        fail(shard.folder, "variant " + std::to_string(*index) + " differs from the one in " +
                               it->second.first->folder.string());
      }
    }
  }
  if (rows.size() != total) {
    // The first missing indices; at most rows.size() + 10 looked at, whatever count sweep.json
    // claims (a count of 1e15 used to be counted through).
    std::string missing;
    size_t count = 0;
    for (size_t i = 0; i < total && count < 10; ++i) {
      if (rows.count(i) == 0 && ++count <= 10)
        missing += (count > 1 ? ", " : "") + std::to_string(i);
    }
    fail(out, std::to_string(total - rows.size()) + " of " + std::to_string(total) +
                  " variants are in none of the shards (e.g. " + missing +
                  "): is a shard folder missing?");
  }
  return rows;
}

}  // namespace

MergeReport merge_sweeps(const fs::path& out, const std::vector<fs::path>& shard_folders,
                         bool force) {
  if (shard_folders.empty()) fail(out, "no shard folders to merge");
  std::error_code error;
  if (fs::exists(out, error) && !force &&
      !(fs::is_directory(out, error) && fs::is_empty(out, error))) {
    fail(out, "the merge output exists and is not empty (pass --force to replace it)");
  }
  std::vector<ShardOutput> shards;
  for (const auto& folder : shard_folders) shards.push_back(read_shard(folder));
  const ShardOutput& first = shards.front();
  const size_t total = variant_count(first);
  const Rows rows = merged_rows(out, shards, total);

  // A folder another process writes into (a sweep still running) is not replaced, nor one that
  // holds anything but an earlier sweep.
  std::optional<OutputLock> out_lock;
  std::vector<fs::path> replaced;
  if (fs::is_directory(out, error)) {
    const bool empty = fs::is_empty(out, error);
    out_lock.emplace(out);
    if (!empty) replaced = detail::replaceable_entries(out);
  } else if (fs::exists(fs::symlink_status(out, error))) {
    fail(out, "the merge output exists and is not a folder");
  }
  // Built next to `out` and renamed into place when complete.
  remove_stale_staging(out);
  const fs::path staging =
      out.parent_path() / ("." + out.filename().string() + ".merge." + std::to_string(::getpid()));
  fs::remove_all(staging, error);
  MergeReport report{rows.size(), 0, shards.size()};
  try {
    fs::create_directory(staging);
    std::optional<OutputLock> staging_lock(std::in_place, staging);
    fs::create_directory(staging / detail::kVariantsFolder);
    write_file_atomic(staging / detail::kDescriptionFile, first.description);
    std::string table = csv_line(first.table.header);
    const size_t status = status_column(first.table.header.size() - kFixedColumnCount);
    for (const ShardOutput& shard : shards) refuse_link(shard.folder / detail::kVariantsFolder);
    for (const auto& [index, entry] : rows) {
      const fs::path variant = fs::path(detail::kVariantsFolder) / std::to_string(index);
      merge_variant(entry.first->folder / variant, staging / variant);
      table += csv_line(*entry.second);
      const std::string& state = (*entry.second)[status];
      report.failed += state != "ok" && state != "skipped" ? 1 : 0;
    }
    write_file_atomic(staging / detail::kSummaryFile, table);
    staging_lock.reset();
    // Only the earlier sweep's own entries; the emptied folder is then replaced by the rename.
    for (const fs::path& entry : replaced) fs::remove(entry, error);
    if (fs::is_symlink(fs::symlink_status(out, error))) fs::remove(out, error);
    fs::rename(staging, out);
  } catch (...) {
    fs::remove_all(staging, error);
    throw;
  }
  return report;
}

}  // namespace corsa::sweep
