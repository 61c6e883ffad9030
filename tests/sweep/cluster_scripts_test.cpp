// The cluster scripts without a cluster: scripts/slurm/sweep.sbatch run by bash with the variables
// Slurm sets for an array task, deploy/k8s/sweep-pod.sh run by /bin/sh with the ones Kubernetes
// sets for an Indexed Job pod, and the Job templates they go with. tests/cluster runs the Slurm
// script on a real Slurm.

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>

#include "corsa/core/atomic_file.h"
#include "run_corsa.h"
#include "sweep_fixtures.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using corsa::read_file;
using corsa::sweep::test::csv_rows;
using corsa::sweep::test::fixture;
using corsa::sweep::test::summary_without_wall_time;
using corsa::test::ProcessResult;
using corsa::test::shell_quote;
using corsa::test::slurp;
using corsa::test::TempDir;

namespace {

// Runs `shell script args` from the source tree with `environment` ("NAME=value ..."), CORSA
// set to the built binary; captures both streams.
ProcessResult run_script(const std::string& shell, const std::string& script,
                         const std::string& environment, const std::string& args) {
  TempDir logs;
  const std::string command = "cd " + shell_quote(CORSA_SOURCE_DIR) +
                              " && env CORSA=" + shell_quote(CORSA_BINARY) + " " + environment +
                              " " + shell + " " + script + " " + args + " >" +
                              shell_quote((logs.path() / "out").string()) + " 2>" +
                              shell_quote((logs.path() / "err").string()) + " </dev/null";
  const int status = std::system(command.c_str());
  ProcessResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = slurp(logs.path() / "out");
  result.err = slurp(logs.path() / "err");
  return result;
}

// Array task `id` of an array with the given min, max, count (and step 1), as Slurm starts it.
ProcessResult slurm_task(int id, int min, int max, int count, const fs::path& out,
                         const std::string& step = "1") {
  std::ostringstream environment;
  environment << "SLURM_ARRAY_JOB_ID=77 SLURM_ARRAY_TASK_ID=" << id
              << " SLURM_ARRAY_TASK_MIN=" << min << " SLURM_ARRAY_TASK_MAX=" << max
              << " SLURM_ARRAY_TASK_COUNT=" << count << " SLURM_ARRAY_TASK_STEP=" << step
              << " SLURM_CPUS_ON_NODE=1";
  return run_script("bash", "scripts/slurm/sweep.sbatch", environment.str(),
                    shell_quote(fixture("grid.xosc").string()) + " " + shell_quote(out.string()) +
                        " --no-trajectories");
}

// A self-contained input folder as run-sweep.sh stages it: the grid distribution, its scenario with
// the map beside it (maps/), and the catalogs.
void stage_inputs(const fs::path& in) {
  fs::create_directories(in / "maps");
  fs::copy(fixture("grid.xosc"), in / "grid.xosc");
  fs::copy(fixture("catalogs"), in / "catalogs", fs::copy_options::recursive);
  fs::copy(fs::path(CORSA_SOURCE_DIR) / "scenarios" / "maps" / "motorway_2km.xodr", in / "maps");
  std::string scenario = read_file(fixture("follow.xosc"));
  const std::string map = "../../../scenarios/maps/";
  REQUIRE(scenario.find(map) != std::string::npos);
  scenario.replace(scenario.find(map), map.size(), "maps/");
  corsa::write_file_atomic(in / "follow.xosc", scenario);
}

// "(shard K/N of V)", as corsa's summary line names a shard.
std::string shard_of(int index, int count, int variants) {
  std::ostringstream text;
  text << "(shard " << index << '/' << count << " of " << variants << ')';
  return text.str();
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("the Slurm script runs task K as shard K of the array's task count",
          "[sweep][cluster][slurm]") {
  TempDir dir;
  const fs::path out = dir.path() / "out";
  for (int task = 0; task < 3; ++task) {
    const auto result = slurm_task(task, 0, 2, 3, out);
    REQUIRE(result.exit_code == 0);
    // The one line a task logs: corsa's summary.
    CHECK(result.err.empty());
    CHECK(contains(result.out, "swept 4 variants " + shard_of(task, 3, 12)));
    CHECK(std::count(result.out.begin(), result.out.end(), '\n') == 1);
  }
  const auto merged = corsa::test::run_corsa(
      {"sweep", "merge", (out / "merged").string(), (out / "shard-0").string(),
       (out / "shard-1").string(), (out / "shard-2").string()});
  REQUIRE(merged.exit_code == 0);
  CHECK(csv_rows(out / "merged" / "summary.csv").size() == 13);
}

TEST_CASE("a resubmitted Slurm task takes the shard count from the shards already there",
          "[sweep][cluster][slurm]") {
  TempDir dir;
  const fs::path out = dir.path() / "out";
  REQUIRE(slurm_task(0, 0, 2, 3, out).exit_code == 0);
  REQUIRE(slurm_task(1, 0, 2, 3, out).exit_code == 0);
  // Task 2 never started; resubmitted alone (sbatch --array=2) it is an array of 1 task from 2,
  // which by itself would read as the whole sweep (shard 0 of 1).
  const auto late = slurm_task(2, 2, 2, 1, out);
  REQUIRE(late.exit_code == 0);
  CHECK(contains(late.out, "swept 4 variants (shard 2/3 of 12)"));
  CHECK(contains(read_file(out / "shard-2" / "shard.json"), "\"shard\": \"2/3\""));
  // Task 1 resubmitted after it finished: it resumes its own shard.
  const auto again = slurm_task(1, 1, 1, 1, out);
  REQUIRE(again.exit_code == 0);
  CHECK(contains(again.out, "(shard 1/3 of 12)"));
  CHECK(contains(again.out, "0 ran, 4 resumed"));
  // A task id that is no shard of the recorded sweep is refused.
  const auto stray = slurm_task(3, 3, 3, 1, out);
  CHECK(stray.exit_code == 2);
  CHECK(
      contains(stray.err, "holds a sweep of 3 shards (tasks 0 to 2), and task 3 is none of them"));
  CHECK_FALSE(fs::exists(out / "shard-3"));
}

TEST_CASE("a Slurm task that cannot know the shard count refuses with the commands that work",
          "[sweep][cluster][slurm]") {
  TempDir dir;
  const fs::path out = dir.path() / "out";
  // Nothing started yet, and the array is not the whole sweep from 0.
  const auto alone = slurm_task(7, 7, 7, 1, out);
  CHECK(alone.exit_code == 2);
  CHECK(contains(alone.err, "the first submission must be the whole array from 0"));
  CHECK(contains(alone.err, "scontrol requeue"));
  const auto single = slurm_task(0, 0, 0, 1, out);
  CHECK(single.exit_code == 2);
  // A step: task 4 of --array=0-6:2 would otherwise be shard 4 of 4.
  const auto stepped = slurm_task(4, 0, 6, 4, out, "2");
  CHECK(stepped.exit_code == 2);
  CHECK(contains(stepped.err, "not consecutive (a step such as --array=0-6:2, or a list)"));
  CHECK(contains(stepped.err, "submit --array=0-3 for 4 shards"));
  // A list (--array=0,3,5): step 1 but ids missing.
  const auto list = slurm_task(3, 0, 5, 3, out);
  CHECK(list.exit_code == 2);
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE(
    "the Kubernetes pod script runs its shard under /bin/sh and the merge equals the "
    "unsharded sweep",
    "[sweep][cluster][kubernetes]") {
  TempDir dir;
  const fs::path sweep_dir = dir.path() / "corsa-sweep-test";
  const std::string inputs = "CORSA_SWEEP_DIR=" + shell_quote(sweep_dir.string()) +
                             " CORSA_DIST=grid.xosc CORSA_SHARD_COUNT=3 CORSA_JOBS=1"
                             " CORSA_SWEEP_ARGS='--record-every 10'";
  stage_inputs(sweep_dir / "in");
  for (int index = 0; index < 3; ++index) {
    const auto pod = run_script("/bin/sh", "deploy/k8s/sweep-pod.sh",
                                inputs + " JOB_COMPLETION_INDEX=" + std::to_string(index), "shard");
    REQUIRE(pod.exit_code == 0);
    CHECK(contains(pod.out, shard_of(index, 3, 12)));
  }
  // A retried pod resumes its shard.
  const auto retried =
      run_script("/bin/sh", "deploy/k8s/sweep-pod.sh", inputs + " JOB_COMPLETION_INDEX=1", "shard");
  REQUIRE(retried.exit_code == 0);
  CHECK(contains(retried.out, "0 ran, 4 resumed"));
  const auto merge = run_script("/bin/sh", "deploy/k8s/sweep-pod.sh", inputs, "merge");
  REQUIRE(merge.exit_code == 0);
  CHECK(contains(merge.out, "merged 3 shards"));

  const auto whole =
      corsa::test::run_corsa({"sweep", (sweep_dir / "in" / "grid.xosc").string(), "--record-every",
                              "10", "-o", (dir.path() / "whole").string(), "--quiet"});
  REQUIRE(whole.exit_code == 0);
  const fs::path merged = sweep_dir / "out" / "merged";
  CHECK(read_file(merged / "sweep.json") == read_file(dir.path() / "whole" / "sweep.json"));
  CHECK(summary_without_wall_time(merged) == summary_without_wall_time(dir.path() / "whole"));
  for (int i = 0; i < 12; ++i) {
    const fs::path file = fs::path("variants") / std::to_string(i) / "trajectory.csv";
    CHECK(read_file(merged / file) == read_file(dir.path() / "whole" / file));
  }
}

TEST_CASE("the Kubernetes pod script exits 2 on bad input, which fails the whole Job",
          "[sweep][cluster][kubernetes]") {
  TempDir dir;
  const std::string base = "CORSA_SWEEP_DIR=" + shell_quote(dir.path().string()) +
                           " CORSA_SHARD_COUNT=2 JOB_COMPLETION_INDEX=0";
  stage_inputs(dir.path() / "in");
  // The exit status podFailurePolicy turns into FailJob.
  const auto bad =
      run_script("/bin/sh", "deploy/k8s/sweep-pod.sh", base + " CORSA_DIST=missing.xosc", "shard");
  CHECK(bad.exit_code == 2);
  CHECK(contains(bad.err, "missing.xosc"));
  const auto unset = run_script("/bin/sh", "deploy/k8s/sweep-pod.sh", base, "shard");
  CHECK(unset.exit_code == 2);
  CHECK(contains(unset.err, "CORSA_DIST is not set"));
  const auto no_shards = run_script("/bin/sh", "deploy/k8s/sweep-pod.sh", base, "merge");
  CHECK(no_shards.exit_code == 2);
  CHECK(contains(no_shards.err, "no shard folder"));
  // A failed variant is recorded, not a failed pod (a retry would fail it again).
  const auto failing =
      run_script("/bin/sh", "deploy/k8s/sweep-pod.sh",
                 base + " CORSA_DIST=grid.xosc CORSA_SWEEP_ARGS='--ego Nobody'", "shard");
  CHECK(failing.exit_code == 0);
  CHECK(contains(failing.out, "6 failed"));
}

TEST_CASE("the Kubernetes Job fails on exit 2 and keeps its shard count in step",
          "[sweep][cluster][kubernetes]") {
  const fs::path k8s = fs::path(CORSA_SOURCE_DIR) / "deploy" / "k8s";
  const std::string job = read_file(k8s / "sweep-job.yaml");
  CHECK(contains(job, "completionMode: Indexed"));
  CHECK(contains(job, "completions: @SHARDS@\n  parallelism: @SHARDS@"));
  CHECK(contains(job, "- name: CORSA_SHARD_COUNT\n              value: \"@SHARDS@\""));
  CHECK(contains(job,
                 "action: FailJob\n        onExitCodes:\n          containerName: corsa\n"
                 "          operator: In\n          values: [2]"));
  CHECK(contains(job, "restartPolicy: Never"));  // podFailurePolicy requires it
  CHECK(contains(job, "claimName: @CLAIM@"));
  CHECK(contains(read_file(k8s / "pvc.yaml"), "ReadWriteMany"));
  // The image ships the pod script where the Jobs run it.
  CHECK(contains(read_file(k8s / "Dockerfile"), "/usr/local/share/corsa/sweep-pod.sh"));
  CHECK(contains(job, "/usr/local/share/corsa/sweep-pod.sh\", \"shard\""));
  CHECK(contains(read_file(k8s / "sweep-merge-job.yaml"),
                 "/usr/local/share/corsa/sweep-pod.sh\", \"merge\""));
  // The wait in run-sweep.sh ends on Failed as well as on Complete.
  const std::string run = read_file(k8s / "run-sweep.sh");
  CHECK(contains(run, "grep -qx Failed"));
  CHECK(contains(run, "grep -qx Complete"));
}
