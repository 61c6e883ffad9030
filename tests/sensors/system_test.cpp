#include <tbb/global_control.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <fstream>

#include "corsa/core/atomic_file.h"
#include "corsa/core/diagnostic.h"
#include "corsa/sensors/buildings.h"
#include "corsa/sensors/sensor_system.h"
#include "fixtures.h"
#include "temp_dir.h"

using namespace corsa::sensors;
namespace fs = std::filesystem;

namespace {

const char* const kSmallRig = R"(<SensorRig version="1" name="small">
  <RgbCamera name="rgb" entity="Ego" width="160" height="96" fov="90"><Mount x="1.5" z="1.4"/></RgbCamera>
  <DepthCamera name="depth" entity="Ego" width="160" height="96" fov="90" maxRange="60"><Mount x="1.5" z="1.4"/></DepthCamera>
  <SemanticCamera name="sem" entity="Ego" width="160" height="96" fov="90"><Mount x="1.5" z="1.4"/></SemanticCamera>
  <InstanceCamera name="inst" entity="Ego" width="160" height="96" fov="90"><Mount x="1.5" z="1.4"/></InstanceCamera>
  <BirdsEyeCamera name="bev" entity="Ego" width="64" height="64" extent="60" style="rgb"/>
  <Lidar name="lidar" entity="Ego" channels="16" pointsPerSecond="57600" noiseStddev="0.02"><Mount z="1.9"/></Lidar>
</SensorRig>)";

corsa::engine::WorldSnapshot world(double t) {
  corsa::engine::WorldSnapshot w;
  w.time = t;
  w.tick = static_cast<int64_t>(t * 100);
  auto ego = corsa::test::box_entity(1, "Ego", 0.0, 0.0, 4.5, 1.9, 1.5,
                                     corsa::engine::EntityCategory::kCar);
  ego.box.center_x = 1.4;
  ego.vx = 10.0;
  ego.pose.x = 10.0 * t;
  auto lead = corsa::test::box_entity(2, "Lead", 25.0 + 8.0 * t, 0.5, 4.5, 1.9, 1.5,
                                      corsa::engine::EntityCategory::kCar);
  lead.vx = 8.0;
  auto walker = corsa::test::box_entity(3, "Walker", 18.0, -6.0, 0.5, 0.6, 1.8,
                                        corsa::engine::EntityCategory::kPedestrian);
  w.entities = {ego, lead, walker};
  return w;
}

Scene district() {
  Scene scene;
  scene.add_road_mesh(corsa::test::flat_road(300.0));
  for (const Footprint& f : street_district(200.0, 10.0, 3)) {
    scene.add_static_mesh(extrude_footprint(f));
  }
  scene.commit();
  return scene;
}

/// Runs two captures into `dir` and returns the files written.
std::vector<fs::path> run(const fs::path& dir, int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  Scene scene = district();
  SensorRig rig = parse_rig(kSmallRig, "small.xml");
  const std::vector<std::string> names{"Ego", "Lead", "Walker"};
  bind_rig(rig, names);
  SensorSystemOptions options;
  options.seed = 11;
  SensorSystem system(rig, scene, options);
  SensorCaptureSink sink(system, dir);
  sink.capture(world(0.0), {});
  const std::vector<std::string> only_lidar{"lidar"};
  sink.capture(world(0.1), only_lidar);
  return sink.files();
}

}  // namespace

TEST_CASE("a rig captures every sensor with labels into per-sensor folders", "[sensors][system]") {
  corsa::test::TempDir dir;
  const auto files = run(dir.path(), 2);
  std::vector<std::string> names;
  for (const auto& f : files) {
    names.push_back(f.generic_string());
    CHECK(fs::exists(dir.path() / f));
  }
  CHECK(names ==
        std::vector<std::string>{
            "rgb/000000.png",           "rgb/000000_labels.json",   "depth/000000.exr",
            "depth/000000.png",         "depth/000000_labels.json", "sem/000000.png",
            "sem/000000_color.png",     "sem/000000_labels.json",   "inst/000000.png",
            "inst/000000_labels.json",  "bev/000000.png",           "lidar/000000.ply",
            "lidar/000000.pcd",         "lidar/000000.bin",         "lidar/000000.label",
            "lidar/000000_labels.json", "lidar/000001.ply",         "lidar/000001.pcd",
            "lidar/000001.bin",         "lidar/000001.label",       "lidar/000001_labels.json"});
  CHECK(fs::exists(dir.path() / "rgb" / "calibration.json"));
  CHECK(fs::exists(dir.path() / "lidar" / "calibration.json"));
  // The camera sees the lead car and the walker, never its own vehicle.
  const std::string labels = corsa::read_file(dir.path() / "rgb" / "000000_labels.json");
  CHECK_THAT(labels, Catch::Contains("\"name\": \"Lead\""));
  CHECK_THAT(labels, Catch::Contains("\"name\": \"Walker\", \"class\": \"person\""));
  CHECK_THAT(labels, !Catch::Contains("\"name\": \"Ego\""));
  // Point counts agree between the PLY header, the KITTI bin and the point labels.
  const std::string ply = corsa::read_file(dir.path() / "lidar" / "000000.ply");
  const size_t at = ply.find("element vertex ") + 15;
  const size_t points = std::stoul(ply.substr(at, ply.find('\n', at) - at));
  CHECK(points > 1000);
  CHECK(fs::file_size(dir.path() / "lidar" / "000000.bin") == points * 16);
  CHECK(fs::file_size(dir.path() / "lidar" / "000000.label") == points * 4);
  const std::string lidar_labels = corsa::read_file(dir.path() / "lidar" / "000000_labels.json");
  CHECK_THAT(lidar_labels, Catch::Contains("\"lidar_points\": "));
}

