// The capture timeline: capture ticks on the integer grid (no drift, rates that do not divide the
// step), corsa:capture windows opened and closed by the storyboard, located errors.

#include "corsa/engine/capture_timeline.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "corsa/engine/run.h"
#include "corsa/engine/simulation.h"
#include "corsa/xosc/scenario.h"

namespace {

using corsa::engine::CaptureTimeline;
using corsa::engine::Fraction;

const std::filesystem::path kWindows =
    std::filesystem::path(CORSA_SOURCE_DIR) / "tests/capture/fixtures/capture_windows.xosc";

// Remembers which sensors were captured at which tick.
class RecordingSink final : public corsa::engine::CaptureSink {
 public:
  void capture(const corsa::engine::WorldSnapshot& world,
               std::span<const std::string> sensors) override {
    for (const std::string& s : sensors) {
      ticks[s].push_back(world.tick);
    }
    entities = world.entities.size();
  }
  std::map<std::string, std::vector<int64_t>> ticks;
  size_t entities = 0;
};

corsa::xosc::Scenario scenario_from(const std::string& storyboard_extra, corsa::Diagnostics& d) {
  const std::string xml =
      "<OpenSCENARIO><FileHeader revMajor=\"1\" revMinor=\"3\" date=\"2026-01-01T00:00:00\" "
      "description=\"t\" author=\"t\"/><ParameterDeclarations/><CatalogLocations/>"
      "<RoadNetwork/><Entities/><Storyboard><Init><Actions>" +
      storyboard_extra +
      "</Actions></Init><StopTrigger><ConditionGroup><Condition name=\"end\" delay=\"0\" "
      "conditionEdge=\"none\"><ByValueCondition><SimulationTimeCondition value=\"1\" "
      "rule=\"greaterOrEqual\"/></ByValueCondition></Condition></ConditionGroup></StopTrigger>"
      "</Storyboard></OpenSCENARIO>";
  return corsa::xosc::parse_scenario(xml, "inline.xosc", {}, d);
}

// The tick at which a storyboard element entered the running state.
int64_t start_tick(const corsa::engine::Simulation& sim, const std::string& suffix) {
  for (const auto& t : sim.transitions()) {
    if (t.path.ends_with(suffix) && t.state == corsa::engine::ElementState::kRunning) {
      return t.tick;
    }
  }
  FAIL("no start transition for " << suffix);
  return -1;
}

}  // namespace

TEST_CASE("Decimal steps and rates become exact fractions", "[capture][ticks]") {
  CHECK(corsa::engine::exact_fraction(0.01).num == 1);
  CHECK(corsa::engine::exact_fraction(0.01).den == 100);
  CHECK(corsa::engine::exact_fraction(3.3).num == 33);
  CHECK(corsa::engine::exact_fraction(3.3).den == 10);
  CHECK(corsa::engine::exact_fraction(10.0).num == 10);
  CHECK(corsa::engine::exact_fraction(10.0).den == 1);
  const Fraction period = corsa::engine::capture_period(10.0, 0.01);
  CHECK(period.num == 10);
  CHECK(period.den == 1);
}

TEST_CASE("A rate that does not divide the step is scheduled without drift", "[capture][ticks]") {
  // 3 Hz at dt = 0.01 s: 100/3 ticks per frame, frame k at ceil(100 k / 3).
  const Fraction period = corsa::engine::capture_period(3.0, 0.01);
  CHECK(period.num == 100);
  CHECK(period.den == 3);
  const std::vector<int64_t> expected{0, 34, 67, 100, 134, 167, 200};
  for (size_t k = 0; k < expected.size(); ++k) {
    CHECK(corsa::engine::capture_tick(0, period, static_cast<int64_t>(k)) == expected[k]);
  }
  // After a million frames (92 hours) frame k = 3 m is still exactly on second m.
  CHECK(corsa::engine::capture_tick(0, period, 3'000'000) == 100'000'000);
  CHECK(corsa::engine::capture_tick(0, period, 3'000'001) == 100'000'034);
  // 7 Hz at dt = 0.02 s (50/7 ticks) from a window opened at tick 5.
  const Fraction seven = corsa::engine::capture_period(7.0, 0.02);
  CHECK(corsa::engine::capture_tick(5, seven, 7) == 55);
  CHECK(corsa::engine::capture_tick(5, seven, 1) == 5 + 8);
  // A window opened mid-grid starts at the next grid tick: 3 Hz opened at tick 35 -> 67.
  CHECK(corsa::engine::first_frame_at_or_after(0, period) == 0);
  CHECK(corsa::engine::first_frame_at_or_after(34, period) == 1);
  CHECK(corsa::engine::first_frame_at_or_after(35, period) == 2);
  CHECK(corsa::engine::capture_tick(0, period, 2) == 67);
}

