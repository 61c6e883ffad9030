// `corsa run` from the command line: options, outputs, exit codes and messages.

#include <algorithm>

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
  // A CSV trajectory is written on the run's thread: the option is refused, not ignored.
  const ProcessResult csv_thread =
      run_corsa({"run", kCutIn, "--record-thread", "writer", "--record", "x.csv"});
  CHECK(csv_thread.exit_code == 2);
  CHECK(csv_thread.err.find("--record-thread applies to binary trajectories only") !=
        std::string::npos);
  CHECK(csv_thread.err.find("x.csv") != std::string::npos);
  const ProcessResult no_record = run_corsa({"run", kCutIn, "--record-thread", "caller"});
  CHECK(no_record.exit_code == 2);
  CHECK(no_record.err.find("no --record") != std::string::npos);
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
  TempDir dir;
  const auto run = [&](const std::string& thread, const std::string& threads) {
    const auto path = dir.path() / (thread + threads + ".corsatraj");
    const ProcessResult result = run_corsa({"run", kCutIn, "--quiet", "--threads", threads,
                                            "--record-thread", thread, "--record", path.string()});
    REQUIRE(result.exit_code == 0);
    return slurp(path);
  };
  const std::string bytes = run("caller", "1");
  CHECK(bytes.size() > 100);
  CHECK(run("writer", "1") == bytes);
  CHECK(run("auto", "2") == bytes);
  CHECK(run("writer", "2") == bytes);
}

}  // namespace
}  // namespace corsa::test