TEST_CASE("a second run gives byte-identical files on any thread count",
          "[sensors][system][determinism]") {
  corsa::test::TempDir a, b;
  const auto files = run(a.path(), 1);
  const auto again = run(b.path(), 2);
  REQUIRE(files == again);
  for (const auto& f : files) {
    INFO(f.string());
    CHECK(corsa::read_file(a.path() / f) == corsa::read_file(b.path() / f));
  }
}

TEST_CASE("capturing a sensor whose entity is missing names the rig line",
          "[sensors][system][errors]") {
  Scene scene = district();
  SensorSystem system(parse_rig(kSmallRig, "small.xml"), scene, {});
  corsa::engine::WorldSnapshot empty;
  CHECK_THROWS_WITH(system.capture(empty, {}),
                    Catch::StartsWith("small.xml:2: error: sensor 'rgb' is attached to entity "
                                      "'Ego', which is not in the world at tick 0"));
}

TEST_CASE(
    "an entity seen only by the sensors a SensorReferenceSet names is missing from the others",
    "[sensors][system][visibility]") {
  // Two instance cameras with the same optics and two LiDARs: "seen" and "lidar_seen" are named,
  // the others are not.
  const char* const rig_text = R"(<SensorRig version="1" name="pair">
  <InstanceCamera name="seen" entity="Ego" width="160" height="96" fov="90"><Mount x="1.5" z="1.4"/></InstanceCamera>
  <InstanceCamera name="blind" entity="Ego" width="160" height="96" fov="90"><Mount x="1.5" z="1.4"/></InstanceCamera>
  <Lidar name="lidar_seen" entity="Ego" channels="16" pointsPerSecond="57600"><Mount z="1.9"/></Lidar>
  <Lidar name="lidar_blind" entity="Ego" channels="16" pointsPerSecond="57600"><Mount z="1.9"/></Lidar>
</SensorRig>)";
  Scene scene = district();
  SensorRig rig = parse_rig(rig_text, "pair.xml");
  bind_rig(rig, std::vector<std::string>{"Ego", "Lead", "Walker"});
  SensorSystem system(rig, scene, {});
  const auto has_lead = [](const SensorFrame& f) {
    const bool labelled = std::any_of(f.labels.begin(), f.labels.end(),
                                      [](const ObjectLabel& l) { return l.name == "Lead"; });
    if (f.kind == SensorKind::kLidar) {
      return labelled;
    }
    const bool drawn = std::find(f.camera.instance.begin(), f.camera.instance.end(), 2u) !=
                       f.camera.instance.end();
    CHECK(drawn == labelled);
    return drawn;
  };
  const auto frame = [](const std::vector<SensorFrame>& frames, const std::string& name) {
    for (const SensorFrame& f : frames) {
      if (f.sensor == name) return f;
    }
    FAIL("no frame of " << name);
    return SensorFrame{};
  };
  corsa::engine::WorldSnapshot w = world(0.0);
  // Everyone sees the lead car at first.
  auto frames = system.capture(w, {});
  CHECK(has_lead(frame(frames, "seen")));
  CHECK(has_lead(frame(frames, "blind")));
  CHECK(has_lead(frame(frames, "lidar_seen")));
  CHECK(has_lead(frame(frames, "lidar_blind")));
  // sensors="true" with the set {seen, lidar_seen}: the others implicitly do not see it.
  w.entities[1].visible = false;
  w.entities[1].sensor_exceptions = {"seen", "lidar_seen"};
  frames = system.capture(w, {});
  CHECK(has_lead(frame(frames, "seen")));
  CHECK_FALSE(has_lead(frame(frames, "blind")));
  CHECK(has_lead(frame(frames, "lidar_seen")));
  CHECK_FALSE(has_lead(frame(frames, "lidar_blind")));
  // The walker, without exceptions, is in every camera's view as before.
  const SensorFrame blind = frame(frames, "blind");
  CHECK(std::find(blind.camera.instance.begin(), blind.camera.instance.end(), 3u) !=
        blind.camera.instance.end());
  // sensors="false" with the set {seen}: only "seen" misses it.
  w.entities[1].visible = true;
  w.entities[1].sensor_exceptions = {"seen"};
  frames = system.capture(w, {});
  CHECK_FALSE(has_lead(frame(frames, "seen")));
  CHECK(has_lead(frame(frames, "blind")));
  CHECK(has_lead(frame(frames, "lidar_seen")));
  CHECK(has_lead(frame(frames, "lidar_blind")));
}
