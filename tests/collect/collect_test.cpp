// The collect library on its own: --model texts, the capture windows of run.json, and whole
// data-collection runs through collect::run_dataset (complete, and stopped by the caller).

#include <tbb/global_control.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "corsa/collect/data_run.h"
#include "corsa/collect/dataset_run.h"
#include "corsa/core/atomic_file.h"
#include "corsa/sensors/preview.h"
#include "corsa/sensors/rig.h"
#include "dataset_check.h"
#include "temp_dir.h"

namespace {

namespace fs = std::filesystem;

corsa::collect::DatasetRunOptions small_run(const fs::path& output, double duration) {
  corsa::collect::DatasetRunOptions options;
  options.run.scenario = "scenarios/demo/cut_in_city.xosc";
  options.run.simulation.duration = duration;
  options.rig = "tests/collect/fixtures/small_rig.xml";
  options.output = output;
  return options;
}

}  // namespace

TEST_CASE("model texts give the file, the offset in metres and the heading in radians",
          "[collect][models]") {
  const corsa::collect::ModelSpec plain = corsa::collect::parse_model_spec("city/block.glb");
  CHECK(plain.file == "city/block.glb");
  CHECK(plain.placement.offset.x == 0.0);
  CHECK(plain.placement.heading == 0.0);

  const corsa::collect::ModelSpec placed = corsa::collect::parse_model_spec("a@b.obj@12.5, -3,90");
  CHECK(placed.file == "a@b.obj");  // the last '@' starts the placement
  CHECK(placed.placement.offset.x == 12.5);
  CHECK(placed.placement.offset.y == -3.0);
  CHECK(placed.placement.heading == Approx(std::numbers::pi / 2));

  for (const char* bad : {"m.obj@1", "m.obj@1,2,3,4", "m.obj@x,2", "m.obj@1,nan", "m.obj@"}) {
    INFO(bad);
    CHECK_THROWS_WITH(corsa::collect::parse_model_spec(bad),
                      Catch::Contains("expected FILE@X,Y[,HEADING_DEG]"));
  }
}

TEST_CASE("capture windows are recorded with their ticks, null while open", "[collect][windows]") {
  const std::vector<corsa::engine::CaptureWindow> windows{{"cam", 0, 120, 10.0},
                                                          {"lidar", 40, -1, 2.5}};
  const corsa::Json json = corsa::collect::capture_windows_json(windows);
  REQUIRE(json.size() == 2);
  CHECK(corsa::json_line(json[0]) ==
        R"({"sensor": "cam", "open_tick": 0, "close_tick": 120, "rate": 10})");
  CHECK(corsa::json_line(json[1]) ==
        R"({"sensor": "lidar", "open_tick": 40, "close_tick": null, "rate": 2.5})");
}

TEST_CASE("a library call collects a complete dataset", "[collect][run]") {
  corsa::test::TempDir dir;
  const auto options = small_run(dir.path() / "data", 0.2);
  corsa::Diagnostics diagnostics;
  int64_t steps = 0;
  corsa::collect::DatasetRunHooks hooks;
  hooks.on_step = [&steps](const corsa::engine::Simulation&) { ++steps; };
  const corsa::collect::DatasetRunReport report =
      corsa::collect::run_dataset(options, diagnostics, hooks);
  CHECK_FALSE(report.interrupted);
  CHECK(report.dataset_started);
  CHECK(steps == 20);
  CHECK(report.run.steps == 20);
  // 0.2 s at dt 0.01: ticks 0..20; the 10 Hz sensors at 0, 10, 20, the 5 Hz ones at 0 and 20.
  CHECK(report.captures == 3);
  CHECK(report.files == static_cast<int64_t>(corsa::test::read_index(options.output).size()));
  CHECK(corsa::test::check_dataset(options.output, 192, 108).empty());
  const std::string run_json = corsa::read_file(options.output / "run.json");
  CHECK(corsa::test::json_string(run_json, "status") == "complete");
  CHECK_FALSE(report.preview.has_value());
}

TEST_CASE("a run the caller stops leaves a consistent dataset that says why",
          "[collect][run][interrupt]") {
  corsa::test::TempDir dir;
  const auto options = small_run(dir.path() / "data", 5.0);
  corsa::Diagnostics diagnostics;
  int64_t last_tick = 0;
  bool simulated = false;
  corsa::collect::DatasetRunHooks hooks;
  hooks.on_step = [&last_tick](const corsa::engine::Simulation& s) { last_tick = s.tick(); };
  hooks.stop = [&last_tick]() -> std::optional<std::string> {
    return last_tick >= 15 ? std::optional<std::string>("stopped by the test") : std::nullopt;
  };
  hooks.on_simulated = [&simulated] { simulated = true; };
  const corsa::collect::DatasetRunReport report =
      corsa::collect::run_dataset(options, diagnostics, hooks);
  CHECK(report.interrupted);
  CHECK(report.interruption == "stopped by the test");
  CHECK(simulated);
  CHECK(report.captures == 2);  // ticks 0 and 10
  CHECK(corsa::test::check_dataset(options.output, 192, 108).empty());
  const std::string run_json = corsa::read_file(options.output / "run.json");
  CHECK(corsa::test::json_string(run_json, "status") == "interrupted");
  CHECK(corsa::test::json_string(run_json, "end_reason") == "stopped by the test");
}

