#pragma once

// `corsa sweep merge OUT SHARD_DIRS...`: joins the output folders of a sweep's shards into one
// folder equal to what the unsharded sweep writes (except wall times).

#include <cstddef>
#include <filesystem>
#include <vector>

namespace corsa::sweep {

struct MergeReport {
  size_t variants = 0;
  size_t failed = 0;
  size_t shards = 0;
};

/// Checks that every folder holds a finished shard (summary.csv) of the same sweep (sweep.json)
/// and that together they hold every variant exactly once (a variant found twice must have the
/// same row), then writes `out`: sweep.json, variants/ (each variant's trajectory.csv,
/// summary.json and result.csv, nothing else: hard links to the shards' files where the file
/// system allows, copies otherwise) and summary.csv. A symbolic link where a shard's variants or
/// their files belong is an error (it is never followed). The folder is built under a temporary
/// name next to `out` and renamed into place, so `out` never holds half a merge (staging folders
/// of killed merges are removed). `out` must not exist or be empty unless `force`, which replaces
/// an earlier sweep or merge there: a folder with Corsa's sweep.json holding only what a sweep
/// writes (anything else, and the folder is refused before anything is removed). `out` must not
/// be locked by a live writer (corsa/core/output_lock.h). Throws InputError naming the folder and
/// the problem.
MergeReport merge_sweeps(const std::filesystem::path& out,
                         const std::vector<std::filesystem::path>& shards, bool force = false);

}  // namespace corsa::sweep
