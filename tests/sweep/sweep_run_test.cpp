#include <catch2/catch.hpp>
#include <filesystem>

#include "corsa/core/atomic_file.h"
#include "corsa/sweep/shared_inputs.h"
#include "corsa/sweep/summary_table.h"
#include "corsa/sweep/sweep.h"
#include "corsa/sweep/variant_run.h"
#include "sweep_fixtures.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using corsa::Diagnostics;
using corsa::InputError;
using corsa::read_file;
using corsa::sweep::parse_grid_axis;
using corsa::sweep::run_sweep;
using corsa::sweep::SweepOptions;
using corsa::sweep::VariantPlan;
using corsa::sweep::test::csv_rows;
using corsa::sweep::test::distribution_plan;
using corsa::sweep::test::fixture;
using corsa::sweep::test::summary_without_wall_time;
using corsa::sweep::test::without_timing;
using corsa::test::TempDir;
using Approx = Catch::Detail::Approx;

namespace {

SweepOptions options_for(const fs::path& out, size_t jobs) {
  SweepOptions options;
  options.output = out;
  options.jobs = jobs;
  options.record_every = 10;
  return options;
}

corsa::sweep::VariantResult run_follow(const corsa::sweep::ParameterValues& parameters) {
  Diagnostics diagnostics;
  corsa::sweep::SharedInputs inputs(fixture("follow.xosc"), diagnostics);
  corsa::sweep::VariantSpec spec;
  spec.parameters = parameters;
  return corsa::sweep::run_variant(inputs, spec, {}, diagnostics);
}

}  // namespace

TEST_CASE("a sweep writes the same files whatever the thread count", "[sweep][run]") {
  TempDir dir;
  const VariantPlan plan = distribution_plan("grid.xosc");
  Diagnostics diagnostics;
  const auto one = run_sweep(plan, options_for(dir.path() / "j1", 1), diagnostics);
  const auto two = run_sweep(plan, options_for(dir.path() / "j2", 2), diagnostics);
  CHECK(one.variants == 12);
  CHECK(one.ran == 12);
  CHECK(one.failed == 0);
  CHECK(two.ran == 12);
  const auto rows = csv_rows(dir.path() / "j1" / "summary.csv");
  REQUIRE(rows.size() == 13);
  CHECK(rows[0] == std::vector<std::string>{"index", "Ego_Speed", "Lane", "Gap", "Lead_Speed",
                                            "status", "exit_status", "end_reason", "sim_time",
                                            "steps", "collisions", "min_ttc", "min_distance",
                                            "max_deceleration", "error", "wall_time"});
  CHECK(rows[12][0] == "11");
  CHECK(rows[12][5] == "ok");
  CHECK(summary_without_wall_time(dir.path() / "j1") ==
        summary_without_wall_time(dir.path() / "j2"));
  CHECK(read_file(dir.path() / "j1" / "sweep.json") == read_file(dir.path() / "j2" / "sweep.json"));
  for (size_t i = 0; i < 12; ++i) {
    const fs::path a = dir.path() / "j1" / "variants" / std::to_string(i);
    const fs::path b = dir.path() / "j2" / "variants" / std::to_string(i);
    CHECK(read_file(a / "trajectory.csv") == read_file(b / "trajectory.csv"));
    CHECK(without_timing(read_file(a / "summary.json")) ==
          without_timing(read_file(b / "summary.json")));
  }
}

TEST_CASE("--resume runs only the variants that did not finish", "[sweep][run]") {
  TempDir dir;
  const fs::path out = dir.path() / "out";
  const VariantPlan plan = distribution_plan("grid.xosc");
  Diagnostics diagnostics;
  run_sweep(plan, options_for(out, 2), diagnostics);
  const std::string before = summary_without_wall_time(out);
  const std::string trajectory = read_file(out / "variants" / "7" / "trajectory.csv");
  fs::remove(out / "variants" / "3" / "result.csv");  // interrupted after its trajectory
  fs::remove_all(out / "variants" / "7");             // never started
  fs::remove(out / "summary.csv");

  SECTION("resuming finishes the sweep with the same results") {
    SweepOptions options = options_for(out, 2);
    options.resume = true;
    const auto report = run_sweep(plan, options, diagnostics);
    CHECK(report.ran == 2);
    CHECK(report.resumed == 10);
    CHECK(summary_without_wall_time(out) == before);
    CHECK(read_file(out / "variants" / "7" / "trajectory.csv") == trajectory);
  }
  SECTION("an earlier sweep is not overwritten without --resume or --force") {
    CHECK_THROWS_WITH(run_sweep(plan, options_for(out, 2), diagnostics),
                      Catch::Contains("holds a sweep already"));
    SweepOptions forced = options_for(out, 2);
    forced.force = true;
    CHECK(run_sweep(plan, forced, diagnostics).ran == 12);
  }
  SECTION("another sweep cannot be resumed in the folder") {
    SweepOptions options = options_for(out, 2);
    options.resume = true;
    options.simulation.dt = 0.02;
    CHECK_THROWS_WITH(run_sweep(plan, options, diagnostics),
                      Catch::Contains("holds a different sweep"));
  }
}

