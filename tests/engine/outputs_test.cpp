// The files a run writes: trajectory CSV, event log, summary JSON; determinism; nothing
// half-written on bad input.

#include "corsa/engine/outputs.h"

#include <fstream>
#include <sstream>

#include "corsa/core/strings.h"
#include "engine_fixture.h"
#include "temp_dir.h"

namespace corsa::test {
namespace {

using Catch::Detail::Approx;

std::string slurp_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    out.push_back(line);
  }
  return out;
}

engine::RunOptions options_for(const std::string& fixture, const TempDir& dir) {
  engine::RunOptions options;
  options.scenario = engine_fixture(fixture);
  options.record = dir.path() / "trajectory.csv";
  options.summary = dir.path() / "summary.json";
  options.log = dir.path() / "log.csv";
  return options;
}

TEST_CASE("The trajectory CSV has one row per entity per step, the exact time and fixed decimals",
          "[engine][output]") {
  TempDir dir;
  Diagnostics diagnostics;
  const engine::RunReport report =
      engine::run_scenario(options_for("condition_road.xosc", dir), diagnostics);
  const auto rows = lines(slurp_file(dir.path() / "trajectory.csv"));
  REQUIRE(!rows.empty());
  CHECK(rows.front() == "time,entity,x,y,z,h,p,r,speed,road,lane,s,t");
  CHECK(rows.size() == 1 + 4 * static_cast<size_t>(report.steps + 1));
  CHECK(rows[1].rfind("0,Ender,950,", 0) == 0);
  CHECK(rows[2].rfind("0,Drifter,", 0) == 0);  // document order
  // Off the road: road, lane, s and t are empty.
  bool saw_offroad = false;
  for (const auto& row : rows) {
    saw_offroad = saw_offroad || (row.find(",Drifter,") != std::string::npos && row.size() > 3 &&
                                  row.substr(row.size() - 3) == ",,,");
  }
  CHECK(saw_offroad);
  // Numbers read back exactly: the last row is the final state.
  const auto fields = split(rows.back(), ',');
  REQUIRE(fields.size() == 13);
  CHECK(fields[1] == "Passer");
  CHECK(parse_double(fields[0]) == report.sim_time);
  REQUIRE(parse_double(fields[2]));
  CHECK(*parse_double(fields[2]) == Approx(60.0 + 20.0 * report.sim_time));
}

TEST_CASE("--record-every keeps every N-th step and the last one", "[engine][output]") {
  TempDir dir;
  Diagnostics diagnostics;
  engine::RunOptions options = options_for("storyboard_stories_complete.xosc", dir);
  options.record_every = 100;
  const engine::RunReport report = engine::run_scenario(options, diagnostics);
  REQUIRE(report.steps == 301);
  const auto rows = lines(slurp_file(dir.path() / "trajectory.csv"));
  std::vector<std::string> times;
  for (size_t i = 1; i < rows.size(); ++i) {
    times.push_back(rows[i].substr(0, rows[i].find(',')));
  }
  CHECK(times == std::vector<std::string>{"0", "1", "2", "3", "3.01"});
}

TEST_CASE("The event log lists every storyboard transition with its time", "[engine][output]") {
  TempDir dir;
  Diagnostics diagnostics;
  engine::run_scenario(options_for("storyboard_act_triggers.xosc", dir), diagnostics);
  const auto rows = lines(slurp_file(dir.path() / "log.csv"));
  REQUIRE(rows.size() > 4);
  CHECK(rows[0] == "time,type,element,transition,state");
  CHECK(rows[1] == "0,storyboard,,startTransition,runningState");
  CHECK(rows[2] == "0,story,S,startTransition,runningState");
  CHECK(std::find(rows.begin(), rows.end(), "3.01,act,S::Later,stopTransition,completeState") !=
        rows.end());
  CHECK(rows.back() == "4.01,storyboard,,stopTransition,completeState");
}

