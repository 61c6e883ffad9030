// The bundled scenarios (scenarios/*.xosc on scenarios/maps/motorway_2km.xodr) run with `corsa
// run` and give their golden trajectories (scenarios/goldens/*.csv, every 10th step), and the
// behaviour each is about: a cut-in, an overtaking, lane changes, a speed change to a stop.
//
// Regenerate a golden after a deliberate behaviour change with
//   corsa run scenarios/NAME.xosc --record-every 10 --record scenarios/goldens/NAME.csv

#include <algorithm>

#include "csv_compare.h"
#include "run_corsa.h"

namespace corsa::test {
namespace {

using Catch::Detail::Approx;

struct ScenarioRun {
  std::vector<TrajectoryRow> rows;
  std::string summary;
};

ScenarioRun run_and_compare(const std::string& name) {
  TempDir dir;
  const auto csv = dir.path() / "run.csv";
  const auto summary = dir.path() / "summary.json";
  const ProcessResult result =
      run_corsa({"run", "scenarios/" + name + ".xosc", "--record-every", "10", "--record",
                 csv.string(), "--summary", summary.string(), "--quiet"});
  INFO(result.err);
  REQUIRE(result.exit_code == 0);
  CHECK(result.out.empty());
  ScenarioRun run{parse_trajectory(slurp(csv)), slurp(summary)};
  const auto golden =
      std::filesystem::path(CORSA_SOURCE_DIR) / "scenarios/goldens" / (name + ".csv");
  REQUIRE(std::filesystem::exists(golden));
  check_against_golden(run.rows, parse_trajectory(slurp(golden)));
  CHECK(run.summary.find("\"end_reason\": \"stop trigger\"") != std::string::npos);
  CHECK(run.summary.find("\"collisions\": []") != std::string::npos);
  return run;
}

TEST_CASE("cut_in: Cutter pulls in ahead of Ego and Ego brakes", "[e2e][scenario]") {
  const ScenarioRun run = run_and_compare("cut_in");
  const auto ego = of(run.rows, "Ego");
  const auto cutter = of(run.rows, "Cutter");
  REQUIRE(ego.size() == cutter.size());
  CHECK(cutter.front().lane == -1);
  CHECK(ego.front().lane == -2);
  CHECK(cutter.back().lane == -2);  // in Ego's lane
  CHECK(cutter.back().x > ego.back().x + 10.0);
  CHECK(ego.back().speed == Approx(20.0));
  CHECK(cutter.back().speed == Approx(22.0));
  // Ego only slows down after the cut-in.
  const auto first_slow =
      std::find_if(ego.begin(), ego.end(), [](const TrajectoryRow& r) { return r.speed < 27.7; });
  REQUIRE(first_slow != ego.end());
  const auto index = static_cast<size_t>(first_slow - ego.begin());
  CHECK(cutter[index].lane == -2);
}

TEST_CASE("overtaking: Ego passes the truck in the middle lane and returns", "[e2e][scenario]") {
  const ScenarioRun run = run_and_compare("overtaking");
  const auto ego = of(run.rows, "Ego");
  const auto truck = of(run.rows, "Truck");
  bool passed_alongside = false;
  for (size_t i = 0; i < ego.size(); ++i) {
    CHECK(truck[i].lane == -3);
    passed_alongside =
        passed_alongside || (ego[i].lane == -2 && std::abs(ego[i].x - truck[i].x) < 5.0);
  }
  CHECK(passed_alongside);
  CHECK(ego.front().x < truck.front().x);
  CHECK(ego.back().x > truck.back().x + 20.0);
  CHECK(ego.back().lane == -3);
  CHECK(ego.back().t == Approx(-9.375));
}

TEST_CASE("lane_change: to lane -2 over time, back over a distance with an offset",
          "[e2e][scenario]") {
  const ScenarioRun run = run_and_compare("lane_change");
  const auto ego = of(run.rows, "Ego");
  const auto at = [&](double time) {
    return *std::find_if(ego.begin(), ego.end(),
                         [&](const TrajectoryRow& r) { return std::abs(r.time - time) < 1e-9; });
  };
  CHECK(at(1.0).lane == -3);
  CHECK(at(8.0).lane == -2);
  CHECK(at(8.0).t == Approx(-5.625));
  CHECK(ego.back().lane == -3);
  CHECK(ego.back().t == Approx(-9.375 + 0.25));
  CHECK(ego.back().h == Approx(0.0).margin(1e-9));
}

TEST_CASE("speed_change: accelerates to 30 m/s and brakes to a stop before the barrier",
          "[e2e][scenario]") {
  const ScenarioRun run = run_and_compare("speed_change");
  const auto ego = of(run.rows, "Ego");
  double top = 0.0;
  for (const auto& row : ego) {
    top = std::max(top, row.speed);
  }
  CHECK(ego.front().speed == 0.0);
  CHECK(top == Approx(30.0));
  CHECK(ego.back().speed == 0.0);
  const double barrier_x = of(run.rows, "Barrier").back().x;
  // Ego's front bumper is 3.75 m ahead of its reference point, the barrier 0.25 m deep.
  const double gap = (barrier_x - 0.25) - (ego.back().x + 3.75);
  CHECK(gap > 15.0);
  CHECK(gap < 25.0);
}

}  // namespace
}  // namespace corsa::test
