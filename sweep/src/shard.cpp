#include "corsa/sweep/shard.h"

#include "corsa/core/diagnostic.h"
#include "corsa/core/strings.h"

namespace corsa::sweep {
namespace {

[[noreturn]] void fail(const std::string& where, const std::string& message) {
  throw InputError(make_error(where, 0, message));
}

std::optional<size_t> non_negative(const std::optional<std::string>& text) {
  if (!text) return std::nullopt;
  const auto value = parse_int(*text);
  if (!value || *value < 0) return std::nullopt;
  return static_cast<size_t>(*value);
}

Shard checked(size_t index, size_t count, const std::string& where) {
  if (count == 0) fail(where, "the shard count must be at least 1");
  if (index >= count) {
    fail(where, "shard index " + std::to_string(index) + " is not below the shard count " +
                    std::to_string(count) + " (shards are numbered 0 to N-1)");
  }
  return Shard{index, count};
}

// The position of task `task` in an array of `tasks` ids from `min`: with a step
// (--array=0-6:2, SLURM_ARRAY_TASK_STEP) the ids are min, min + step, ...; a list of ids
// (--array=0,3,5) has no such position and is refused.
size_t slurm_array_position(const EnvironmentLookup& environment, size_t task, size_t min,
                            size_t tasks) {
  const std::string where = "--shard auto (Slurm)";
  const auto step_text = environment("SLURM_ARRAY_TASK_STEP");
  const auto step = step_text ? non_negative(step_text) : std::optional<size_t>(1);
  const auto max_text = environment("SLURM_ARRAY_TASK_MAX");
  const auto max = max_text ? non_negative(max_text) : std::nullopt;
  if (!step || *step == 0) fail(where, "SLURM_ARRAY_TASK_STEP must be a positive whole number");
  if ((task - min) % *step != 0 || (max && (*max < min || (*max - min) / *step + 1 != tasks))) {
    fail(where, "the array's task ids are a list, not a range A-B or A-B:STEP, so task " +
                    std::to_string(task) + " has no shard index; submit --array=0-" +
                    std::to_string(tasks > 0 ? tasks - 1 : 0) + " or use --shard K/N");
  }
  return (task - min) / *step;
}

}  // namespace

std::string Shard::text() const { return std::to_string(index) + "/" + std::to_string(count); }

Shard parse_shard(std::string_view text) {
  const std::string where = "--shard " + std::string(text);
  const size_t slash = text.find('/');
  if (slash == std::string_view::npos) {
    fail(where, "expected K/N (shard K of N, K from 0 to N-1) or 'auto'");
  }
  const auto k = parse_int(text.substr(0, slash));
  const auto n = parse_int(text.substr(slash + 1));
  if (!k || !n || *k < 0 || *n < 1) {
    fail(where, "expected K/N with whole numbers, 0 <= K < N");
  }
  return checked(static_cast<size_t>(*k), static_cast<size_t>(*n), where);
}

Shard shard_from_environment(const EnvironmentLookup& environment, std::optional<size_t> count) {
  const std::string where = "--shard auto";
  if (const auto id = environment("SLURM_ARRAY_TASK_ID")) {
    const auto task = non_negative(id);
    const auto tasks = non_negative(environment("SLURM_ARRAY_TASK_COUNT"));
    const auto min_text = environment("SLURM_ARRAY_TASK_MIN");
    const auto min = min_text ? non_negative(min_text) : std::optional<size_t>(0);
    if (!task || !tasks || !min || *task < *min) {
      fail(where,
           "SLURM_ARRAY_TASK_ID, SLURM_ARRAY_TASK_COUNT and SLURM_ARRAY_TASK_MIN must be "
           "whole numbers with ID >= MIN (is this a job array with --array=A-B?)");
    }
    return checked(slurm_array_position(environment, *task, *min, *tasks), count.value_or(*tasks),
                   where + " (Slurm)");
  }
  if (const auto index_text = environment("JOB_COMPLETION_INDEX")) {
    const auto index = non_negative(index_text);
    if (!index) fail(where, "JOB_COMPLETION_INDEX must be a whole number");
    std::optional<size_t> n = count;
    if (!n) {
      const auto env_count = environment("CORSA_SHARD_COUNT");
      if (!env_count) {
        fail(where,
             "a Kubernetes Indexed Job needs the shard count: pass --shard-count N (the "
             "Job's completions) or set CORSA_SHARD_COUNT");
      }
      n = non_negative(env_count);
      if (!n) fail(where, "CORSA_SHARD_COUNT must be a whole number");
    }
    return checked(*index, *n, where + " (Kubernetes)");
  }
  fail(where,
       "found neither SLURM_ARRAY_TASK_ID (a Slurm job array) nor JOB_COMPLETION_INDEX (a "
       "Kubernetes Indexed Job); use --shard K/N to give the shard by hand");
}

}  // namespace corsa::sweep
