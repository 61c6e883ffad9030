// `corsa sweep` end to end: shards as separate processes merged back, environment-driven shards,
// located errors, exit codes, and a variant rerun alone with `corsa run`.

#include <stdlib.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>

#include "corsa/core/atomic_file.h"
#include "run_corsa.h"
#include "sweep_fixtures.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using corsa::read_file;
using corsa::sweep::test::csv_rows;
using corsa::sweep::test::fixture;
using corsa::sweep::test::summary_without_wall_time;
using corsa::sweep::test::without_timing;
using corsa::test::run_corsa;
using corsa::test::shell_quote;
using corsa::test::TempDir;

namespace {

// Every file under `folder`, relative, sorted.
std::vector<std::string> files_under(const fs::path& folder) {
  std::vector<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    if (entry.is_regular_file()) files.push_back(fs::relative(entry.path(), folder).string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Sets environment variables for the child processes of one test, and removes them again.
class ScopedEnvironment {
 public:
  explicit ScopedEnvironment(std::initializer_list<std::pair<std::string, std::string>> values)
      : values_(values) {
    for (const auto& [name, value] : values_) ::setenv(name.c_str(), value.c_str(), 1);
  }
  ScopedEnvironment(const ScopedEnvironment&) = delete;
  ScopedEnvironment& operator=(const ScopedEnvironment&) = delete;
  ~ScopedEnvironment() {
    for (const auto& [name, value] : values_) ::unsetenv(name.c_str());
  }

 private:
  std::vector<std::pair<std::string, std::string>> values_;
};

}  // namespace

TEST_CASE("four shards run as processes merge into the unsharded sweep", "[sweep][cli][shard]") {
  TempDir dir;
  const std::string dist = fixture("stochastic.xosc").string();
  // The four shards at the same time, each its own process (as a job array would start them).
  std::string command = "cd " + shell_quote(CORSA_SOURCE_DIR) + " && (";
  for (int k = 0; k < 4; ++k) {
    command += shell_quote(CORSA_BINARY) + " sweep " + shell_quote(dist) + " --shard " +
               std::to_string(k) + "/4 -j 1 --record-every 5 -o " +
               shell_quote((dir.path() / ("shard-" + std::to_string(k))).string()) +
               " >/dev/null 2>&1 & ";
  }
  command += "wait)";
  REQUIRE(std::system(command.c_str()) == 0);
  for (int k = 0; k < 4; ++k) {
    const fs::path shard = dir.path() / ("shard-" + std::to_string(k));
    REQUIRE(fs::exists(shard / "summary.csv"));
    CHECK(csv_rows(shard / "summary.csv").size() == 5);  // header + 4 of 16
    CHECK(read_file(shard / "shard.json").find("\"shard\": \"" + std::to_string(k) + "/4\"") !=
          std::string::npos);
  }
  std::vector<std::string> merge = {"sweep", "merge", (dir.path() / "merged").string()};
  for (int k = 3; k >= 0; --k)
    merge.push_back((dir.path() / ("shard-" + std::to_string(k))).string());
  const auto merged = run_corsa(merge);
  REQUIRE(merged.exit_code == 0);
  CHECK(merged.out.find("merged 4 shards") != std::string::npos);

  const auto whole = run_corsa({"sweep", dist, "-j2", "--record-every", "5", "-o",
                                (dir.path() / "whole").string(), "--quiet"});
  REQUIRE(whole.exit_code == 0);
  CHECK(whole.out.empty());
  CHECK(summary_without_wall_time(dir.path() / "merged") ==
        summary_without_wall_time(dir.path() / "whole"));
  CHECK(read_file(dir.path() / "merged" / "sweep.json") ==
        read_file(dir.path() / "whole" / "sweep.json"));
  const auto files = files_under(dir.path() / "whole");
  CHECK(files == files_under(dir.path() / "merged"));
  for (const auto& file : files) {
    const std::string a = read_file(dir.path() / "whole" / file);
    const std::string b = read_file(dir.path() / "merged" / file);
    if (file.ends_with("trajectory.csv")) {
      CHECK(a == b);
    } else if (file.ends_with("summary.json")) {
      CHECK(without_timing(a) == without_timing(b));
    }
  }
}

TEST_CASE("merging refuses incomplete or foreign shards", "[sweep][cli][shard]") {
  TempDir dir;
  const std::string dist = fixture("grid.xosc").string();
  for (int k = 0; k < 2; ++k) {
    REQUIRE(run_corsa({"sweep", dist, "--shard", std::to_string(k) + "/3", "--no-trajectories",
                       "-o", (dir.path() / std::to_string(k)).string()})
                .exit_code == 0);
  }
  const auto missing = run_corsa({"sweep", "merge", (dir.path() / "m").string(),
                                  (dir.path() / "0").string(), (dir.path() / "1").string()});
  CHECK(missing.exit_code == 2);
  CHECK(missing.err.find("4 of 12 variants are in none of the shards (e.g. 2, 5, 8, 11)") !=
        std::string::npos);
  CHECK_FALSE(fs::exists(dir.path() / "m"));
  REQUIRE(run_corsa({"sweep", fixture("stochastic.xosc").string(), "--shard", "2/3",
                     "--no-trajectories", "-o", (dir.path() / "2").string()})
              .exit_code == 0);
  const auto foreign = run_corsa({"sweep", "merge", (dir.path() / "m").string(),
                                  (dir.path() / "0").string(), (dir.path() / "2").string()});
  CHECK(foreign.exit_code == 2);
  CHECK(foreign.err.find("holds another sweep") != std::string::npos);
  const auto none =
      run_corsa({"sweep", "merge", (dir.path() / "m").string(), (dir.path() / "nothing").string()});
  CHECK(none.exit_code == 2);
}

TEST_CASE("merging leaves out the temporaries of a run killed while writing",
          "[sweep][cli][shard]") {
  TempDir dir;
  const std::string dist = fixture("grid.xosc").string();
  for (int k = 0; k < 2; ++k) {
    REQUIRE(run_corsa({"sweep", dist, "--shard", std::to_string(k) + "/2", "--record-every", "50",
                       "-o", (dir.path() / std::to_string(k)).string(), "--quiet"})
                .exit_code == 0);
  }
  // What a task killed half-way through a trajectory leaves, beside the file of its rerun.
  const fs::path variant = dir.path() / "1" / "variants" / "3";
  corsa::write_file_atomic(variant / ".trajectory.csv.tmp.4242.0", "time,entity\n0,Ego");
  const auto merged = run_corsa({"sweep", "merge", (dir.path() / "m").string(),
                                 (dir.path() / "0").string(), (dir.path() / "1").string()});
  REQUIRE(merged.exit_code == 0);
  CHECK(files_under(dir.path() / "m" / "variants" / "3") ==
        std::vector<std::string>{"result.csv", "summary.json", "trajectory.csv"});
  CHECK(read_file(dir.path() / "m" / "variants" / "3" / "trajectory.csv") ==
        read_file(variant / "trajectory.csv"));
}

TEST_CASE("--shard auto takes the shard from a Slurm job array", "[sweep][cli][shard]") {
  TempDir dir;
  const ScopedEnvironment slurm({{"SLURM_ARRAY_TASK_ID", "1"}, {"SLURM_ARRAY_TASK_COUNT", "2"}});
  const auto result = run_corsa({"sweep", fixture("grid.xosc").string(), "--shard", "auto",
                                 "--no-trajectories", "-o", dir.path().string()});
  REQUIRE(result.exit_code == 0);
  CHECK(read_file(dir.path() / "shard.json").find("\"shard\": \"1/2\"") != std::string::npos);
  const auto rows = csv_rows(dir.path() / "summary.csv");
  REQUIRE(rows.size() == 7);
  CHECK(rows[1][0] == "1");
  CHECK(rows[6][0] == "11");
}

TEST_CASE("--shard auto takes a Kubernetes completion index with --shard-count",
          "[sweep][cli][shard]") {
  TempDir dir;
  const ScopedEnvironment k8s({{"JOB_COMPLETION_INDEX", "2"}});
  const auto result =
      run_corsa({"sweep", fixture("grid.xosc").string(), "--shard", "auto", "--shard-count", "4",
                 "--no-trajectories", "-o", dir.path().string()});
  REQUIRE(result.exit_code == 0);
  const auto rows = csv_rows(dir.path() / "summary.csv");
  REQUIRE(rows.size() == 4);
  CHECK(rows[1][0] == "2");
  CHECK(rows[3][0] == "10");
  const auto no_count = run_corsa({"sweep", fixture("grid.xosc").string(), "--shard", "auto", "-o",
                                   (dir.path() / "x").string()});
  CHECK(no_count.exit_code == 2);
  CHECK(no_count.err.find("--shard auto: error:") != std::string::npos);
}

TEST_CASE("bad sweep input is located and exits 2", "[sweep][cli][errors]") {
  TempDir dir;
  const auto undeclared = run_corsa(
      {"sweep", fixture("undeclared.xosc").string(), "--strict", "-o", dir.path().string()});
  CHECK(undeclared.exit_code == 2);
  CHECK(undeclared.err.find("undeclared.xosc:10: error: parameter 'Wind_Speed' is not declared") !=
        std::string::npos);
  const auto empty = run_corsa({"sweep", fixture("follow.xosc").string(), "--param",
                                "Ego_Speed=40:20:5", "-o", dir.path().string()});
  CHECK(empty.exit_code == 2);
  CHECK(empty.err.find("--param Ego_Speed=40:20:5: error: empty range") != std::string::npos);
  const auto range =
      run_corsa({"sweep", fixture("empty_range.xosc").string(), "-o", dir.path().string()});
  CHECK(range.exit_code == 2);
  CHECK(range.err.find("empty_range.xosc:8: error:") != std::string::npos);
  const auto usage = run_corsa({"sweep", fixture("grid.xosc").string(), "-j", "0"});
  CHECK(usage.exit_code == 2);
  CHECK(dir.entries() == 0);
}

TEST_CASE("a distribution without variants is refused by corsa run as by corsa sweep",
          "[sweep][cli][errors]") {
  TempDir dir;
  const std::string dist = fixture("no_runs.xosc").string();
  const std::string located =
      "no_runs.xosc:7: error: numberOfTestRuns is 0: the distribution has no variants";
  const auto sweep = run_corsa({"sweep", dist, "-o", (dir.path() / "sweep").string()});
  CHECK(sweep.exit_code == 2);
  CHECK(sweep.err.find(located) != std::string::npos);
  // `corsa run` reads a distribution as its first variant, and there is none.
  const auto run =
      run_corsa({"run", dist, "--record", (dir.path() / "run.csv").string(), "--quiet"});
  CHECK(run.exit_code == 2);
  CHECK(run.err.find(located) != std::string::npos);
  CHECK(run.err.find("first variant") == std::string::npos);
  CHECK(dir.entries() == 0);
}

TEST_CASE("a distribution parameter the scenario lacks is not varied, with a warning",
          "[sweep][cli]") {
  TempDir dir;
  const auto result =
      run_corsa({"sweep", fixture("undeclared.xosc").string(), "-o", dir.path().string()});
  CHECK(result.exit_code == 0);
  CHECK(result.out.find("swept 2 variants") != std::string::npos);
  CHECK(result.err.find("undeclared.xosc:10: warning: parameter 'Wind_Speed' is not declared") !=
        std::string::npos);
}

TEST_CASE("variants outside the scenario's value constraints are skipped, not failed",
          "[sweep][cli]") {
  TempDir dir;
  const auto result = run_corsa({"sweep", fixture("follow.xosc").string(), "--param",
                                 "Brake_Rate=-1,4", "-o", dir.path().string()});
  CHECK(result.exit_code == 0);
  CHECK(result.out.find("1 skipped") != std::string::npos);
  CHECK(result.out.find("0 failed") != std::string::npos);
  const std::string table = corsa::read_file(dir.path() / "summary.csv");
  CHECK(table.find(",skipped,0,") != std::string::npos);
  CHECK(table.find("violates its value constraints") != std::string::npos);
}

TEST_CASE("failed variants make the sweep exit 1 and are listed", "[sweep][cli]") {
  TempDir dir;
  const auto result = run_corsa({"sweep", fixture("follow.xosc").string(), "--param", "Lane=-2,-9",
                                 "-o", dir.path().string()});
  CHECK(result.exit_code == 1);
  CHECK(result.out.find("swept 2 variants") != std::string::npos);
  CHECK(result.out.find("1 failed") != std::string::npos);
  CHECK(result.err.find("variant 1 failed: ") != std::string::npos);
}

TEST_CASE("a variant reruns alone with corsa run and gives the same trajectory", "[sweep][cli]") {
  TempDir dir;
  const std::string scenario = fixture("follow.xosc").string();
  REQUIRE(run_corsa({"sweep", scenario, "--param", "Ego_Speed=22:28:3", "--param", "Gap=35",
                     "--seed", "5", "--record-every", "4", "-o", (dir.path() / "s").string()})
              .exit_code == 0);
  const auto alone = run_corsa({"run", scenario, "--param", "Ego_Speed=25", "--param", "Gap=35",
                                "--seed", "5", "--record-every", "4", "--record",
                                (dir.path() / "alone.csv").string(), "--quiet"});
  REQUIRE(alone.exit_code == 0);
  CHECK(read_file(dir.path() / "alone.csv") ==
        read_file(dir.path() / "s" / "variants" / "1" / "trajectory.csv"));
}
