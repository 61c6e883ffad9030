// esmini's sloppyDriver (controllers/sloppy_driver.h), on tests/engine/fixtures/
// controller_sloppy_driver.xosc (esmini's multi_controller up to its interactive driver: Ego at
// 15 m/s, the controller active in the lateral domain from 1 s to 10 s, sloppiness 0.7, additive)
// and controller_sloppy_driver_both.xosc (both domains from the Init on, sloppiness 0.5,
// override); both at esmini's smoke-test step 0.1 s and seed 397860069.
//
// What to expect, from esmini's source: the draws are libstdc++'s uniform_real_distribution on
// a std::mt19937 seeded with the seed; the controller's clock starts with its first step (the
// step after the activation); its lateral target holds 0 for its first 1.5 s, so the entity
// keeps its lane until then, and the step after the first draw moves it right by
// 15 m/s x 0.1 s x sin(-0.02 x target x 0.1 / period x 0.1 s x 15 m/s). esmini's own rows for
// multi_controller (its smoke test) put Ego 0.546 m right of its start at 3.2 s, heading 6.157,
// and 3.950 m right at 5.1 s, heading 0.045.

#include "controllers/sloppy_driver.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <random>

#include "engine_fixture.h"

using corsa::engine::detail::EsminiRandom;
using corsa::test::engine_fixture;
using corsa::test::FixtureRun;

namespace {

constexpr uint32_t kSmokeTestSeed = 397860069;  // esmini's smoke test, test_multi_controller

corsa::engine::SimulationOptions sloppy_options() {
  corsa::engine::SimulationOptions options;
  options.dt = 0.1;
  options.seed = kSmokeTestSeed;
  return options;
}

// The difference of two headings, in (-pi, pi].
double heading_gap(double a, double b) { return std::remainder(a - b, 2.0 * std::numbers::pi); }

}  // namespace

TEST_CASE("esmini's generator draws as libstdc++'s uniform_real_distribution on mt19937",
          "[engine][controllers][sloppy]") {
  EsminiRandom random(kSmokeTestSeed);
  // The first draws of std::uniform_real_distribution<>{0.5, 1.5} with g++'s library.
  CHECK(random.real_between(0.5, 1.5) == 0.97750969260590759);
  CHECK(random.real_between(0.5, 1.5) == 0.61150063694002033);
  CHECK(random.real_between(0.5, 1.5) == 0.84725510056405562);
#if defined(__GLIBCXX__)
  // Any range, many draws: the same numbers as the standard library's (g++'s) distribution.
  EsminiRandom ours(12345);
  std::mt19937 engine(12345);
  for (int i = 0; i < 2000; ++i) {
    const double low = i % 3 == 0 ? -0.35 : 0.5;
    const double high = i % 3 == 0 ? 0.35 : 1.5;
    REQUIRE(ours.real_between(low, high) == std::uniform_real_distribution<>{low, high}(engine));
  }
#endif
  // After the entities: two draws per entity made.
  EsminiRandom after = EsminiRandom::after_entities(kSmokeTestSeed, 1);
  CHECK(after.real_between(0.5, 1.5) == 0.84725510056405562);
}

TEST_CASE("esmini's sloppyDriver drifts as esmini's multi_controller rows have it",
          "[engine][controllers][sloppy]") {
  FixtureRun run(engine_fixture("controller_sloppy_driver.xosc"), sloppy_options());
  run.run();
  CHECK(run.sim().controller_substitute(run.entity("Ego")).empty());
  const double y0 = run.at(0.0, "Ego").pose.y;
  // Its first step ends at 1.2 s; the first period (1.5 s of its clock) holds the lane to 2.6 s.
  for (const double t : {1.0, 1.5, 2.0, 2.6}) {
    CAPTURE(t);
    CHECK(run.at(t, "Ego").pose.y == y0);
    CHECK(run.at(t, "Ego").pose.h == 0.0);
  }
  // The step after the first draw: the draws as esmini makes them, after its entity's two.
  EsminiRandom random = EsminiRandom::after_entities(kSmokeTestSeed, 1);
  const double target = 5.0 * 0.7 * 0.7 * random.real_between(0.5, 1.5);
  const double period = 1.5 * random.real_between(0.5, 1.5);
  const double turn = -0.02 * (target * 0.1 / period) * 0.1 * 15.0;
  CHECK(run.at(2.7, "Ego").pose.y - y0 == Approx(15.0 * 0.1 * std::sin(turn)).margin(1e-12));
  CHECK(heading_gap(run.at(2.7, "Ego").pose.h, turn) == Approx(0.0).margin(1e-12));
  // esmini's rows (3 decimals).
  CHECK(run.at(3.2, "Ego").pose.y - y0 == Approx(-0.546).margin(0.0015));
  CHECK(heading_gap(run.at(3.2, "Ego").pose.h, 6.157) == Approx(0.0).margin(0.0015));
  CHECK(run.at(5.1, "Ego").pose.y - y0 == Approx(-3.950).margin(0.0015));
  CHECK(heading_gap(run.at(5.1, "Ego").pose.h, 0.045) == Approx(0.0).margin(0.0015));
  // The lateral domain only: the speed is the actions'; along the road at 15 m/s.
  CHECK(run.at(5.1, "Ego").speed == 15.0);
  CHECK(run.at(5.1, "Ego").pose.x - run.at(0.0, "Ego").pose.x == Approx(76.5).margin(1e-9));
  // Deactivated at 10.1 s: the offset it made stays, the heading is the road's again.
  const double left_at = run.at(10.2, "Ego").pose.y;
  CHECK(left_at != y0);
  CHECK(run.at(13.0, "Ego").pose.y == Approx(left_at).margin(1e-9));
  CHECK(heading_gap(run.at(13.0, "Ego").pose.h, 0.0) == Approx(0.0).margin(1e-12));
}

TEST_CASE("esmini's sloppyDriver varies the speed within its sloppiness, period by period",
          "[engine][controllers][sloppy]") {
  FixtureRun run(engine_fixture("controller_sloppy_driver_both.xosc"), sloppy_options());
  run.run();
  // First period: 3 s of its clock at the reference speed (its target factor is 1; esmini's
  // blend of 15 x (1 - w) + 15 x w, exact to rounding).
  for (int tick = 1; tick <= 30; ++tick) {
    CAPTURE(tick);
    CHECK(run.at(tick * 0.1, "Ego").speed == Approx(15.0).margin(1e-12));
  }
  // Then within 15 x (1 +- 0.35 x 0.5), and not constant.
  double slowest = 15.0, fastest = 15.0;
  for (int tick = 31; tick <= 300; ++tick) {
    const double speed = run.at(tick * 0.1, "Ego").speed;
    slowest = std::min(slowest, speed);
    fastest = std::max(fastest, speed);
  }
  CHECK(slowest >= 15.0 * (1.0 - 0.35 * 0.5));
  CHECK(fastest <= 15.0 * (1.0 + 0.35 * 0.5));
  CHECK(fastest - slowest > 0.5);
  // A run is the same again, and with another seed it differs.
  FixtureRun again(engine_fixture("controller_sloppy_driver_both.xosc"), sloppy_options());
  again.run();
  CHECK(again.now("Ego").pose.x == run.now("Ego").pose.x);
  CHECK(again.now("Ego").pose.y == run.now("Ego").pose.y);
  auto other = sloppy_options();
  other.seed = 7;
  FixtureRun reseeded(engine_fixture("controller_sloppy_driver_both.xosc"), other);
  reseeded.run();
  CHECK(reseeded.now("Ego").pose.x != run.now("Ego").pose.x);
}
