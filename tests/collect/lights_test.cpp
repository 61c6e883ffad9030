// Vehicle lights in the camera labels: a braking car whose indicator a LightStateAction flashes
// green is labelled, frame by frame, with its brake lamps on, its indicator flashing (lit or in
// its off phase) and the colour and intensity the scenario gave, as the image shows it; the run
// summary records when each light was set; the labels are the same bytes on one and two threads.

#include <tbb/global_control.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "corsa/collect/dataset_run.h"
#include "corsa/core/atomic_file.h"
#include "dataset_check.h"
#include "temp_dir.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// The braking_lights scenario captured into `out` on `threads` threads (engine and sensors).
void capture_braking_lights(const fs::path& out, int threads) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  corsa::collect::DatasetRunOptions options;
  options.run.scenario = "tests/collect/fixtures/braking_lights.xosc";
  options.run.simulation.threads = static_cast<unsigned>(threads);
  options.run.summary = out.parent_path() / (out.filename().string() + "_summary.json");
  options.rig = "tests/collect/fixtures/lights_rig.xml";
  options.output = out;
  corsa::Diagnostics diagnostics;
  corsa::collect::run_dataset(options, diagnostics);
}

/// The label object of the entity `name` in a camera label file.
json object_named(const fs::path& labels, const std::string& name) {
  const json document = json::parse(corsa::read_file(labels));
  for (const json& object : document.at("objects")) {
    if (object.at("name") == name) {
      return object;
    }
  }
  FAIL("no label of " << name << " in " << labels);
  return {};
}

/// Pixels of instance `id` in a frame that show a lit lamp of a colour: bright in `channel`,
/// dark in the other two.
int lamp_pixels(const fs::path& dataset, const std::string& frame, uint32_t id, int channel) {
  const cv::Mat rgb = cv::imread((dataset / "cam" / (frame + ".png")).string(), cv::IMREAD_COLOR);
  const cv::Mat ids =
      cv::imread((dataset / "instance" / (frame + ".png")).string(), cv::IMREAD_UNCHANGED);
  REQUIRE(!rgb.empty());
  REQUIRE(ids.type() == CV_16UC1);
  int n = 0;
  for (int y = 0; y < rgb.rows; ++y) {
    for (int x = 0; x < rgb.cols; ++x) {
      if (ids.at<uint16_t>(y, x) != id) {
        continue;
      }
      const cv::Vec3b bgr = rgb.at<cv::Vec3b>(y, x);
      const int c[3] = {bgr[2], bgr[1], bgr[0]};  // r, g, b
      const int others = std::max(c[(channel + 1) % 3], c[(channel + 2) % 3]);
      n += c[channel] > 170 && others < c[channel] / 2 ? 1 : 0;
    }
  }
  return n;
}

std::vector<std::string> lamps(const json& object) {
  return object.at("lamps").get<std::vector<std::string>>();
}

}  // namespace

TEST_CASE(
    "Camera labels give a braking car's brake lamps and its flashing green indicator as "
    "drawn, and the summary says when the lights were set",
    "[collect][lights]") {
  corsa::test::TempDir dir;
  const fs::path a = dir.path() / "one_thread";
  const fs::path b = dir.path() / "two_threads";
  capture_braking_lights(a, 1);
  capture_braking_lights(b, 2);
  // Frames 0..3 at 0, 0.4, 0.8 and 1.2 s; every file the same bytes on one and two threads.
  const auto files = corsa::test::files_under(a);
  REQUIRE(files == corsa::test::files_under(b));
  for (const std::string& file : files) {
    INFO(file);
    CHECK(corsa::read_file(a / file) == corsa::read_file(b / file));
  }
  const fs::path cam = a / "cam";
  const json before = object_named(cam / "000001_labels.json", "Lead");
  const json lit = object_named(cam / "000002_labels.json", "Lead");
  const json dark_phase = object_named(cam / "000003_labels.json", "Lead");
  INFO(before.dump() << "\n" << lit.dump() << "\n" << dark_phase.dump());
  const auto id = before.at("instance_id").get<uint32_t>();

  // 0.4 s: driving steadily at noon, nothing set: no light on, no lamp lit.
  CHECK(before.at("lights") == json::object());
  CHECK(lamps(before).empty());

  // 0.8 s: braking at 4 m/s^2, the indicator in its first on phase (0.51 .. 0.91 s).
  const json brake = {{"mode", "on"}, {"lit", true}};
  CHECK(lit.at("lights").at("brakeLights") == brake);
  CHECK(lit.at("lights").at("indicatorLeft") == json{{"mode", "flashing"},
                                                     {"lit", true},
                                                     {"set", true},
                                                     {"intensity_cd", 200},
                                                     {"colour", {0, 1, 0}}});
  CHECK(lit.at("lights").at("lowBeam") == json{{"mode", "off"}, {"lit", false}, {"set", true}});
  CHECK(lit.at("lights").size() == 3);
  CHECK(lamps(lit) == std::vector<std::string>{"brake", "indicator_left"});

  // 1.2 s: still braking, the indicator flashing in its off phase (0.91 .. 1.31 s).
  CHECK(dark_phase.at("lights").at("brakeLights") == brake);
  CHECK(dark_phase.at("lights").at("indicatorLeft").at("mode") == "flashing");
  CHECK(dark_phase.at("lights").at("indicatorLeft").at("lit") == false);
  CHECK(dark_phase.at("lights").at("indicatorLeft").at("colour") == json{0, 1, 0});
  CHECK(lamps(dark_phase) == std::vector<std::string>{"brake"});

  // The image agrees: red lamp pixels on Lead only while the label says its brake lamps are
  // lit, green ones only while its indicator is.
  const int red[3] = {lamp_pixels(a, "000001", id, 0), lamp_pixels(a, "000002", id, 0),
                      lamp_pixels(a, "000003", id, 0)};
  const int green[3] = {lamp_pixels(a, "000001", id, 1), lamp_pixels(a, "000002", id, 1),
                        lamp_pixels(a, "000003", id, 1)};
  INFO("red lamp pixels " << red[0] << " " << red[1] << " " << red[2] << ", green " << green[0]
                          << " " << green[1] << " " << green[2]);
  CHECK(red[0] == 0);
  CHECK(red[1] > 0);
  CHECK(red[2] > 0);
  CHECK(green[0] == 0);
  CHECK(green[1] > 0);
  CHECK(green[2] == 0);

  // The record of the run: when each light was set, and how.
  const json summary = json::parse(corsa::read_file(dir.path() / "one_thread_summary.json"));
  json lead_lights;
  for (const json& entity : summary.at("entities")) {
    CHECK((entity.at("name") == "Lead") == entity.contains("lights"));
    if (entity.at("name") == "Lead") {
      lead_lights = entity.at("lights");
    }
  }
  CHECK(lead_lights == json::parse(R"([
      {"time": 0.51, "light": "indicatorLeft", "mode": "flashing", "flashing": [0.4, 0.4],
       "intensity_cd": 200, "colour": [0, 1, 0]},
      {"time": 0.51, "light": "lowBeam", "mode": "off"}])"));
}