TEST_CASE("a rig that cannot be read stops the run before any dataset folder appears",
          "[collect][run][errors]") {
  corsa::test::TempDir dir;
  auto options = small_run(dir.path() / "data", 0.1);
  options.rig = dir.path() / "missing_rig.xml";
  corsa::Diagnostics diagnostics;
  CHECK_THROWS_AS(corsa::collect::run_dataset(options, diagnostics), corsa::InputError);
  CHECK_FALSE(fs::exists(options.output));
}

TEST_CASE("entity model texts name an entity or a category and the file",
          "[collect][models][entity-model]") {
  const std::vector<std::string> entities{"Ego", "Cutter"};
  const auto ego = corsa::collect::parse_entity_model_spec("Ego=models/ego.glb");
  CHECK(ego.who == "Ego");
  CHECK(ego.file == "models/ego.glb");
  const corsa::sensors::EntityModel by_name = corsa::collect::resolve_entity_model(ego, entities);
  CHECK(by_name.entity == "Ego");
  CHECK(by_name.category.empty());
  CHECK(by_name.origin == "--entity-model Ego=models/ego.glb");
  const corsa::sensors::EntityModel by_category = corsa::collect::resolve_entity_model(
      corsa::collect::parse_entity_model_spec("pedestrian=a=b.obj"), entities);
  CHECK(by_category.category == "pedestrian");
  CHECK(by_category.file == "a=b.obj");  // the first '=' ends the name
  for (const char* bad : {"car", "=car.glb", "car=", " =x.obj"}) {
    INFO(bad);
    CHECK_THROWS_WITH(corsa::collect::parse_entity_model_spec(bad),
                      Catch::Contains("expected WHO=FILE"));
  }
  try {
    corsa::collect::resolve_entity_model(corsa::collect::parse_entity_model_spec("Eg=x.glb"),
                                         entities);
    FAIL("a name that is neither an entity nor a category was taken");
  } catch (const corsa::InputError& error) {
    CHECK(error.diagnostic().file == "--entity-model Eg=x.glb");
    CHECK_THAT(error.diagnostic().message,
               Catch::Contains("neither an entity of the scenario nor a category") &&
                   Catch::Contains("did you mean 'Ego'?"));
  }
}

TEST_CASE(
    "a command-line entity model wins over the rig's and an unreadable one is a warning at the "
    "option while the generated shape stands in",
    "[collect][run][entity-model]") {
  corsa::test::TempDir dir;
  // The rig names a model for cars too; the command line's comes first, so only its (missing)
  // file is tried and reported.
  std::string rig = corsa::read_file("tests/collect/fixtures/small_rig.xml");
  rig.replace(rig.find("</SensorRig>"), 12,
              "<EntityModel category=\"car\" file=\"rig_car.obj\"/></SensorRig>");
  corsa::write_file_atomic(dir.path() / "rig.xml", rig);
  auto options = small_run(dir.path() / "data", 0.1);
  options.rig = dir.path() / "rig.xml";
  const std::string missing = (dir.path() / "nothere.glb").string();
  options.entity_models.push_back(corsa::collect::parse_entity_model_spec("car=" + missing));
  std::vector<corsa::Diagnostic> warnings;
  corsa::Diagnostics diagnostics([&](const corsa::Diagnostic& d) {
    if (d.message.find("model") != std::string::npos) {
      warnings.push_back(d);
    }
  });
  const auto report = corsa::collect::run_dataset(options, diagnostics);
  CHECK(report.dataset_started);
  CHECK(corsa::test::check_dataset(options.output, 192, 108).empty());
  REQUIRE(warnings.size() == 1);  // once for the file, not once per car
  CHECK(warnings[0].file == "--entity-model car=" + missing);
  CHECK(warnings[0].line == 0);
  CHECK_THAT(warnings[0].message, Catch::Contains("nothere.glb") && Catch::Contains("stand in"));
}

TEST_CASE(
    "the preview video encoded during a run is the same bytes on one and two threads, and the "
    "video encoded from the dataset's files",
    "[collect][run][preview]") {
  corsa::test::TempDir dir;
  std::vector<std::string> videos;
  fs::path dataset;
  for (const int threads : {1, 2}) {
    // The camera's and the encoder's threads both come from this limit.
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    auto options = small_run(dir.path() / ("data" + std::to_string(threads)), 1.0);
    options.preview = true;
    options.run.simulation.threads = static_cast<unsigned>(threads);
    corsa::Diagnostics diagnostics;
    const auto report = corsa::collect::run_dataset(options, diagnostics);
    REQUIRE(report.preview.has_value());
    CHECK(report.preview->codec == "avc1");
    CHECK(report.preview->frames == 11);  // the 10 Hz camera over 1 s: ticks 0, 10, ..., 100
    REQUIRE(fs::exists(report.preview->video));
    videos.push_back(corsa::read_file(report.preview->video));
    dataset = options.output;
  }
  REQUIRE(videos.size() == 2);
  CHECK_FALSE(videos[0].empty());
  CHECK(videos[0] == videos[1]);
  // Encoded again from the files, without the streamed video.
  corsa::Diagnostics diagnostics;
  const corsa::sensors::PreviewReport from_files = corsa::sensors::write_preview(
      dataset, corsa::sensors::load_rig("tests/collect/fixtures/small_rig.xml"), diagnostics);
  CHECK(from_files.frames == 11);
  CHECK(corsa::read_file(from_files.video) == videos[0]);
}
