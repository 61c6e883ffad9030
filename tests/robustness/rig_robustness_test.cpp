// Broken sensor rigs through `corsa run --rig`: unknown sensor types and image qualities, sizes
// that are zero, negative, text or absurd (a 100000 x 100000 image, a LiDAR of 2e10 beams per
// revolution) are located errors before the dataset folder is made, never an out-of-memory or a
// hang.

#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "bounded_run.h"

namespace corsa::test {
namespace {

const std::filesystem::path kSmallRig =
    std::filesystem::path(CORSA_SOURCE_DIR) / "scenarios/rigs/small.xml";

/// `corsa run SCENARIO --duration 0.1 --quiet --rig RIG -o DATASET` (two frames of each sensor).
BoundedResult run_with_rig(const std::filesystem::path& scenario, const std::filesystem::path& rig,
                           const std::filesystem::path& dataset,
                           int limit_seconds = kCaseTimeLimit) {
  return run_bounded({"run", scenario.string(), "--duration", "0.1", "--quiet", "--rig",
                      rig.string(), "-o", dataset.string()},
                     limit_seconds);
}

/// A scenario of one car `dimensions` (Dimensions attributes) on road 1 of `map`, its
/// BoundingBox on line 7.
void write_one_car_drive(
    const std::filesystem::path& file, const std::filesystem::path& map,
    const std::string& dimensions = "width=\"1.8\" length=\"4.5\" height=\"1.5\"") {
  std::ofstream(file) << "<?xml version=\"1.0\"?>\n<OpenSCENARIO>\n"
                         "  <FileHeader revMajor=\"1\" revMinor=\"3\" date=\"2026-01-01T00:00:00\" "
                         "description=\"\" author=\"\"/>\n"
                         "  <ParameterDeclarations/><CatalogLocations/>\n"
                         "  <RoadNetwork><LogicFile filepath=\""
                      << map.string()
                      << "\"/></RoadNetwork>\n"
                         "  <Entities><ScenarioObject name=\"Ego\"><Vehicle name=\"car\" "
                         "vehicleCategory=\"car\"><Performance maxSpeed=\"50\" "
                         "maxAcceleration=\"5\" maxDeceleration=\"9\"/>\n"
                         "    <BoundingBox><Center x=\"1.4\" y=\"0\" z=\"0.8\"/><Dimensions "
                      << dimensions
                      << "/></BoundingBox>\n"
                         "    <Axles><FrontAxle maxSteering=\"0.5\" wheelDiameter=\"0.6\" "
                         "trackWidth=\"1.6\" positionX=\"2.8\" positionZ=\"0.3\"/><RearAxle "
                         "maxSteering=\"0\" wheelDiameter=\"0.6\" trackWidth=\"1.6\" "
                         "positionX=\"0\" positionZ=\"0.3\"/></Axles><Properties/>"
                         "</Vehicle></ScenarioObject></Entities>\n"
                         "  <Storyboard><Init><Actions><Private entityRef=\"Ego\"><PrivateAction>"
                         "<TeleportAction><Position><LanePosition roadId=\"1\" laneId=\"-1\" "
                         "s=\"10\"/></Position></TeleportAction></PrivateAction></Private>"
                         "</Actions></Init><StopTrigger/></Storyboard>\n</OpenSCENARIO>\n";
}

TEST_CASE("Rigs with unknown sensors and absurd sizes are rejected at their line",
          "[robustness][rig]") {
  const std::string scenario = std::string(CORSA_SOURCE_DIR) + "/scenarios/cut_in.xosc";
  struct Case {
    const char* what;
    const char* sensor;
    const char* message;
  };
  const Case cases[] = {
      {"unknown sensor type", "<Radar name=\"a\" entity=\"Ego\"/>", "<Radar> is not allowed"},
      {"image 100000 x 100000",
       "<RgbCamera name=\"a\" entity=\"Ego\" width=\"100000\" height=\"100000\"/>",
       "above the maximum 8192"},
      {"zero height", "<DepthCamera name=\"a\" entity=\"Ego\" height=\"0\"/>", "height"},
      {"LiDAR of 2e10 beams per revolution",
       "<Lidar name=\"a\" entity=\"Ego\" channels=\"256\" pointsPerSecond=\"20000000\" "
       "rotationFrequency=\"0.001\"/>",
       "beams per revolution"},
      {"image quality that does not exist",
       "<RgbCamera name=\"a\" entity=\"Ego\" quality=\"ultra\"/>",
       "expected one of 'fast', 'default', 'high'"},
  };
  for (const Case& c : cases) {
    TempDir dir;
    std::ofstream(dir.path() / "rig.xml") << "<?xml version=\"1.0\"?>\n<SensorRig version=\"1\" "
                                             "name=\"broken\">\n  "
                                          << c.sensor << "\n</SensorRig>\n";
    const BoundedResult result =
        run_with_rig(scenario, dir.path() / "rig.xml", dir.path() / "dataset");
    INFO(describe(c.what, result));
    CHECK_FALSE(result.timed_out);
    CHECK(result.exit_code == 2);
    CHECK(result.err.find("rig.xml:3: error: ") != std::string::npos);
    CHECK(result.err.find(c.message) != std::string::npos);
    CHECK(entry_names(dir.path()) == std::set<std::string>{"rig.xml"});
  }
}

TEST_CASE("A rig of more maximal sensors than one run can hold is rejected at the sensor",
          "[robustness][rig]") {
  const std::string scenario = std::string(CORSA_SOURCE_DIR) + "/scenarios/cut_in.xosc";
  TempDir dir;
  std::ofstream rig(dir.path() / "rig.xml");
  rig << "<?xml version=\"1.0\"?>\n<SensorRig version=\"1\" name=\"huge\">\n";
  // Each 8192 x 8192 camera is allowed alone (about 1 GB of rays and images); the third is
  // past the rig's budget, on line 5.
  for (const char* name : {"c1", "c2", "c3"}) {
    rig << "  <SemanticCamera name=\"" << name << "\" entity=\"Ego\" width=\"8192\" "
        << "height=\"8192\" fov=\""
        << (name[1] == '1'   ? "60"
            : name[1] == '2' ? "70"
                             : "80")
        << "\"/>\n";
  }
  rig << "</SensorRig>\n";
  rig.close();
  const BoundedResult result =
      run_with_rig(scenario, dir.path() / "rig.xml", dir.path() / "dataset");
  INFO(describe("three 8192 x 8192 cameras", result));
  CHECK(result.exit_code == 2);
  CHECK(result.err.find("rig.xml:5: error: with this sensor the rig has") != std::string::npos);
  CHECK(entry_names(dir.path()) == std::set<std::string>{"rig.xml"});
}

TEST_CASE("A map whose surface or objects a sensor world cannot hold is refused at their lines",
          "[robustness][rig]") {
  // Found by tests/robustness/campaign.py. Each map loads, validates and meshes (its numbers are
  // finite), but Embree traces in single precision and the ground is a grid of 4 m cells over the
  // roads: the elevation of slope 1e300 aborted in Embree's ray assertion (SIGABRT, a stale
  // .corsa.lock left), the lane 1e206 m wide ended in "cannot create std::vector larger than
  // max_size()" (exit 3), the roads 1e12 m apart the same; objects 1e17 and 1e300 m long ran out
  // of memory (exit 3).
  const auto corpus = std::filesystem::path(CORSA_SOURCE_DIR) / "tests/robustness/corpus";
  struct Case {
    const char* map;
    const char* message;
  };
  const Case cases[] = {
      {"ok_elevation_slope_1e300.xodr",
       ":7: error: road '1': its surface reaches z = 1e+302 m; sensors trace at most 1e6 m"},
      {"ok_lane_width_1e206.xodr", ":7: error: road '1': the road surfaces span 100 m x 1e+206 m"},
      {"ok_roads_1e12_apart.xodr", ":6: error: road '1': the road surfaces span 1e+12 m x 3.5 m"},
      // Every object no road can hold, in one pass (the fourth object is a normal crosswalk).
      {"ok_objects_longer_than_any_road.xodr",
       ":28: error: object '9': its box is 1e+17 m long; no road holds an object longer than "
       "1,000 km"},
      {"ok_objects_longer_than_any_road.xodr",
       ":29: error: object '10': a repeat is 1e+300 m long"},
      {"ok_objects_longer_than_any_road.xodr", ":33: error: object '11': its outline is 1e+300 m"},
  };
  for (const Case& c : cases) {
    TempDir dir;
    write_one_car_drive(dir.path() / "drive.xosc", corpus / c.map);
    const BoundedResult result =
        run_with_rig(dir.path() / "drive.xosc", kSmallRig, dir.path() / "dataset");
    INFO(describe(c.map, result));
    CHECK_FALSE(result.timed_out);
    CHECK(result.exit_code == 2);
    std::string expected = c.map;
    expected += c.message;
    CHECK(result.err.find(expected) != std::string::npos);
    CHECK(entry_names(dir.path()) == std::set<std::string>{"drive.xosc"});
  }
}

TEST_CASE("Roads tens of kilometres apart get a sensor world of larger ground cells",
          "[robustness][rig]") {
  // Roads 40 km apart east and north need 1e8 ground cells of 4 m: the map was refused (exit 2)
  // as if the file were at fault; the ground now takes larger cells, at most 2^22 of them.
  const auto corpus = std::filesystem::path(CORSA_SOURCE_DIR) / "tests/robustness/corpus";
  TempDir dir;
  write_one_car_drive(dir.path() / "drive.xosc", corpus / "ok_roads_40km_apart.xodr");
  const BoundedResult result =
      run_with_rig(dir.path() / "drive.xosc", kSmallRig, dir.path() / "dataset",
                   300);  // about 20 s of CPU time, mostly the ground's 2^22 cells
  INFO(describe("roads 40 km apart", result));
  CHECK_FALSE(result.timed_out);
  CHECK(result.exit_code == 0);
  CHECK(result.err.find("error") == std::string::npos);
  // The LiDAR sees the road and the ground around the car.
  const auto scan = dir.path() / "dataset" / "roof_lidar" / "000000.bin";
  REQUIRE(std::filesystem::exists(scan));
  CHECK(std::filesystem::file_size(scan) > 1000 * 16);  // float32 x y z intensity per point
}

TEST_CASE("A vehicle larger than any is a plain box to the sensors, with a warning at its box",
          "[robustness][rig]") {
  // Found by tests/robustness/campaign.py: the car generator builds its lamps in 15 cm pieces on
  // a surface found in 5 mm steps, so a car 60 m in every dimension took minutes, 1 km more than
  // 14 minutes and 1e7 m all the memory.
  const auto map =
      std::filesystem::path(CORSA_SOURCE_DIR) / "tests/robustness/corpus" / "ok_minimal_road.xodr";
  const std::pair<const char*, const char*> sizes[] = {{"1000", "1000"}, {"1e7", "1e+07"}};
  for (const auto& [size, shown] : sizes) {
    TempDir dir;
    const std::string s = size;
    write_one_car_drive(dir.path() / "drive.xosc", map,
                        "width=\"" + s + "\" length=\"" + s + "\" height=\"" + s + "\"");
    const BoundedResult result =
        run_with_rig(dir.path() / "drive.xosc", kSmallRig, dir.path() / "dataset");
    INFO(describe(std::string("a car of ") + size + " m", result));
    CHECK_FALSE(result.timed_out);
    CHECK(result.exit_code == 0);
    CHECK(result.cpu_seconds < 10.0);  // CPU time: wall time depends on the load
    const std::string n = shown;
    CHECK(result.err.find("drive.xosc:7: warning: vehicle 'Ego': its bounding box (" + n + " x " +
                          n + " x " + n + " m) is larger than any vehicle") != std::string::npos);
  }
  // A car of 1000 m with its own model3d is seen as that model: nothing to warn about.
  {
    TempDir dir;
    write_one_car_drive(dir.path() / "drive.xosc", map,
                        "width=\"1000\" length=\"1000\" height=\"1000\"");
    std::ifstream in(dir.path() / "drive.xosc");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string category = "vehicleCategory=\"car\"";
    REQUIRE(text.find(category) != std::string::npos);
    text.insert(
        text.find(category) + category.size(),
        " model3d=\"" + std::string(CORSA_SOURCE_DIR) + "/scenarios/models/street_district.obj\"");
    std::ofstream(dir.path() / "drive.xosc") << text;
    const BoundedResult result =
        run_with_rig(dir.path() / "drive.xosc", kSmallRig, dir.path() / "dataset");
    INFO(describe("a car of 1000 m with a model3d", result));
    CHECK(result.exit_code == 0);
    CHECK(result.err.find("cannot use the model") == std::string::npos);
    CHECK(result.err.find("larger than any vehicle") == std::string::npos);
  }
  // The largest plausible sizes keep their details, without a word.
  TempDir dir;
  write_one_car_drive(dir.path() / "drive.xosc", map, "width=\"3\" length=\"25\" height=\"4.5\"");
  const BoundedResult result =
      run_with_rig(dir.path() / "drive.xosc", kSmallRig, dir.path() / "dataset");
  INFO(describe("a car of 25 x 3 x 4.5 m", result));
  CHECK(result.exit_code == 0);
  CHECK(result.err.find("larger than any vehicle") == std::string::npos);
}

TEST_CASE("Header bounds far from the roads do not move the sensor scene there",
          "[robustness][rig]") {
  // Found by tests/robustness/campaign.py: bounds 1e29..1e30 m north put the scene's origin
  // there; Embree traces in single precision around it, and the run wrote empty images, exit 0.
  const auto corpus = std::filesystem::path(CORSA_SOURCE_DIR) / "tests/robustness/corpus";
  TempDir dir;
  write_one_car_drive(dir.path() / "drive.xosc", corpus / "ok_header_bounds_far_from_roads.xodr");
  const BoundedResult result =
      run_with_rig(dir.path() / "drive.xosc", kSmallRig, dir.path() / "dataset");
  INFO(describe("header bounds 1e30 m away", result));
  CHECK(result.exit_code == 0);
  // At the header's line (line 5 of the file).
  CHECK(result.err.find("ok_header_bounds_far_from_roads.xodr:5: warning: <header> bounds (west "
                        "-1e+30, east 1e+30, south 1e+29, north 1e+30) are centred more than "
                        "1 km from the roads") != std::string::npos);
  // The LiDAR sees the road and the ground (it saw nothing: no point at all).
  const auto scan = dir.path() / "dataset" / "roof_lidar" / "000000.bin";
  REQUIRE(std::filesystem::exists(scan));
  CHECK(std::filesystem::file_size(scan) > 1000 * 16);  // float32 x y z intensity per point
}

TEST_CASE("The sun is placed at the sensor scene's origin, the roads when the bounds lie far",
          "[robustness][rig]") {
  // The scene was centred on the roads but the sun placed from the header bounds' centre, 8500 km
  // north: the images differed from those of the same map with bounds around its road.
  const auto far_map = std::filesystem::path(CORSA_SOURCE_DIR) /
                       "tests/robustness/corpus/ok_header_bounds_far_with_georeference.xodr";
  std::ifstream in(far_map);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string far_bounds =
      "north=\"9000000\" south=\"8000000\" east=\"100\"\n          west=\"-100\"";
  const size_t at = text.find(far_bounds);
  REQUIRE(at != std::string::npos);
  // The road spans x 0 to 100, y -3.5 to 0: bounds around it give the same origin.
  text.replace(at, far_bounds.size(), "north=\"0\" south=\"-3.5\" east=\"100\" west=\"0\"");
  TempDir dir;
  std::ofstream(dir.path() / "near.xodr") << text;
  const auto images_of = [&dir](const std::filesystem::path& map, const std::string& name) {
    write_one_car_drive(dir.path() / (name + ".xosc"), map);
    const BoundedResult result =
        run_with_rig(dir.path() / (name + ".xosc"), kSmallRig, dir.path() / name);
    INFO(describe(name, result));
    CHECK(result.exit_code == 0);
    std::string bytes;
    for (const char* frame : {"000000.png", "000001.png"}) {
      std::ifstream image(dir.path() / name / "front_rgb" / frame, std::ios::binary);
      bytes.append(std::istreambuf_iterator<char>(image), std::istreambuf_iterator<char>());
    }
    return bytes;
  };
  const std::string far_images = images_of(far_map, "far");
  CHECK(far_images.size() > 1000);
  CHECK(far_images == images_of(dir.path() / "near.xodr", "near"));
}

}  // namespace
}  // namespace corsa::test