TEST_CASE("Without corsa:capture actions every sensor is captured at its rate for the whole run",
          "[capture][ticks]") {
  corsa::Diagnostics d;
  const corsa::xosc::Scenario scenario = scenario_from("", d);
  CaptureTimeline timeline({{"camera", 10.0}, {"lidar", 3.0}}, scenario, 0.01, d);
  std::map<std::string, std::vector<int64_t>> seen;
  for (int64_t tick = 0; tick <= 100; ++tick) {
    for (const std::string& s : timeline.take_due(tick)) {
      seen[s].push_back(tick);
    }
  }
  CHECK(seen["camera"] == std::vector<int64_t>{0, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100});
  CHECK(seen["lidar"] == std::vector<int64_t>{0, 34, 67, 100});
}

TEST_CASE("A rate above the step rate captures every step and warns once", "[capture][ticks]") {
  corsa::Diagnostics d;
  const corsa::xosc::Scenario scenario = scenario_from("", d);
  CaptureTimeline timeline({{"fast", 500.0}}, scenario, 0.01, d);
  int captured = 0;
  for (int64_t tick = 0; tick < 10; ++tick) {
    captured += static_cast<int>(timeline.take_due(tick).size());
  }
  CHECK(captured == 10);
  CHECK(d.count(corsa::Severity::kWarning) == 1);
}

TEST_CASE("Capture windows open and close where the storyboard's actions start",
          "[capture][windows]") {
  corsa::Diagnostics d;
  const corsa::xosc::Scenario scenario = corsa::xosc::load_scenario(kWindows, {}, d);
  corsa::engine::Simulation sim(scenario, corsa::engine::load_road_network(scenario, d), {}, d);
  CaptureTimeline timeline({{"camera", 10.0}, {"lidar", 10.0}}, scenario, sim.dt(), d);
  RecordingSink sink;
  timeline.attach(sim, sink);
  sim.run();

  const int64_t open = start_tick(sim, "::OpenCamera") + 1;
  const int64_t close = start_tick(sim, "::CloseCamera");
  const int64_t all = start_tick(sim, "::AllSlow") + 1;
  CHECK(open == 101);  // SimulationTime >= 1 holds at tick 100; the window opens after it
  REQUIRE(close > open);
  REQUIRE(all > close);
  // Frames stay on each rate's grid from tick 0: 5 Hz every 20 ticks, 3 Hz at ceil(100 k / 3).
  const auto three_hz = [](int64_t k) { return (k * 100 + 2) / 3; };
  std::vector<int64_t> camera;
  for (int64_t t = 0; t <= close; t += 20) {
    if (t >= open) {
      camera.push_back(t);
    }
  }
  std::vector<int64_t> slow;
  for (int64_t k = 0; three_hz(k) <= sim.tick(); ++k) {
    if (three_hz(k) >= all) {
      slow.push_back(three_hz(k));
    }
  }
  camera.insert(camera.end(), slow.begin(), slow.end());
  CHECK(camera.front() == 120);
  CHECK(sink.ticks["camera"] == camera);

  std::vector<int64_t> lidar;
  for (int64_t t = 0; t < all; t += 10) {  // the Init window at the rig rate, then 3 Hz
    lidar.push_back(t);
  }
  lidar.insert(lidar.end(), slow.begin(), slow.end());
  CHECK(sink.ticks["lidar"] == lidar);
  CHECK(sink.entities == 1);

  const auto windows = timeline.windows();
  REQUIRE(windows.size() == 4);  // lidar (Init), camera 5 Hz, then both again at 3 Hz
  CHECK(windows[0].sensor == "lidar");
  CHECK(windows[0].open_tick == 0);
  CHECK(windows[0].close_tick == all - 1);
  CHECK(windows[1].sensor == "camera");
  CHECK(windows[1].close_tick == close);
  CHECK(windows[1].rate_hz == 5.0);
}

