// Issue #6 part B: entities added and deleted, visibility, traffic signals, traffic swarm,
// sources, sinks and stops, on the focused fixtures of tests/engine/fixtures.

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "corsa/engine/outputs.h"
#include "engine_fixture.h"
#include "temp_dir.h"

namespace {

using corsa::engine::TransitionKind;
using corsa::test::engine_fixture;
using corsa::test::FixtureRun;

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Rows of the trajectory CSV for an entity, as (time) values.
std::vector<double> row_times(const std::string& csv, const std::string& entity) {
  std::vector<double> times;
  std::istringstream lines(csv);
  std::string line;
  std::getline(lines, line);  // header
  while (std::getline(lines, line)) {
    const size_t a = line.find(',');
    const size_t b = line.find(',', a + 1);
    if (line.substr(a + 1, b - a - 1) == entity) {
      times.push_back(std::stod(line.substr(0, a)));
    }
  }
  return times;
}

}  // namespace

TEST_CASE(
    "An added entity appears at its position, a deleted one disappears from rows and conditions",
    "[engine][entities]") {
  corsa::test::TempDir dir;
  FixtureRun run(engine_fixture("entity_add_delete_visibility.xosc"));
  corsa::engine::TrajectoryRecorder recorder(dir.path() / "out.csv", 1);
  run.sim().add_observer(recorder);
  run.run();
  recorder.finish(run.sim());

  CHECK_FALSE(run.at(1.0, "Late").placed);
  const auto& added = run.at(2.5, "Late");
  REQUIRE(added.placed);
  REQUIRE(added.road);
  CHECK(added.road->lane == -3);
  CHECK(added.road->s == Approx(100.0).margin(0.5));
  CHECK(run.at(5.0, "Late").speed == Approx(8.0));  // its own action moved it once added

  CHECK(run.at(3.9, "Gone").placed);
  CHECK_FALSE(run.at(4.1, "Gone").placed);
  // The speed condition on Gone (faster than 5 m/s, after 4.5 s) never holds once it is gone.
  CHECK_FALSE(run.first("GoneFast", TransitionKind::kStart));

  const std::string csv = read_text(dir.path() / "out.csv");
  const auto late = row_times(csv, "Late");
  REQUIRE_FALSE(late.empty());
  CHECK(late.front() >= 2.0);
  const auto gone = row_times(csv, "Gone");
  REQUIRE_FALSE(gone.empty());
  CHECK(gone.back() < 4.1);
  CHECK(row_times(csv, "Ego").size() > late.size());
}

TEST_CASE("VisibilityAction hides the entity from the sensors in the world snapshot",
          "[engine][entities]") {
  FixtureRun run(engine_fixture("entity_add_delete_visibility.xosc"));
  corsa::engine::WorldSnapshot world;
  const size_t late = run.entity("Late");
  while (run.sim().time() < 2.5) {
    run.sim().step();
  }
  run.sim().fill_snapshot(world);
  CHECK(world.entities[late].visible);
  while (run.sim().time() < 3.5) {
    run.sim().step();
  }
  run.sim().fill_snapshot(world);
  CHECK_FALSE(world.entities[late].visible);
  CHECK_FALSE(run.now("Late").visible);
  run.run();
  run.sim().fill_snapshot(world);
  CHECK_FALSE(world.entities[run.entity("Gone")].visible);  // deleted
}

TEST_CASE("Traffic signal controllers cycle through their phases; signal conditions and actions",
          "[engine][signals]") {
  FixtureRun run(engine_fixture("traffic_signal_phases.xosc"));
  corsa::engine::WorldSnapshot world;
  run.sim().fill_snapshot(world);
  const auto signal = [&](const std::string& id) -> std::string {
    for (const auto& s : world.signals) {
      if (s.id == id) return s.state;
    }
    return "";
  };
  CHECK(signal("1") == "off;off;on");
  CHECK(signal("2").empty());  // Side starts 1 s after Main
  run.run();
  // Main: go 0-5, caution 5-7, stop 7-10, go 10-15; forced to stop at 12 (run ends at 14).
  const auto main_stop = run.first("MainStop", TransitionKind::kStart);
  REQUIRE(main_stop);
  CHECK(*main_stop == Approx(7.0).margin(0.011));
  CHECK(run.count("SignalRed", TransitionKind::kStart) == 1);
  const auto red = run.first("SignalRed", TransitionKind::kStart);
  REQUIRE(red);
  CHECK(*red == Approx(7.0).margin(0.011));
  // Side: stop 1-5, go 5-11.
  const auto side_go = run.first("SideGoes", TransitionKind::kStart);
  REQUIRE(side_go);
  CHECK(*side_go == Approx(5.0).margin(0.011));
  // SideGoes set it to 2 at 5 s, SignalRed to 1 at 7 s.
  CHECK(run.sim().parameter("Dummy")->text() == "1");
  run.sim().fill_snapshot(world);
  CHECK(signal("3") == "flashing");
  // Forced to "stop" at 12 s, which lasts its 3 s: stop at the end (14 s), not "go".
  CHECK(signal("1") == "on;off;off");
  CHECK(run.now("Ego").speed == Approx(0.0));
}

