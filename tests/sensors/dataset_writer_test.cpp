// DatasetWriter encodes a capture's files on TBB tasks while the next capture renders: the index
// must still name only complete captures and the bytes must not depend on the thread count.

#include "corsa/sensors/dataset_writer.h"

#include <tbb/global_control.h>

#include <catch2/catch.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "corsa/core/atomic_file.h"
#include "corsa/sensors/buildings.h"
#include "fixtures.h"
#include "temp_dir.h"

using namespace corsa::sensors;
namespace fs = std::filesystem;

namespace {

const char* const kRig = R"(<SensorRig version="1" name="pair">
  <RgbCamera name="rgb" entity="Ego" width="96" height="64" fov="90"><Mount x="1.5" z="1.4"/></RgbCamera>
  <DepthCamera name="depth" entity="Ego" width="96" height="64" fov="90"><Mount x="1.5" z="1.4"/></DepthCamera>
  <BirdsEyeCamera name="bev" entity="Ego" width="48" height="48" extent="60" style="rgb"/>
  <Lidar name="lidar" entity="Ego" channels="8" pointsPerSecond="28800" noiseStddev="0.02"><Mount z="1.9"/></Lidar>
</SensorRig>)";

corsa::engine::WorldSnapshot world(int64_t tick) {
  corsa::engine::WorldSnapshot w;
  w.tick = tick;
  w.time = 0.01 * static_cast<double>(tick);
  auto ego = corsa::test::box_entity(1, "Ego", 10.0 * w.time, 0.0, 4.5, 1.9, 1.5,
                                     corsa::engine::EntityCategory::kCar);
  ego.vx = 10.0;
  auto lead = corsa::test::box_entity(2, "Lead", 20.0 + 8.0 * w.time, 0.5, 4.5, 1.9, 1.5,
                                      corsa::engine::EntityCategory::kCar);
  lead.vx = 8.0;
  w.entities = {ego, lead};
  return w;
}

/// Every file under `dir` (relative path -> bytes).
std::map<std::string, std::string> contents(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.is_regular_file()) {
      out[fs::relative(entry.path(), dir).generic_string()] = corsa::read_file(entry.path());
    }
  }
  return out;
}

/// Three captures (the second without the cameras) into `dir`; returns captures() after each.
std::vector<int64_t> run(const fs::path& dir, int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  Scene scene;
  scene.add_road_mesh(corsa::test::flat_road(200.0));
  for (const Footprint& f : street_district(120.0, 10.0, 5)) {
    scene.add_static_mesh(extrude_footprint(f));
  }
  scene.commit();
  SensorRig rig = parse_rig(kRig, "pair.xml");
  bind_rig(rig, std::vector<std::string>{"Ego", "Lead"});
  SensorSystemOptions options;
  options.seed = 5;
  SensorSystem system(rig, scene, options);
  DatasetRunInfo info;
  info.scenario = "pair.xosc";
  DatasetWriter writer(system, dir, info, DatasetFormat::kCorsa, false);
  std::vector<int64_t> counted;
  const std::vector<std::string> lidar_only{"lidar"};
  for (int64_t tick : {0, 10, 20}) {
    writer.capture(world(tick), tick == 10 ? std::span<const std::string>(lidar_only)
                                           : std::span<const std::string>());
    counted.push_back(writer.captures());
  }
  DatasetEnd end;
  end.status = "complete";
  end.end_reason = "test";
  end.tick = 20;
  end.time = 0.2;
  writer.finish(end);
  counted.push_back(writer.captures());
  return counted;
}

}  // namespace

TEST_CASE("the dataset index names only captures whose files are all written",
          "[sensors][dataset]") {
  corsa::test::TempDir dir;
  const std::vector<int64_t> counted = run(dir.path() / "set", 2);
  // A capture is counted once indexed; finish() indexes the last one.
  for (size_t i = 0; i + 1 < counted.size(); ++i) {
    CHECK(counted[i] <= static_cast<int64_t>(i) + 1);
  }
  CHECK(counted.back() == 3);
  std::istringstream index(corsa::read_file(dir.path() / "set" / "frames.csv"));
  std::string line;
  std::getline(index, line);
  CHECK(line == "capture,tick,time,sensor,frame,file,overlap");
  size_t rows = 0;
  while (std::getline(index, line)) {
    const std::string without_overlap = line.substr(0, line.rfind(','));
    const std::string file = without_overlap.substr(without_overlap.rfind(',') + 1);
    CHECK(line.substr(line.rfind(',') + 1) == "0");  // nothing interpenetrates here
    INFO(line);
    CHECK(fs::exists(dir.path() / "set" / file));
    ++rows;
  }
  // Capture 0: rgb 2 files, depth 3, bev 1, lidar 5, pose 1; capture 1: lidar 5 + pose; 2 as 0.
  CHECK(rows == 12 + 6 + 12);
  CHECK_THAT(corsa::read_file(dir.path() / "set" / "run.json"), Catch::Contains("\"captures\": 3"));
}

TEST_CASE("a dataset written on one or two threads has the same bytes",
          "[sensors][dataset][determinism]") {
  corsa::test::TempDir a, b;
  run(a.path() / "set", 1);
  run(b.path() / "set", 2);
  const auto one = contents(a.path() / "set");
  const auto two = contents(b.path() / "set");
  REQUIRE(one.size() == two.size());
  CHECK(one.size() > 30);
  for (const auto& [name, bytes] : one) {
    INFO(name);
    REQUIRE(two.count(name) == 1);
    CHECK(two.at(name) == bytes);
  }
}

TEST_CASE("every dataset carries the class table with CARLA's ids and Cityscapes' colours",
          "[sensors][dataset]") {
  corsa::test::TempDir dir;
  run(dir.path() / "set", 1);
  const auto table = nlohmann::json::parse(corsa::read_file(dir.path() / "set" / "classes.json"));
  const auto& classes = table.at("classes");
  REQUIRE(classes.size() == static_cast<size_t>(kSemanticClassCount));
  std::map<std::string, int> ids;
  for (size_t i = 0; i < classes.size(); ++i) {
    CHECK(classes[i].at("id").get<size_t>() == i);
    ids[classes[i].at("name").get<std::string>()] = static_cast<int>(i);
  }
  CHECK(ids.at("road") == 1);
  CHECK(ids.at("sky") == 11);
  CHECK(ids.at("person") == 12);
  CHECK(ids.at("rider") == 13);
  CHECK(ids.at("car") == 14);
  CHECK(ids.at("lane_marking") == 24);
  CHECK(classes[14].at("color") == nlohmann::json::array({0, 0, 142}));
  CHECK(classes[7].at("color") == nlohmann::json::array({250, 170, 30}));  // traffic light
}