TEST_CASE("The same run captures the same ticks twice", "[capture][determinism]") {
  std::map<std::string, std::vector<int64_t>> runs[2];
  for (auto& run : runs) {
    corsa::Diagnostics d;
    const corsa::xosc::Scenario scenario = corsa::xosc::load_scenario(kWindows, {}, d);
    corsa::engine::Simulation sim(scenario, corsa::engine::load_road_network(scenario, d), {}, d);
    CaptureTimeline timeline({{"camera", 10.0}, {"lidar", 10.0}}, scenario, sim.dt(), d);
    RecordingSink sink;
    timeline.attach(sim, sink);
    sim.run();
    run = sink.ticks;
  }
  CHECK(runs[0] == runs[1]);
  CHECK(!runs[0]["camera"].empty());
}

TEST_CASE("Bad corsa:capture content is reported at the action's line", "[capture][errors]") {
  const auto error_for = [](const std::string& content) -> std::string {
    corsa::Diagnostics d;
    const corsa::xosc::Scenario scenario =
        scenario_from("\n<UserDefinedAction><CustomCommandAction type=\"corsa:capture\">" +
                          content + "</CustomCommandAction></UserDefinedAction>",
                      d);
    try {
      CaptureTimeline timeline({{"camera", 10.0}}, scenario, 0.01, d);
    } catch (const corsa::InputError& e) {
      return e.diagnostic().format();
    }
    return "no error";
  };
  CHECK_THAT(error_for("begin"), Catch::Contains("inline.xosc:2: error: corsa:capture") &&
                                     Catch::Contains("does not begin with start or stop"));
  CHECK_THAT(error_for("start rate=-1"), Catch::Contains("rate '-1' is not a positive number"));
  CHECK_THAT(error_for("stop rate=5"), Catch::Contains("unexpected 'rate=5'"));
  CHECK_THAT(error_for("start sensors=camera"), Catch::Equals("no error"));
}

TEST_CASE("A capture action naming a sensor the rig lacks warns and leaves it out",
          "[capture][windows]") {
  std::vector<corsa::Diagnostic> warnings;
  corsa::Diagnostics d([&warnings](const corsa::Diagnostic& w) { warnings.push_back(w); });
  const corsa::xosc::Scenario scenario = scenario_from(
      "\n<UserDefinedAction><CustomCommandAction type=\"corsa:capture\">start sensors=camra,radar"
      "</CustomCommandAction></UserDefinedAction>",
      d);
  corsa::engine::Simulation sim(scenario, nullptr, {}, d);
  CaptureTimeline timeline({{"camera", 10.0}, {"lidar", 10.0}}, scenario, sim.dt(), d);
  RecordingSink sink;
  timeline.attach(sim, sink);
  sim.run();
  // Each unknown name warns once (not again when the action runs), located at the action.
  std::vector<std::string> texts;
  for (const corsa::Diagnostic& w : warnings) {
    if (w.message.find("corsa:capture") != std::string::npos) {
      texts.push_back(w.format());
    }
  }
  REQUIRE(texts.size() == 2);
  CHECK_THAT(texts[0], Catch::Contains("inline.xosc:2: warning: corsa:capture: the rig has no "
                                       "sensor 'camra' (did you mean 'camera'?)"));
  CHECK_THAT(texts[1],
             Catch::Contains("no sensor 'radar'") && Catch::Contains("(sensors: camera, lidar)"));
  // A start that names only unknown sensors opens nothing (not every sensor).
  CHECK(sink.ticks.empty());
}

TEST_CASE("A corsa:capture Init action opens the window at tick 0", "[capture][windows]") {
  corsa::Diagnostics d;
  const corsa::xosc::Scenario scenario = scenario_from(
      "<UserDefinedAction><CustomCommandAction type=\"corsa:capture\">start rate=2"
      "</CustomCommandAction></UserDefinedAction>",
      d);
  corsa::engine::Simulation sim(scenario, nullptr, {}, d);
  CaptureTimeline timeline({{"camera", 10.0}}, scenario, sim.dt(), d);
  RecordingSink sink;
  timeline.attach(sim, sink);
  sim.run();
  CHECK(sink.ticks["camera"] == std::vector<int64_t>{0, 50, 100});
  CHECK(timeline.captures() == 3);
}
