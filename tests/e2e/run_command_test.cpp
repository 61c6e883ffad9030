// `corsa run` from the command line: options, outputs, exit codes and messages.

#include <algorithm>
#include <iterator>
#include <map>
#include <utility>
#include <vector>

#include "csv_compare.h"
#include "run_corsa.h"

namespace corsa::test {
namespace {

const std::string kCutIn = "scenarios/cut_in.xosc";

TEST_CASE("corsa run --help lists its options", "[e2e][run]") {
  const ProcessResult result = run_corsa({"run", "--help"});
  CHECK(result.exit_code == 0);
  for (const char* option :
       {"--param", "--dt", "--duration", "--seed", "--record", "--record-every", "--record-thread",
        "--summary", "--log", "--quiet"}) {
    CHECK(result.out.find(option) != std::string::npos);
  }
}

TEST_CASE("corsa run prints a one-line summary and exits 0", "[e2e][run]") {
  const ProcessResult result = run_corsa({"run", kCutIn});
  CHECK(result.exit_code == 0);
  CHECK(result.out.find("ended by stop trigger at ") != std::string::npos);
  CHECK(result.out.find(" steps, ") != std::string::npos);
  CHECK(result.out.find("x real time") != std::string::npos);
  CHECK(std::count(result.out.begin(), result.out.end(), '\n') == 1);
}

TEST_CASE("corsa run places GeoPositions through PROJ, loaded for them only", "[e2e][run][geo]") {
  TempDir dir;
  const auto record = dir.path() / "out.csv";
  const ProcessResult result =
      run_corsa({"run", "tests/engine/fixtures/action_teleport_story.xosc", "--quiet", "--duration",
                 "1.5", "--record", record.string()});
  REQUIRE(result.exit_code == 0);
  // The GeoPosition at t = 1 is map point (250, -5.25) (tests/engine/actions_test.cpp).
  const auto rows = parse_trajectory(slurp(record));
  const auto jumped = std::find_if(rows.begin(), rows.end(), [](const TrajectoryRow& r) {
    return r.entity == "Jumper" && r.time == 1.02;
  });
  REQUIRE(jumped != rows.end());
  CHECK(jumped->x == Catch::Detail::Approx(250.0).margin(0.01));
  CHECK(jumped->y == Catch::Detail::Approx(-5.25).margin(0.01));
}

TEST_CASE("corsa run rejects bad usage with exit 2", "[e2e][run]") {
  CHECK(run_corsa({"run"}).exit_code == 2);
  CHECK(run_corsa({"run", kCutIn, "--dt", "0"}).exit_code == 2);
  CHECK(run_corsa({"run", kCutIn, "--record-every", "0"}).exit_code == 2);
  const ProcessResult thread = run_corsa({"run", kCutIn, "--record-thread", "writers"});
  CHECK(thread.exit_code == 2);
  CHECK(thread.err.find("--record-thread expects auto, caller or writer") != std::string::npos);
  CHECK(run_corsa({"run", kCutIn, "--param", "novalue"}).exit_code == 2);
  const ProcessResult unknown = run_corsa({"run", kCutIn, "--param", "NoSuchParameter=1"});
  CHECK(unknown.exit_code == 2);
  CHECK(unknown.err.find("NoSuchParameter") != std::string::npos);
}

TEST_CASE("corsa run reports bad placements with file:line and writes nothing", "[e2e][run]") {
  TempDir dir;
  const auto record = dir.path() / "out.csv";
  const ProcessResult result =
      run_corsa({"run", "tests/engine/fixtures/error_missing_road.xosc", "--record",
                 record.string(), "--summary", (dir.path() / "s.json").string()});
  CHECK(result.exit_code == 2);
  CHECK(result.err.find("error_missing_road.xosc:27: error: road '7' does not exist") !=
        std::string::npos);
  CHECK(dir.entries() == 0);
}

TEST_CASE("--param changes the scenario, --duration caps it, --dt sets the step", "[e2e][run]") {
  TempDir dir;
  const auto log = [&](const std::vector<std::string>& extra) {
    std::vector<std::string> args{"run",
                                  kCutIn,
                                  "--quiet",
                                  "--log",
                                  (dir.path() / "log.csv").string(),
                                  "--summary",
                                  (dir.path() / "s.json").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    REQUIRE(run_corsa(args).exit_code == 0);
    return std::make_pair(slurp(dir.path() / "log.csv"), slurp(dir.path() / "s.json"));
  };
  const auto plain = log({});
  const auto later = log({"--param", "CutInGap=25"});
  CHECK(plain.first != later.first);
  CHECK(later.second.find("\"CutInGap\": \"25\"") != std::string::npos);
  const auto capped = log({"--duration", "5"});
  CHECK(capped.second.find("\"end_reason\": \"duration\"") != std::string::npos);
  CHECK(capped.second.find("\"sim_time\": 5,") != std::string::npos);
  const auto coarse = log({"--dt", "0.05", "--duration", "5"});
  CHECK(coarse.second.find("\"steps\": 100,") != std::string::npos);
}

TEST_CASE("corsa run writes byte-identical outputs for the same inputs", "[e2e][run]") {
  TempDir dir;
  const auto run = [&](const std::string& tag) {
    const ProcessResult result = run_corsa({"run", kCutIn, "--quiet", "--seed", "7", "--record",
                                            (dir.path() / (tag + ".csv")).string(), "--log",
                                            (dir.path() / (tag + ".log")).string()});
    REQUIRE(result.exit_code == 0);
  };
  run("a");
  run("b");
  CHECK(slurp(dir.path() / "a.csv") == slurp(dir.path() / "b.csv"));
  CHECK(slurp(dir.path() / "a.log") == slurp(dir.path() / "b.log"));
  const auto rows = parse_trajectory(slurp(dir.path() / "a.csv"));
  CHECK(rows.front().time == 0.0);
  CHECK(rows.front().entity == "Ego");
}

TEST_CASE("corsa run writes the same binary trajectory on every recording thread", "[e2e][run]") {
  // 300 NPC vehicles on Town04 code about 300 rows a tick: from --threads 2, auto (the default)
  // moves the recording to its writer thread after its first 256 ticks (the engine's test "A
  // binary trajectory moved to the writer thread mid-run ..." asserts the move), and writer
  // encodes every tick there. Each file must be the bytes the run's own thread writes.
  TempDir dir;
  const auto record = [&](const std::string& threads, const std::string& thread,
                          const std::string& extension) {
    const auto path = dir.path() / (threads + thread + extension);
    std::vector<std::string> args{"run",
                                  "scenarios/town04_junction.xosc",
                                  "--quiet",
                                  "--duration",
                                  "4",
                                  "--seed",
                                  "3",
                                  "--npc",
                                  "vehicles=300",
                                  "--threads",
                                  threads,
                                  "--record",
                                  path.string()};
    if (!thread.empty()) {
      args.insert(args.end(), {"--record-thread", thread});
    }
    const ProcessResult result = run_corsa(args);
    INFO(result.err);
    REQUIRE(result.exit_code == 0);
    return path;
  };
  // The run's thread: one thread, no --record-thread.
  const auto own = record("1", "", ".corsatraj");
  const std::string bytes = slurp(own);
  CHECK(bytes.size() > 100000);
  for (const auto& [threads, thread] :
       std::vector<std::pair<std::string, std::string>>{{"1", "caller"},
                                                        {"1", "writer"},
                                                        {"2", ""},
                                                        {"2", "auto"},
                                                        {"2", "caller"},
                                                        {"2", "writer"}}) {
    INFO("--threads " << threads << " --record-thread '" << thread << "'");
    const bool same = slurp(record(threads, thread, ".corsatraj")) == bytes;  // not printed: MBs
    CHECK(same);
  }
  // The file holds the run's rows (the CSV it writes directly), and enough of them moving that
  // auto's rule applies: 128 coded rows a tick or more over its first window of 256 ticks.
  const auto csv = record("1", "", ".csv");
  const auto exported = dir.path() / "exported.csv";
  REQUIRE(run_corsa({"record", "export", own.string(), "-o", exported.string()}).exit_code == 0);
  const std::string text = slurp(csv);
  CHECK(slurp(exported) == text);
  std::map<double, int> moving;
  for (const TrajectoryRow& row : parse_trajectory(text)) {
    moving[row.time] += row.speed != 0.0 ? 1 : 0;
  }
  REQUIRE(moving.size() == 401);  // ticks 0 to 400 of 10 ms
  int window = 0;
  for (auto it = moving.begin(); it != std::next(moving.begin(), 256); ++it) {
    window += it->second;
  }
  CHECK(window >= 256 * 128);
}

TEST_CASE("corsa run refuses --record-thread without a binary trajectory", "[e2e][run]") {
  // A CSV trajectory is written on the run's thread: the option is refused, not ignored, and
  // nothing is written.
  TempDir dir;
  const auto csv = dir.path() / "x.csv";
  const ProcessResult csv_thread =
      run_corsa({"run", kCutIn, "--record-thread", "writer", "--record", csv.string()});
  CHECK(csv_thread.exit_code == 2);
  CHECK(csv_thread.err.find("--record-thread applies to binary trajectories only (--record "
                            "FILE.corsatraj), got --record '" +
                            csv.generic_string() + "'") != std::string::npos);
  for (const char* thread : {"auto", "caller", "writer"}) {
    const ProcessResult no_record = run_corsa(
        {"run", kCutIn, "--record-thread", thread, "--summary", (dir.path() / "s.json").string()});
    CHECK(no_record.exit_code == 2);
    CHECK(no_record.err.find("--record-thread applies to binary trajectories only (--record "
                             "FILE.corsatraj), got no --record") != std::string::npos);
  }
  CHECK(dir.entries() == 0);
}

}  // namespace
}  // namespace corsa::test
