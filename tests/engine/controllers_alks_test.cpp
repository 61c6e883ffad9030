// esmini's ALKS_R157SM_Controller emulated (controllers/alks_r157.h): on esmini's own map, a
// target cuts in 30 m ahead of the ego and brakes (as esmini's alks_r157_cut_in_quick_brake).

#include <cmath>
#include <optional>

#include "engine_fixture.h"

namespace corsa::test {
namespace {

using Catch::Detail::Approx;
using Params = std::vector<std::pair<std::string, std::string>>;

std::filesystem::path alks_fixture() { return engine_fixture("controller_alks_r157.xosc"); }

// The first tick (s) at which the ego's speed drops, and the ego's acceleration then (m/s^2).
std::pair<double, double> braking_onset(FixtureRun& run) {
  const size_t ego = run.entity("Ego");
  std::optional<double> before;
  for (const auto& [tick, states] : run.trace().ticks()) {
    const double v = states.at(ego).speed;
    if (before && v < *before - 1e-9) {
      return {tick * run.sim().dt(), (v - *before) / run.sim().dt()};
    }
    before = v;
  }
  return {-1.0, 0.0};
}

TEST_CASE("ALKS R157 Regulation model with cruise drives as esmini's smoke test records",
          "[engine][controllers][alks]") {
  // smoke_test.py test_alks (esmini), model Regulation with cruise: the ego's rows at 2.85 s
  // (still 20 m/s), 4.99 s (x 140.769, 11.520 m/s) and 6.35 s (x 152.710, 6.080 m/s).
  FixtureRun run(alks_fixture(), {}, Params{});
  run.run();
  CHECK(run.sim().controller_substitute(run.entity("Ego")).empty());
  CHECK(all_text(run.diagnostics()).find("stands in") == std::string::npos);
  CHECK(run.sim().collisions().empty());
  CHECK(run.at(2.85, "Ego").speed == Approx(20.0).margin(1e-9));
  CHECK(run.at(2.85, "Ego").pose.x == Approx(107.0).margin(0.001));
  CHECK(run.at(4.99, "Ego").pose.x == Approx(140.769).margin(0.005));
  CHECK(run.at(4.99, "Ego").speed == Approx(11.520).margin(0.005));
  CHECK(run.at(6.35, "Ego").pose.x == Approx(152.710).margin(0.005));
  CHECK(run.at(6.35, "Ego").speed == Approx(6.080).margin(0.005));
}

TEST_CASE("ALKS R157 Regulation brakes at 6 m/s^2 once the cut-in's TTC is critical",
          "[engine][controllers][alks]") {
  // Without cruise it keeps 20 m/s until TTC < dv / (2 x 6) + 0.35 + 0.1 s (the regulation's
  // lane intrusion criterion), then brakes at 6 m/s^2; with fullStop down to standstill (the
  // target brakes gently here: no collision).
  FixtureRun run(alks_fixture(), {},
                 Params{{"Cruise", "false"}, {"FullStop", "true"}, {"TargetBrakeRate", "2"}});
  run.run();
  const auto [onset, acceleration] = braking_onset(run);
  REQUIRE(onset > 2.0);
  CHECK(acceleration == Approx(-6.0).margin(1e-6));
  CHECK(run.at(onset - 0.01, "Ego").speed == Approx(20.0).margin(1e-9));
  // The model judges the target where it is after its move and the ego where the step began.
  const auto criterion = [&](double ego_time, double target_time) {
    const auto& ego = run.at(ego_time, "Ego");
    const auto& target = run.at(target_time, "Target");
    // Free space along the straight road (x): the target's box (centre 1.45 m ahead, 5.04 x 2 m,
    // turned by its heading) from its rear to the ego's front (centre 1.4 m ahead); speeds along
    // the lane.
    const double h = target.pose.h;
    const double rear = target.pose.x + 1.45 * std::cos(h) - 2.52 * std::abs(std::cos(h)) -
                        1.0 * std::abs(std::sin(h));
    const double gap = rear - (ego.pose.x + 1.4 + 2.52);
    const double dv = ego.speed - target.speed;
    return dv > 0.0 && gap / dv < dv / 12.0 + 0.45;
  };
  CHECK(criterion(onset - 0.01, onset));
  CHECK_FALSE(criterion(onset - 0.02, onset - 0.01));
  const double stop = onset + 20.0 / 6.0;  // 20 m/s at 6 m/s^2
  CHECK(run.at(stop - 0.1, "Ego").speed == Approx(0.6).margin(0.07));
  CHECK(run.now("Ego").speed == 0.0);
  CHECK(run.sim().collisions().empty());
}

TEST_CASE("ALKS R157 ReferenceDriver perceives the cut-in at 0.375 m, reacts 0.4 + 0.75 s later",
          "[engine][controllers][alks]") {
  // Annex 3's driver: the cut-in is perceived when the target has moved 0.375 m (lane
  // wandering) toward the ego; 0.4 s of perception (cutInPerceptionDelayMode Time) and 0.75 s of
  // reaction later, the TTC being under 2 s, the brake builds up at 0.774 g per 0.6 s.
  FixtureRun run(alks_fixture(), {},
                 Params{{"Model", "ReferenceDriver"},
                        {"Cruise", "false"},
                        {"PerceptionMode", "Time"},
                        {"FullStop", "true"}});
  run.run();
  CHECK(run.sim().controller_substitute(run.entity("Ego")).empty());
  const size_t target = run.entity("Target");
  const double t0 = run.at(2.0, "Target").road->t;
  std::optional<double> wandered;
  for (const auto& [tick, states] : run.trace().ticks()) {
    if (!wandered && states.at(target).road && std::abs(states.at(target).road->t - t0) > 0.375) {
      wandered = tick * run.sim().dt();
    }
  }
  REQUIRE(wandered);
  const auto [onset, acceleration] = braking_onset(run);
  CHECK(onset == Approx(*wandered + 0.4 + 0.75).margin(0.015));
  const double jerk = 0.774 * 9.8 / 0.6;  // m/s^3
  CHECK(acceleration == Approx(-jerk * 0.01).margin(1e-6));
  // Two steps later the brake has built up three steps' worth.
  const double v0 = run.at(onset - 0.01, "Ego").speed;
  const double v3 = run.at(onset + 0.02, "Ego").speed;
  CHECK(v0 - v3 == Approx(jerk * 0.01 * 0.01 * (1 + 2 + 3)).margin(1e-6));
  // Full braking: 0.774 g, or 0.85 g once the AEB joins (TTC under 1.5 s, the target across
  // the ego's front).
  double hardest = 0.0;
  const size_t ego = run.entity("Ego");
  std::optional<double> before;
  for (const auto& [tick, states] : run.trace().ticks()) {
    if (before) hardest = std::max(hardest, (*before - states.at(ego).speed) / run.sim().dt());
    before = states.at(ego).speed;
  }
  CHECK(hardest <= 0.85 * 9.8 + 1e-6);
  CHECK(hardest >= 0.774 * 9.8 - 1e-6);
}

TEST_CASE(
    "ALKS R157 ReferenceDriver brakes 0.4 + 0.75 s after its leader brakes harder than 5 m/s^2",
    "[engine][controllers][alks]") {
  // The target drives 25 m ahead in the ego's lane at the ego's 20 m/s and brakes at 6 m/s^2: a
  // deceleration scenario, perceived when the leader's deceleration passes 5 m/s^2, critical
  // with a headway under 2 s (1.25 s here) once the reaction time has run.
  FixtureRun run(alks_fixture(), {},
                 Params{{"Model", "ReferenceDriver"},
                        {"Cruise", "false"},
                        {"FullStop", "true"},
                        {"TargetLane", "-1"},
                        {"TargetSpeed", "20"},
                        {"TargetBrakeRate", "6"}});
  run.run();
  const size_t target = run.entity("Target");
  std::optional<double> leader_brakes;
  for (const auto& [tick, states] : run.trace().ticks()) {
    if (!leader_brakes && states.at(target).acceleration < -5.0) {
      leader_brakes = tick * run.sim().dt();
    }
  }
  REQUIRE(leader_brakes);
  const auto [onset, acceleration] = braking_onset(run);
  CHECK(onset == Approx(*leader_brakes + 0.4 + 0.75).margin(0.015));
  CHECK(acceleration == Approx(-0.774 * 9.8 / 0.6 * 0.01).margin(1e-6));
  CHECK(run.sim().collisions().empty());
  CHECK(run.now("Ego").speed == 0.0);
}

TEST_CASE("ALKS R157 models not emulated (RSS, FSM) run under the acc substitute, said so",
          "[engine][controllers][alks]") {
  FixtureRun run(alks_fixture(), {}, Params{{"Model", "RSS"}});
  run.run();
  CHECK(run.sim().controller_substitute(run.entity("Ego")) == "ALKS_R157SM_Controller");
  CHECK(all_text(run.diagnostics()).find("model 'RSS'") != std::string::npos);
}

}  // namespace
}  // namespace corsa::test
