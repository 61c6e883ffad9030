// Issue #6 (traffic, continued) and issue #9's NPCs: car following along the lane path,
// TrafficDistribution, TrafficAreaAction, NPCs as engine entities, spawn and removal times.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>

#include "engine_fixture.h"

namespace {

using corsa::test::engine_fixture;
using corsa::test::FixtureRun;

std::filesystem::path asam(const std::string& name) {
  return std::filesystem::path(CORSA_SHARED_DIR) / "conformance/asam-osc-1.3" / name;
}

bool collided(const corsa::engine::Simulation& sim, size_t a) {
  for (const auto& c : sim.collisions()) {
    if (c.first == a || c.second == a) return true;
  }
  return false;
}

}  // namespace

TEST_CASE("The acc controller follows a standing vehicle just across a road link",
          "[engine][acc]") {
  FixtureRun run(engine_fixture("traffic_follow_across_link.xosc"));
  run.run();
  CHECK(run.sim().collisions().empty());
  const auto& follower = run.now("Follower");
  const auto& lead = run.now("Lead");
  REQUIRE(follower.road);
  // The follower drove through the link onto road 2 (lane 1, toward -s) and waits behind.
  CHECK(run.sim().road_id(follower.road->road) == "2");
  CHECK(follower.road->lane == 1);
  CHECK(follower.speed < 0.5);
  // Bumper to bumper: lead rear (x 550 + 1.4 - 2.25) minus follower front (x + 1.4 + 2.25).
  const double gap = (lead.pose.x + 1.4 - 2.25) - (follower.pose.x + 1.4 + 2.25);
  CHECK(gap > 2.5);
  CHECK(gap < 6.0);
}

TEST_CASE("ASAM TrafficJam: Ego drives into the jam as asked, and stops before it under acc",
          "[engine][acc][asam]") {
  // The scenario gives Ego 36.1 m/s and no controller: an ideal driver meets the standing A5
  // (same lane, 151 m ahead) after about 4 s. That collision is what the scenario asks for.
  FixtureRun ideal(asam("TrafficJam.xosc"));
  ideal.run();
  REQUIRE_FALSE(ideal.sim().collisions().empty());
  const auto& first = ideal.sim().collisions().front();
  CHECK(first.time == Approx(4.05).margin(0.05));
  CHECK(ideal.sim().entity(first.first).name == "Ego");
  CHECK(ideal.sim().entity(first.second).name == "A5");

  // With a car-following driver Ego stops behind A5: no collision at all.
  corsa::engine::SimulationOptions options;
  options.controller = "acc";
  FixtureRun acc(asam("TrafficJam.xosc"), options);
  acc.run();
  CHECK_FALSE(collided(acc.sim(), acc.entity("Ego")));
  CHECK(acc.now("Ego").speed < 5.0);  // from 36.1 m/s, still creeping up at the 10 s stop
  CHECK(acc.now("Ego").pose.y < acc.now("A5").pose.y - 4.5);
}
