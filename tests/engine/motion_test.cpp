// The default controller along lanes, sections, road links and junctions; bad placements.

#include "engine_fixture.h"

namespace corsa::test {
namespace {

using Catch::Detail::Approx;

TEST_CASE("The default controller follows lanes through sections, road links and junctions",
          "[engine][motion]") {
  FixtureRun run(engine_fixture("motion_lane_links.xosc"));
  run.run();
  const size_t driver = run.entity("Driver");
  std::vector<std::pair<std::string, int>> visited;
  const engine::EntityState* previous = nullptr;
  double largest_step = 0.0;
  for (const auto& [tick, states] : run.trace().ticks()) {
    const engine::EntityState& s = states[driver];
    REQUIRE(s.road);
    const std::pair<std::string, int> where{run.sim().road_id(s.road->road), s.road->lane};
    if (visited.empty() || visited.back() != where) {
      visited.push_back(where);
    }
    CHECK(std::abs(s.pose.h) < 1e-9);  // every road here runs along +x for the driver
    CHECK(s.pose.y == Approx(-1.75));
    if (previous != nullptr) {
      largest_step = std::max(largest_step,
                              std::hypot(s.pose.x - previous->pose.x, s.pose.y - previous->pose.y));
    }
    previous = &s;
  }
  // Road 2 runs the other way round: its lane 1 continues lane -1; the junction's straight
  // connection (road 10) wins over the right turn (road 11).
  const std::vector<std::pair<std::string, int>> expected{
      {"1", -1}, {"2", 1}, {"10", -1}, {"3", -1}};
  CHECK(visited == expected);
  CHECK(largest_step <= 20.0 * 0.01 + 1e-9);  // no jump anywhere
  // 300 + 300 + 20 + 200 m at 20 m/s: at the end of road 3 after 41 s, stopped there.
  CHECK(run.now("Driver").pose.x == Approx(1020.0));
  CHECK(run.now("Driver").speed == 0.0);
  CHECK(run.now("Driver").odometer == Approx(820.0));
  CHECK(run.sim().time() == Approx(41.01));
  CHECK(run.sim().end_reason() == engine::EndReason::kStopTrigger);
}

TEST_CASE("Entities placed on a missing road or lane, or off the map, fail before the run",
          "[engine][motion][errors]") {
  const auto message = [](const std::string& fixture) -> std::string {
    try {
      FixtureRun run(engine_fixture(fixture));
    } catch (const InputError& error) {
      CHECK(error.diagnostic().file.find(fixture) != std::string::npos);
      CHECK(error.diagnostic().line == 27);
      return error.diagnostic().message;
    }
    FAIL("no error for " << fixture);
    return {};
  };
  CHECK(message("error_missing_road.xosc") == "road '7' does not exist in the road network");
  CHECK(message("error_missing_lane.xosc") == "road '1' has no lane -9 at s = 10");
  CHECK(message("error_off_map.xosc").find("placed off the map") != std::string::npos);
}

TEST_CASE("Two simulations of one scenario in one process do not interact",
          "[engine][motion][determinism]") {
  FixtureRun first(engine_fixture("action_lane_change.xosc"));
  FixtureRun second(engine_fixture("action_lane_change.xosc"));
  // Interleaved steps, one simulation ahead of the other.
  for (int i = 0; i < 50; ++i) {
    first.sim().step();
  }
  while (first.sim().step()) {
    second.sim().step();
  }
  second.run();
  REQUIRE(first.sim().tick() == second.sim().tick());
  for (const auto& [tick, states] : first.trace().ticks()) {
    for (size_t i = 0; i < states.size(); ++i) {
      CHECK(states[i].pose.x == second.trace().at(tick, i).pose.x);
      CHECK(states[i].pose.y == second.trace().at(tick, i).pose.y);
    }
  }
}

}  // namespace
}  // namespace corsa::test