TEST_CASE("a failing variant is recorded and the sweep goes on", "[sweep][run]") {
  TempDir dir;
  const VariantPlan plan = VariantPlan::from_scenario(
      fixture("follow.xosc"), {parse_grid_axis("Lane=-9,-2"), parse_grid_axis("Gap=30,50")});
  Diagnostics diagnostics;
  const auto report = run_sweep(plan, options_for(dir.path(), 2), diagnostics);
  CHECK(report.variants == 4);
  CHECK(report.failed == 2);
  REQUIRE(report.first_failures.size() == 2);
  CHECK(report.first_failures[0].first == 0);
  const auto rows = csv_rows(dir.path() / "summary.csv");
  REQUIRE(rows.size() == 5);
  const auto& failed = rows[1];
  CHECK(failed[3] == "error");
  CHECK(failed[4] == "2");
  CHECK(failed[5].empty());  // no end reason
  CHECK(failed[12].find("follow.xosc:") != std::string::npos);
  CHECK(failed[12].find("error:") != std::string::npos);
  CHECK_FALSE(fs::exists(dir.path() / "variants" / "0" / "trajectory.csv"));
  CHECK(fs::exists(dir.path() / "variants" / "0" / "result.csv"));
  CHECK(rows[3][3] == "ok");
  CHECK(rows[4][3] == "ok");
  CHECK(fs::exists(dir.path() / "variants" / "3" / "trajectory.csv"));
}

TEST_CASE("a bad plan fails before anything is written", "[sweep][run]") {
  TempDir dir;
  Diagnostics diagnostics;
  // Strictly, a distribution over a parameter the scenario lacks is a bad plan.
  auto options = options_for(dir.path() / "o", 1);
  options.simulation.strict = true;
  CHECK_THROWS_AS(run_sweep(distribution_plan("undeclared.xosc"), options, diagnostics),
                  InputError);
  CHECK_FALSE(fs::exists(dir.path() / "o"));
}

TEST_CASE("the metrics follow the ego's braking and the gap to the lead", "[sweep][metrics]") {
  const auto calm = run_follow({});
  REQUIRE(calm.ok());
  CHECK(calm.metrics.ego == "Ego");
  CHECK(calm.collisions == 0);
  CHECK(calm.end_reason == corsa::engine::EndReason::kStopTrigger);
  REQUIRE(calm.metrics.max_deceleration.value);
  CHECK(*calm.metrics.max_deceleration.value == Approx(4.0).margin(0.05));
  // 35.6 m free space closing at 10 m/s, braking at 4 m/s^2 from the start: about 23 m left.
  REQUIRE(calm.metrics.min_distance.value);
  CHECK(*calm.metrics.min_distance.value == Approx(23.1).margin(1.0));
  CHECK(calm.metrics.min_distance.other == "Lead");
  REQUIRE(calm.metrics.min_ttc.value);
  CHECK(*calm.metrics.min_ttc.value > 2.0);

  const auto crash = run_follow({{"Brake_Rate", "0.5"}});
  REQUIRE(crash.ok());
  CHECK(crash.collisions == 1);
  CHECK(crash.ego_collisions == 1);
  CHECK(crash.first_collision.find("Ego and Lead at t=") == 0);
  CHECK(*crash.metrics.min_distance.value == 0.0);
  CHECK(*crash.metrics.min_ttc.value == 0.0);
  CHECK(crash.sim_time < 6.0);
}

TEST_CASE("variants share one map and parse the catalogs once", "[sweep][run]") {
  Diagnostics diagnostics;
  corsa::sweep::SharedInputs inputs(fixture("follow.xosc"), diagnostics);
  for (const char* speed : {"20", "25", "30"}) {
    corsa::sweep::VariantSpec spec;
    spec.parameters = {{"Ego_Speed", speed}};
    CHECK(corsa::sweep::run_variant(inputs, spec, {}, diagnostics).ok());
  }
  CHECK(inputs.maps_loaded() == 1);
  CHECK(inputs.catalog_files() == 1);
}

TEST_CASE("an unknown ego is the variant's error", "[sweep][run]") {
  Diagnostics diagnostics;
  corsa::sweep::SharedInputs inputs(fixture("follow.xosc"), diagnostics);
  corsa::sweep::VariantSpec spec;
  spec.ego = "Nobody";
  const auto result = corsa::sweep::run_variant(inputs, spec, {}, diagnostics);
  CHECK(result.status == corsa::sweep::VariantStatus::kBadInput);
  CHECK(result.error.find("the ego entity 'Nobody'") != std::string::npos);
}

TEST_CASE("a ghost run counts its steps from the head start and measures no distance to the ghost",
          "[sweep][run]") {
  // esmini's followGhost: the run starts at -2 s; Ego_ghost stands on Ego until it drives off.
  Diagnostics diagnostics;
  corsa::sweep::SharedInputs inputs(
      fs::path(CORSA_SOURCE_DIR) / "tests/engine/fixtures/controller_follow_ghost.xosc",
      diagnostics);
  const auto result = corsa::sweep::run_variant(inputs, {}, {}, diagnostics);
  CHECK(result.steps == 1700);
  // The nearest entity is Other, in lane -3, beside Ego once Ego is in lane -2 (3.5 m between
  // the lanes' centres, less the 2 m width); the ghost would be 0 m.
  REQUIRE(result.metrics.min_distance.value);
  CHECK(*result.metrics.min_distance.value > 1.0);
  CHECK(result.metrics.min_distance.other == "Other");
}
