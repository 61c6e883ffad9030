#pragma once

// Sharding a sweep over a cluster: shard K of N runs the variants whose index i has
// i % N == K (round robin, so that a grid whose cost grows along one axis still splits evenly).
// Corsa schedules nothing itself: a Slurm job array or a Kubernetes Indexed Job starts one process
// per shard, and `corsa sweep merge` joins their output folders.

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

namespace corsa::sweep {

struct Shard {
  size_t index = 0;  ///< K, 0-based
  size_t count = 1;  ///< N >= 1

  bool whole() const { return count == 1; }
  bool contains(size_t variant) const { return variant % count == index; }
  /// How many of `total` variants this shard runs.
  size_t share(size_t total) const { return total / count + (index < total % count ? 1 : 0); }
  /// "K/N".
  std::string text() const;
};

/// Parses "K/N" (0 <= K < N). Throws InputError located at "--shard".
Shard parse_shard(std::string_view text);

/// Reads an environment variable; nothing when unset. The command line passes std::getenv; tests
/// pass a table.
using EnvironmentLookup = std::function<std::optional<std::string>(const std::string& name)>;

/// `--shard auto`: the shard from the scheduler's environment.
///   - Slurm job array: K = SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN (0 when unset, so both
///     --array=0-3 and --array=1-4 work), N = SLURM_ARRAY_TASK_COUNT.
///   - Kubernetes Indexed Job: K = JOB_COMPLETION_INDEX, N = `count` (--shard-count) or else
///     CORSA_SHARD_COUNT (a pod does not see its Job's completions).
/// Throws InputError located at "--shard auto" when neither is there or the values are invalid.
Shard shard_from_environment(const EnvironmentLookup& environment, std::optional<size_t> count);

}  // namespace corsa::sweep