TEST_CASE("A traffic swarm keeps its vehicles in the ring around the central entity, by the seed",
          "[engine][traffic]") {
  corsa::engine::SimulationOptions options;
  options.seed = 7;
  FixtureRun run(engine_fixture("traffic_swarm.xosc"), options);
  const size_t own = 1;
  size_t most = 0;
  while (run.sim().step()) {
    const auto& ego = run.now("Ego");
    size_t present = 0;
    const bool swarming = run.sim().time() < 20.0;  // TrafficStopAction at 20 s
    for (size_t i = own; i < run.sim().entity_count(); ++i) {
      const auto& s = run.sim().state(i);
      if (!s.placed) continue;
      ++present;
      REQUIRE(s.road);
      if (swarming) {
        // Inside the ellipse (semi-major 120 m along the road): leavers are removed at once.
        CHECK(std::abs(s.pose.x - ego.pose.x) <= 120.0);
        // DirectionOfTravelDistribution same="1" opposite="0": all drive Ego's way.
        CHECK(std::cos(s.pose.h - ego.pose.h) > 0.9);
      }
    }
    CHECK(present <= 8);
    most = std::max(most, present);
  }
  CHECK(most == 8);
  CHECK(run.sim().entity_count() >= 1 + 8);

  FixtureRun again(engine_fixture("traffic_swarm.xosc"), options);
  again.run();
  REQUIRE(again.sim().entity_count() == run.sim().entity_count());
  for (size_t i = 0; i < run.sim().entity_count(); ++i) {
    CHECK(again.sim().state(i).pose.x == run.sim().state(i).pose.x);
  }
  options.seed = 8;
  FixtureRun other(engine_fixture("traffic_swarm.xosc"), options);
  other.run();
  bool differs = other.sim().entity_count() != run.sim().entity_count();
  for (size_t i = 1; !differs && i < run.sim().entity_count(); ++i) {
    differs = other.sim().state(i).pose.x != run.sim().state(i).pose.x;
  }
  CHECK(differs);
}

TEST_CASE("A traffic source emits at its rate, a sink absorbs, a stop ends the source",
          "[engine][traffic]") {
  FixtureRun run(engine_fixture("traffic_source_sink.xosc"));
  run.run();
  // 0.5 vehicles/s from 0.1 s to 20 s: about 10 vehicles (the first at once).
  const size_t spawned = run.sim().entity_count() - 1;
  CHECK(spawned >= 9);
  CHECK(spawned <= 11);
  size_t present = 0;
  for (size_t i = 1; i < run.sim().entity_count(); ++i) {
    const auto& s = run.sim().state(i);
    if (s.placed) {
      ++present;
      // Nobody passed the sink at s = 400 (10 m radius).
      REQUIRE(s.road);
      CHECK(s.road->s < 411.0);
    }
  }
  // At 15 m/s the 350 m to the sink take 23 s: the vehicles of the first 17 s are gone by 40 s.
  CHECK(present < spawned);
  CHECK(present <= 3);
}

TEST_CASE("Pedestrians walk along the sidewalk and cross the road", "[engine][pedestrians]") {
  FixtureRun run(engine_fixture("traffic_pedestrians.xosc"));
  run.run();
  const auto& walker = run.now("Walker");
  REQUIRE(walker.road);
  CHECK(walker.road->lane == -4);  // still on the sidewalk
  CHECK(walker.road->s == Approx(50.0 + 1.4 * 25.0).margin(0.05));
  // The crosser walks across the six 3.5 m lanes (t from about -11 to +10.5), then stops at the
  // far edge of the road.
  const auto& before = run.at(0.5, "Crosser");
  REQUIRE(before.road);
  CHECK(before.road->lane == -4);
  const auto& middle = run.at(9.0, "Crosser");
  REQUIRE(middle.road);
  CHECK(std::abs(middle.road->lane) <= 3);
  CHECK(middle.pose.x == Approx(before.pose.x).margin(1e-6));  // straight across
  const auto& end = run.now("Crosser");
  CHECK(end.speed == 0.0);
  CHECK(end.pose.y > 10.5);
  CHECK(end.pose.y < 10.5 + 0.1);
}