TEST_CASE("The run summary names the end, the times and the collisions", "[engine][output]") {
  TempDir dir;
  Diagnostics diagnostics;
  engine::RunOptions options = options_for("condition_distances.xosc", dir);
  options.simulation.seed = 42;
  engine::run_scenario(options, diagnostics);
  const std::string json = slurp_file(dir.path() / "summary.json");
  CHECK(json.find("\"end_reason\": \"stop trigger\"") != std::string::npos);
  CHECK(json.find("\"sim_time\": 12.01") != std::string::npos);
  CHECK(json.find("\"steps\": 1201") != std::string::npos);
  CHECK(json.find("\"seed\": 42") != std::string::npos);
  CHECK(json.find("\"wall_time\": ") != std::string::npos);
  CHECK(json.find("{\"time\": 11.55, \"entities\": [\"Runner\", \"Slow\"]}") != std::string::npos);
  CHECK(json.find("{\"name\": \"Runner\"") != std::string::npos);
}

TEST_CASE("A run stopped from outside still writes its outputs, ending as interrupted",
          "[engine][output]") {
  TempDir dir;
  Diagnostics diagnostics;
  engine::RunOptions options = options_for("condition_distances.xosc", dir);
  int64_t steps = 0;
  options.stop = [&steps] { return ++steps == 300; };
  const engine::RunReport report = engine::run_scenario(options, diagnostics);
  CHECK(report.end_reason == engine::EndReason::kInterrupted);
  CHECK(report.steps == 300);
  const std::string json = slurp_file(dir.path() / "summary.json");
  CHECK(json.find("\"end_reason\": \"interrupted\"") != std::string::npos);
  CHECK(json.find("\"sim_time\": 3,") != std::string::npos);
  const auto rows = lines(slurp_file(dir.path() / "trajectory.csv"));
  REQUIRE(rows.size() > 2);
  CHECK(rows.back().rfind("3,", 0) == 0);  // the last recorded tick is where it stopped
  CHECK(std::filesystem::exists(dir.path() / "log.csv"));
}

TEST_CASE("The expected end of a run is its SimulationTime stop trigger, else the cap",
          "[engine][output]") {
  Diagnostics diagnostics;
  const xosc::Scenario demo = xosc::load_scenario(
      std::filesystem::path(CORSA_SOURCE_DIR) / "scenarios/demo/cut_in_city.xosc", {}, diagnostics);
  CHECK(engine::expected_end_time(demo, 3600.0) == 20.0);  // greaterOrEqual 20
  CHECK(engine::expected_end_time(demo, 5.0) == 5.0);      // --duration 5 comes first
  const xosc::Scenario greater_than =
      xosc::load_scenario(engine_fixture("condition_distances.xosc"), {}, diagnostics);
  CHECK(engine::expected_end_time(greater_than, 3600.0) == 12.0);
  // No stop trigger, or one that waits for something other than time: the cap stands.
  const xosc::Scenario stories =
      xosc::load_scenario(engine_fixture("storyboard_stories_complete.xosc"), {}, diagnostics);
  CHECK(engine::expected_end_time(stories, 3600.0) == 3600.0);
  const xosc::Scenario links =
      xosc::load_scenario(engine_fixture("motion_lane_links.xosc"), {}, diagnostics);
  CHECK(engine::expected_end_time(links, 60.0) == 60.0);
}

TEST_CASE("Same scenario, options and seed give byte-identical outputs", "[engine][output]") {
  TempDir first, second;
  Diagnostics diagnostics;
  engine::run_scenario(options_for("action_lane_change.xosc", first), diagnostics);
  engine::run_scenario(options_for("action_lane_change.xosc", second), diagnostics);
  CHECK(slurp_file(first.path() / "trajectory.csv") ==
        slurp_file(second.path() / "trajectory.csv"));
  CHECK(slurp_file(first.path() / "log.csv") == slurp_file(second.path() / "log.csv"));
}

TEST_CASE("Bad input writes no output at all", "[engine][output][errors]") {
  TempDir dir;
  Diagnostics diagnostics;
  CHECK_THROWS_AS(engine::run_scenario(options_for("error_missing_lane.xosc", dir), diagnostics),
                  InputError);
  CHECK(dir.entries() == 0);
}

}  // namespace
}  // namespace corsa::test
