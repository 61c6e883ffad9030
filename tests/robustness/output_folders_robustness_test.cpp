// Writes stay inside the output folder given, one writer at a time, and what a killed run left
// is cleaned by the next: a planted symbolic link inside a sweep folder or a shard is refused
// (never followed), a folder another corsa writes into is refused, a stale lock or temporary of
// a killed process is taken over or removed, and an interrupted sweep stops cleanly for --resume.

#include <signal.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "bounded_run.h"
#include "corsa/core/output_lock.h"

namespace corsa::test {
namespace {

namespace fs = std::filesystem;

const std::string kSuiteScenario = "scenarios/suites/regression/cut_in.xosc";

/// A four-variant sweep of `kSuiteScenario` into `out` (shard `shard` of 2 when given).
std::vector<std::string> small_sweep(const fs::path& out, const std::string& shard = {}) {
  std::vector<std::string> args{"sweep", kSuiteScenario, "--param", "Ego_Speed=20:23:1",
                                "-o",    out.string(),   "--quiet", "--duration",
                                "0.5",   "-j",           "1"};
  if (!shard.empty()) {
    args.insert(args.end(), {"--shard", shard});
  }
  return args;
}

/// Every file below `folder` (symbolic links not followed), relative.
std::set<std::string> files_below(const fs::path& folder) {
  std::set<std::string> names;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    if (!entry.is_directory()) names.insert(fs::relative(entry.path(), folder).string());
  }
  return names;
}

TEST_CASE("A symbolic link planted inside a sweep folder is refused, its target untouched",
          "[robustness][sweep][output]") {
  TempDir dir;
  fs::create_directories(dir.path() / "target");
  fs::create_directories(dir.path() / "out");
  fs::create_directory_symlink(dir.path() / "target", dir.path() / "out" / "variants");
  const BoundedResult planted = run_bounded(small_sweep(dir.path() / "out"));
  INFO(describe("sweep -o with a planted variants link", planted));
  CHECK(planted.exit_code == 2);
  CHECK(planted.err.find("out/variants: error: is a symbolic link inside the output folder") !=
        std::string::npos);
  CHECK(fs::is_empty(dir.path() / "target"));
  CHECK_FALSE(fs::exists(dir.path() / "out" / "sweep.json"));

  // The same for one variant's folder, planted before --resume.
  fs::remove(dir.path() / "out" / "variants");
  REQUIRE(run_bounded(small_sweep(dir.path() / "out")).exit_code == 0);
  fs::remove_all(dir.path() / "out" / "variants" / "2");
  fs::remove(dir.path() / "out" / "summary.csv");
  fs::create_directory_symlink(dir.path() / "target", dir.path() / "out" / "variants" / "2");
  std::vector<std::string> resume = small_sweep(dir.path() / "out");
  resume.push_back("--resume");
  const BoundedResult resumed = run_bounded(resume);
  INFO(describe("sweep --resume with a planted variant link", resumed));
  CHECK(resumed.exit_code == 2);
  CHECK(resumed.err.find("variants/2: error: is a symbolic link") != std::string::npos);
  CHECK(fs::is_empty(dir.path() / "target"));
}

/// Two finished shards of the four-variant sweep in dir/s0 and dir/s1.
void make_shards(const TempDir& dir) {
  for (const char* k : {"0", "1"}) {
    const BoundedResult result =
        run_bounded(small_sweep(dir.path() / (std::string("s") + k), std::string(k) + "/2"));
    INFO(describe(std::string("shard ") + k, result));
    REQUIRE(result.exit_code == 0);
  }
}

std::vector<std::string> merge_args(const TempDir& dir) {
  return {"sweep",
          "merge",
          (dir.path() / "merged").string(),
          (dir.path() / "s0").string(),
          (dir.path() / "s1").string(),
          "--quiet"};
}

TEST_CASE("merge --force replaces an earlier sweep only, never a folder of the user's",
          "[robustness][sweep][output]") {
  TempDir dir;
  make_shards(dir);
  std::vector<std::string> forced = merge_args(dir);
  forced.push_back("--force");
  const fs::path merged = dir.path() / "merged";
  fs::create_directories(merged / "figures");
  std::ofstream(merged / "thesis.tex") << "\\documentclass{article}\n";
  std::ofstream(merged / "figures" / "plot.png") << "png";
  const BoundedResult user = run_bounded(forced);
  INFO(describe("merge --force onto a user's folder", user));
  CHECK(user.exit_code == 2);
  CHECK(user.err.find(merged.string() +
                      ": error: --force replaces only an earlier sweep or "
                      "merge (a folder with Corsa's sweep.json); this folder has none, and "
                      "nothing was removed") != std::string::npos);
  CHECK(files_below(merged) == std::set<std::string>{"figures/plot.png", "thesis.tex"});

  // An earlier merge is replaced; the same with a file of the user's added is refused.
  fs::remove_all(merged);
  REQUIRE(run_bounded(merge_args(dir)).exit_code == 0);
  const std::set<std::string> merge_files = files_below(merged);
  CHECK(run_bounded(forced).exit_code == 0);
  CHECK(files_below(merged) == merge_files);
  std::ofstream(merged / "variants" / "1" / "notes.txt") << "mine";
  const BoundedResult added = run_bounded(forced);
  INFO(describe("merge --force onto a merge with a user's file", added));
  CHECK(added.exit_code == 2);
  CHECK(added.err.find(merged.string() +
                       ": error: --force replaces only an earlier sweep or "
                       "merge, and this folder also holds 1 entry a sweep does not write "
                       "(variants/1/notes.txt); nothing was removed") != std::string::npos);
  CHECK(slurp(merged / "variants" / "1" / "notes.txt") == "mine");
  CHECK(fs::exists(merged / "summary.csv"));
}

TEST_CASE("sweep --force removes only what the earlier sweep's own index accounts for",
          "[robustness][sweep][output]") {
  TempDir dir;
  const fs::path out = dir.path() / "out";
  std::vector<std::string> forced = small_sweep(out);
  forced.push_back("--force");
  REQUIRE(run_bounded(small_sweep(out)).exit_code == 0);
  const std::set<std::string> sweep_files = files_below(out);
  // An earlier sweep alone, and with a killed run's temporary, is replaced file by file.
  std::ofstream(out / "variants" / "2" / ".trajectory.csv.tmp.99999.3") << "half";
  const BoundedResult replaced = run_bounded(forced);
  INFO(describe("sweep --force onto an earlier sweep", replaced));
  CHECK(replaced.exit_code == 0);
  CHECK(files_below(out) == sweep_files);

  // A file of the user's in variants/ (the whole folder used to be removed with it), in a
  // variant's folder, or a variant folder beyond sweep.json's count: refused, nothing removed.
  const std::string refusal = out.string() +
                              ": error: --force replaces only an earlier sweep or merge, and "
                              "this folder also holds 1 entry a sweep does not write (";
  for (const std::string planted :
       {"variants/notes.txt", "variants/1/plot.png", "variants/99/result.csv"}) {
    fs::create_directories((out / planted).parent_path());
    std::ofstream(out / planted) << "mine";
    const BoundedResult user = run_bounded(forced);
    INFO(describe("sweep --force with " + planted, user));
    CHECK(user.exit_code == 2);
    CHECK(user.err.find(refusal + (planted == "variants/99/result.csv" ? "variants/99" : planted) +
                        "); nothing was removed") != std::string::npos);
    CHECK(slurp(out / planted) == "mine");
    std::set<std::string> expected = sweep_files;
    expected.insert(planted);
    CHECK(files_below(out) == expected);
    fs::remove(out / planted);
    if (planted == "variants/99/result.csv") fs::remove(out / "variants" / "99");
  }

  // A sweep.json that is not Corsa's: nothing of the folder is an earlier sweep.
  std::ofstream(out / "sweep.json", std::ios::trunc) << "{\"my\": \"notes\"}\n";
  const BoundedResult foreign = run_bounded(forced);
  INFO(describe("sweep --force onto a folder with a sweep.json of the user's", foreign));
  CHECK(foreign.exit_code == 2);
  CHECK(foreign.err.find(out.string() +
                         ": error: --force replaces only an earlier sweep or merge (a folder "
                         "with Corsa's sweep.json); this folder has none, and nothing was "
                         "removed") != std::string::npos);
  CHECK(files_below(out) == sweep_files);
}

TEST_CASE("A merge of shards claiming 1e15 variants ends at once", "[robustness][sweep]") {
  TempDir dir;
  make_shards(dir);
  for (const char* shard : {"s0", "s1"}) {
    const fs::path description = dir.path() / shard / "sweep.json";
    std::string text = slurp(description);
    const size_t at = text.find("\"variants\": 4,");
    REQUIRE(at != std::string::npos);
    text.replace(at, 14, "\"variants\": 1000000000000000,");
    std::ofstream(description, std::ios::trunc) << text;
  }
  const BoundedResult result = run_bounded(merge_args(dir), 10);
  INFO(describe("merge of 1e15 claimed variants", result));
  CHECK_FALSE(result.timed_out);
  CHECK(result.exit_code == 2);
  CHECK(result.err.find("999999999999996 of 1000000000000000 variants are in none of the shards "
                        "(e.g. 4, 5, 6, 7, 8, 9, 10, 11, 12, 13)") != std::string::npos);
  CHECK_FALSE(fs::exists(dir.path() / "merged"));
}

TEST_CASE("A sweep.json holding a number beyond the range of doubles is located bad input",
          "[robustness][sweep]") {
  TempDir dir;
  make_shards(dir);
  const fs::path description = dir.path() / "s1" / "sweep.json";
  std::string text = slurp(description);
  const size_t at = text.find("\"seed\": 0,");
  REQUIRE(at != std::string::npos);
  text.replace(at, 10, "\"seed\": 117e401,");
  std::ofstream(description, std::ios::trunc) << text;
  const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
  const std::string located = description.string() + ":" + std::to_string(line) +
                              ": error: not valid JSON: number overflow parsing '117e401'";
  // The merge reads it (exit 3, an uncaught exception, before).
  const BoundedResult merged = run_bounded(merge_args(dir));
  INFO(describe("merge of a shard whose sweep.json holds 117e401", merged));
  CHECK(merged.exit_code == 2);
  CHECK(merged.err.find(located) != std::string::npos);
  CHECK_FALSE(fs::exists(dir.path() / "merged"));
  // So does --resume of that shard.
  fs::remove(dir.path() / "s1" / "summary.csv");
  std::vector<std::string> resume = small_sweep(dir.path() / "s1", "1/2");
  resume.push_back("--resume");
  const BoundedResult resumed = run_bounded(resume);
  INFO(describe("--resume of a shard whose sweep.json holds 117e401", resumed));
  CHECK(resumed.exit_code == 2);
  CHECK(resumed.err.find(located) != std::string::npos);
}

TEST_CASE("A merge never follows a symbolic link in a shard nor carries stale temporaries",
          "[robustness][sweep][output]") {
  TempDir dir;
  make_shards(dir);
  std::ofstream(dir.path() / "secret.txt") << "not a trajectory\n";
  const fs::path planted = dir.path() / "s1" / "variants" / "1" / "trajectory.csv";
  fs::remove(planted);
  fs::create_symlink(dir.path() / "secret.txt", planted);
  const BoundedResult linked = run_bounded(merge_args(dir));
  INFO(describe("merge with a planted trajectory link", linked));
  CHECK(linked.exit_code == 2);
  CHECK(linked.err.find(planted.string() + ": error: is a symbolic link") != std::string::npos);
  CHECK_FALSE(fs::exists(dir.path() / "merged"));

  // A temporary a killed run left in a finished variant's folder, and a stray file: neither is
  // part of the sweep, so neither is merged.
  fs::remove(planted);
  std::ofstream(dir.path() / "s0" / "variants" / "0" / ".trajectory.csv.tmp.99999.3") << "half";
  std::ofstream(dir.path() / "s0" / "variants" / "2" / "notes.txt") << "mine";
  const BoundedResult merged = run_bounded(merge_args(dir));
  INFO(describe("merge", merged));
  CHECK(merged.exit_code == 0);
  CHECK(files_below(dir.path() / "merged") ==
        std::set<std::string>{
            "summary.csv", "sweep.json", "variants/0/result.csv", "variants/0/summary.json",
            "variants/0/trajectory.csv", "variants/1/result.csv", "variants/1/summary.json",
            "variants/2/result.csv", "variants/2/summary.json", "variants/2/trajectory.csv",
            "variants/3/result.csv", "variants/3/summary.json", "variants/3/trajectory.csv"});
}

TEST_CASE("A folder another corsa writes into is refused; a killed writer's lock is taken over",
          "[robustness][sweep][output]") {
  TempDir dir;
  const fs::path out = dir.path() / "out";
  fs::create_directory(out);
  {
    // This process plays the other writer.
    const OutputLock held(out);
    const BoundedResult refused = run_bounded(small_sweep(out));
    INFO(describe("sweep into a locked folder", refused));
    CHECK(refused.exit_code == 2);
    CHECK(refused.err.find(out.string() + ": error: another corsa (pid ") != std::string::npos);
    CHECK(refused.err.find("is writing into this folder") != std::string::npos);
    CHECK(entry_names(out) == std::set<std::string>{".corsa.lock"});
    TempDir shards;
    make_shards(shards);
    const BoundedResult merge =
        run_bounded({"sweep", "merge", out.string(), (shards.path() / "s0").string(),
                     (shards.path() / "s1").string(), "--force", "--quiet"});
    INFO(describe("merge --force onto a locked folder", merge));
    CHECK(merge.exit_code == 2);
    CHECK(merge.err.find("is writing into this folder") != std::string::npos);
  }
  // What a killed writer leaves: the lock file, its flock gone with the process.
  std::ofstream(out / ".corsa.lock") << "pid 999999 on host elsewhere\n";
  const BoundedResult taken = run_bounded(small_sweep(out));
  INFO(describe("sweep into a folder with a stale lock", taken));
  CHECK(taken.exit_code == 0);
  CHECK_FALSE(fs::exists(out / ".corsa.lock"));
  CHECK(fs::exists(out / "summary.csv"));
}

TEST_CASE("SIGINT stops a sweep after the variants in progress, and --resume finishes it",
          "[robustness][sweep][interrupt]") {
  TempDir dir;
  const fs::path out = dir.path() / "out";
  // 40 variants of about 0.1 s each at a 0.5 ms step.
  const std::vector<std::string> args{"sweep",  kSuiteScenario, "--param", "Ego_Speed=20:39.5:0.5",
                                      "-o",     out.string(),   "--quiet", "--dt",
                                      "0.0005", "-j",           "1",       "--no-trajectories"};
  const pid_t child = spawn_corsa(args, dir.path() / "stderr");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  std::error_code error;
  while (!fs::exists(out / "variants" / "1" / "result.csv", error) &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  REQUIRE(kill(child, SIGINT) == 0);
  CHECK(wait_corsa(child) == 128 + SIGINT);
  const std::string err = slurp(dir.path() / "stderr");
  INFO(err);
  CHECK(err.find("corsa sweep: interrupted by SIGINT; " + out.string() + " holds ") !=
        std::string::npos);
  CHECK(err.find("of 40 variants, complete (finish with --resume)") != std::string::npos);
  // Unfinished: no summary.csv, no lock, no temporary; every variant folder made is complete.
  CHECK_FALSE(fs::exists(out / "summary.csv"));
  CHECK_FALSE(fs::exists(out / ".corsa.lock"));
  size_t done = 0;
  for (const auto& variant : fs::directory_iterator(out / "variants")) {
    CHECK(entry_names(variant.path()) == std::set<std::string>{"result.csv", "summary.json"});
    ++done;
  }
  CHECK(done >= 2);
  CHECK(done < 40);
  std::vector<std::string> resume = args;
  resume.push_back("--resume");
  const BoundedResult resumed = run_bounded(resume, 60);
  INFO(describe("--resume", resumed));
  CHECK(resumed.exit_code == 0);
  const std::string summary = slurp(out / "summary.csv");
  CHECK(std::count(summary.begin(), summary.end(), '\n') == 41);  // header and 40 variants
}

TEST_CASE("Temporaries a SIGKILLed run left are removed by the next run of the same output",
          "[robustness][output][interrupt]") {
  TempDir dir;
  // cut_in without its stop conditions: runs until --duration, long enough to be killed. The
  // engine runs this scenario at over 20,000x real time, so the delay and the duration are far
  // beyond any time it reaches before the kill (an hour of wall time or more).
  std::string scenario = cut_in_text();
  for (const auto& [from, to] :
       {std::pair<std::string, std::string>{"delay=\"5\"", "delay=\"500000000\""},
        std::pair<std::string, std::string>{"value=\"60\" rule", "value=\"1e6\" rule"}}) {
    const size_t at = scenario.find(from);
    REQUIRE(at != std::string::npos);
    scenario.replace(at, from.size(), to);
  }
  std::ofstream(dir.path() / "endless.xosc") << scenario;
  const fs::path out = dir.path() / "out";
  const pid_t child =
      spawn_corsa({"run", (dir.path() / "endless.xosc").string(), "--quiet", "--duration",
                   "100000000", "--record", (out / "trajectories.csv").string()},
                  dir.path() / "stderr");
  const auto temporaries = [&] {
    size_t count = 0;
    std::error_code error;
    for (fs::directory_iterator it(out, error), end; !error && it != end; it.increment(error)) {
      count += it->path().filename().string().starts_with(".trajectories.csv.tmp.") ? 1 : 0;
    }
    return count;
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (temporaries() == 0 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  REQUIRE(kill(child, SIGKILL) == 0);
  CHECK(wait_corsa(child) == -1);
  REQUIRE(temporaries() == 1);
  const BoundedResult next = run_bounded(
      {"run", kSuiteScenario, "--quiet", "--record", (out / "trajectories.csv").string()});
  INFO(describe("the next run into the same folder", next));
  CHECK(next.exit_code == 0);
  CHECK(temporaries() == 0);
  CHECK(entry_names(out) == std::set<std::string>{"trajectories.csv"});
}

TEST_CASE("Two runs writing into one folder at once both succeed with whole files",
          "[robustness][output][race]") {
  TempDir dir;
  const fs::path out = dir.path() / "out";
  const std::vector<std::string> common{"run", kSuiteScenario, "--quiet", "--duration", "1"};
  const auto args = [&](const std::string& record) {
    std::vector<std::string> all = common;
    for (const std::string& arg : {std::string("--record"), (out / record).string(),
                                   std::string("--summary"), (out / "summary.json").string()}) {
      all.push_back(arg);
    }
    return all;
  };
  std::vector<std::string> alone = common;
  alone.insert(alone.end(), {"--record", (dir.path() / "alone.csv").string()});
  REQUIRE(run_bounded(alone).exit_code == 0);
  const std::string expected = slurp(dir.path() / "alone.csv");
  // Each run cleans the folder of killed runs' temporaries as it starts, while the other may be
  // creating its own there: that temporary must never be taken for a stale one.
  for (int round = 0; round < 40; ++round) {
    const pid_t a = spawn_corsa(args("a.csv"), dir.path() / "a.err");
    const pid_t b = spawn_corsa(args("b.csv"), dir.path() / "b.err");
    const int a_exit = wait_corsa(a);
    const int b_exit = wait_corsa(b);
    INFO("round " << round << ": " << slurp(dir.path() / "a.err") << slurp(dir.path() / "b.err"));
    REQUIRE(a_exit == 0);
    REQUIRE(b_exit == 0);
    CHECK(slurp(out / "a.csv") == expected);
    CHECK(slurp(out / "b.csv") == expected);
    // One name both write: whole, from whichever run renamed it last.
    const std::string summary = slurp(out / "summary.json");
    CHECK(summary.starts_with("{"));
    CHECK(summary.ends_with("}\n"));
    CHECK(entry_names(out) == std::set<std::string>{"a.csv", "b.csv", "summary.json"});
  }
}

TEST_CASE("sweep --resume removes the temporaries a killed run left in its variants",
          "[robustness][sweep][interrupt]") {
  TempDir dir;
  const fs::path out = dir.path() / "out";
  REQUIRE(run_bounded(small_sweep(out)).exit_code == 0);
  const std::set<std::string> sweep_files = files_below(out);
  // A variant the killed run finished, with its temporary left behind, and one it did not finish.
  std::ofstream(out / "variants" / "2" / ".trajectory.csv.tmp.99999.3") << "half";
  std::ofstream(out / "variants" / "3" / ".result.csv.tmp.99999.4") << "half";
  fs::remove(out / "variants" / "3" / "result.csv");
  std::vector<std::string> resume = small_sweep(out);
  resume.push_back("--resume");
  const BoundedResult resumed = run_bounded(resume);
  INFO(describe("sweep --resume over a killed run's temporaries", resumed));
  CHECK(resumed.exit_code == 0);
  CHECK(files_below(out) == sweep_files);
}

}  // namespace
}  // namespace corsa::test
