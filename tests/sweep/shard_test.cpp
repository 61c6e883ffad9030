#include "corsa/sweep/shard.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <map>

#include "corsa/core/diagnostic.h"

using corsa::InputError;
using corsa::sweep::parse_shard;
using corsa::sweep::Shard;
using corsa::sweep::shard_from_environment;

namespace {

corsa::sweep::EnvironmentLookup table(std::map<std::string, std::string> values) {
  return [values](const std::string& name) -> std::optional<std::string> {
    const auto found = values.find(name);
    return found == values.end() ? std::nullopt : std::optional<std::string>(found->second);
  };
}

std::string error_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const InputError& error) {
    return error.diagnostic().format();
  }
  return "no error";
}

}  // namespace

TEST_CASE("shards split the variants round robin and cover each exactly once", "[sweep][shard]") {
  const size_t total = 10;
  std::vector<int> owners(total, 0);
  size_t shared = 0;
  for (size_t k = 0; k < 4; ++k) {
    const Shard shard{k, 4};
    shared += shard.share(total);
    for (size_t i = 0; i < total; ++i) owners[i] += shard.contains(i) ? 1 : 0;
  }
  CHECK(shared == total);
  CHECK(std::all_of(owners.begin(), owners.end(), [](int n) { return n == 1; }));
  CHECK(Shard{1, 4}.share(10) == 3);
  CHECK(Shard{3, 4}.share(10) == 2);
  CHECK(Shard{}.whole());
}

TEST_CASE("--shard K/N parses and rejects what is not a shard", "[sweep][shard]") {
  const Shard shard = parse_shard("2/8");
  CHECK(shard.index == 2);
  CHECK(shard.count == 8);
  CHECK(shard.text() == "2/8");
  CHECK(error_of([] {
          parse_shard("4/4");
        }).find("--shard 4/4: error: shard index 4 is not below") == 0);
  CHECK(error_of([] { parse_shard("1-4"); }).find("expected K/N") != std::string::npos);
  CHECK(error_of([] { parse_shard("a/4"); }).find("whole numbers") != std::string::npos);
  CHECK(error_of([] { parse_shard("0/0"); }).find("whole numbers") != std::string::npos);
}

TEST_CASE("--shard auto reads a Slurm job array, from 0 or from 1", "[sweep][shard]") {
  const Shard zero = shard_from_environment(
      table({{"SLURM_ARRAY_TASK_ID", "3"}, {"SLURM_ARRAY_TASK_COUNT", "4"}}), std::nullopt);
  CHECK(zero.index == 3);
  CHECK(zero.count == 4);
  const Shard one = shard_from_environment(table({{"SLURM_ARRAY_TASK_ID", "1"},
                                                  {"SLURM_ARRAY_TASK_COUNT", "4"},
                                                  {"SLURM_ARRAY_TASK_MIN", "1"}}),
                                           std::nullopt);
  CHECK(one.index == 0);
  CHECK(error_of([] {
          shard_from_environment(table({{"SLURM_ARRAY_TASK_ID", "x"}}), std::nullopt);
        }).find("SLURM_ARRAY_TASK_ID") != std::string::npos);
}

TEST_CASE("--shard auto numbers the tasks of a Slurm array with a step, and refuses a list",
          "[sweep][shard]") {
  // --array=0-6:2: ids 0, 2, 4, 6 are shards 0 to 3 of 4.
  const Shard stepped = shard_from_environment(table({{"SLURM_ARRAY_TASK_ID", "4"},
                                                      {"SLURM_ARRAY_TASK_COUNT", "4"},
                                                      {"SLURM_ARRAY_TASK_MIN", "0"},
                                                      {"SLURM_ARRAY_TASK_MAX", "6"},
                                                      {"SLURM_ARRAY_TASK_STEP", "2"}}),
                                               std::nullopt);
  CHECK(stepped.index == 2);
  CHECK(stepped.count == 4);
  // --array=0,3,5: Slurm says step 1, but the ids are not 0 to 2.
  CHECK(error_of([] {
          shard_from_environment(table({{"SLURM_ARRAY_TASK_ID", "3"},
                                        {"SLURM_ARRAY_TASK_COUNT", "3"},
                                        {"SLURM_ARRAY_TASK_MIN", "0"},
                                        {"SLURM_ARRAY_TASK_MAX", "5"},
                                        {"SLURM_ARRAY_TASK_STEP", "1"}}),
                                 std::nullopt);
        })
            .find("the array's task ids are a list, not a range A-B or A-B:STEP, so task 3 has no "
                  "shard index; submit --array=0-2") != std::string::npos);
}

TEST_CASE("--shard auto reads a Kubernetes Indexed Job with its count", "[sweep][shard]") {
  const Shard given = shard_from_environment(table({{"JOB_COMPLETION_INDEX", "2"}}), 5);
  CHECK(given.index == 2);
  CHECK(given.count == 5);
  const Shard from_env = shard_from_environment(
      table({{"JOB_COMPLETION_INDEX", "0"}, {"CORSA_SHARD_COUNT", "3"}}), std::nullopt);
  CHECK(from_env.count == 3);
  CHECK(error_of([] {
          shard_from_environment(table({{"JOB_COMPLETION_INDEX", "1"}}), std::nullopt);
        }).find("--shard-count") != std::string::npos);
  CHECK(error_of([] {
          shard_from_environment(table({{"JOB_COMPLETION_INDEX", "7"}}), 4);
        }).find("not below the shard count 4") != std::string::npos);
  CHECK(error_of([] {
          shard_from_environment(table({}), std::nullopt);
        }).find("--shard auto: error: found neither SLURM_ARRAY_TASK_ID") == 0);
}
