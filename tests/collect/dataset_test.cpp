// `corsa run --rig` end to end: the dataset is complete and consistent, a second run gives the
// same bytes, windows follow the triggers, KITTI export, located errors.

#include <catch2/catch.hpp>
#include <cstring>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>

#include "corsa/core/atomic_file.h"
#include "dataset_check.h"
#include "run_corsa.h"
#include "temp_dir.h"

namespace {

namespace fs = std::filesystem;
using corsa::test::run_corsa;

const std::string kDemo = "scenarios/demo/cut_in_city.xosc";
const std::string kSmallRig = "tests/collect/fixtures/small_rig.xml";

corsa::test::ProcessResult run_small(const fs::path& out, std::vector<std::string> extra) {
  std::vector<std::string> args{"run", kDemo, "--rig", kSmallRig, "-o", out.string(), "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  return run_corsa(args);
}

}  // namespace

TEST_CASE("A dataset is complete, consistent, and byte-identical when run again",
          "[dataset][determinism]") {
  corsa::test::TempDir dir;
  const std::vector<std::string> options{
      "--duration",    "1",    "--npc", "vehicles=3,pedestrians=4", "--weather", "fog=300,rain=2",
      "--time-of-day", "19:45"};
  const auto first = run_small(dir.path() / "a", options);
  INFO(first.err);
  REQUIRE(first.exit_code == 0);
  const auto second = run_small(dir.path() / "b", options);
  REQUIRE(second.exit_code == 0);

  CHECK(corsa::test::check_dataset(dir.path() / "a", 192, 108).empty());
  const auto rows = corsa::test::read_index(dir.path() / "a");
  std::map<std::string, std::set<int64_t>> ticks;
  for (const auto& row : rows) {
    ticks[row.sensor].insert(row.tick);
  }
  // 1 s at dt 0.01: ticks 0..100; 10 Hz every 10 ticks, 5 Hz every 20, 3 Hz at ceil(100 k / 3).
  CHECK(ticks["cam"] == std::set<int64_t>{0, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100});
  CHECK(ticks["semantic"] == std::set<int64_t>{0, 20, 40, 60, 80, 100});
  CHECK(ticks["top"] == std::set<int64_t>{0, 34, 67, 100});
  CHECK(ticks["roof_lidar"] == ticks["cam"]);
  CHECK(fs::exists(dir.path() / "a/cam/calibration.json"));
  CHECK(fs::exists(dir.path() / "a/roof_lidar/calibration.json"));

  const std::string run_json = corsa::read_file(dir.path() / "a/run.json");
  CHECK(corsa::test::json_string(run_json, "status") == "complete");
  CHECK(corsa::test::json_string(run_json, "scenario") == kDemo);
  CHECK(corsa::test::json_number(run_json, "captures") == 13);  // 11 ticks + 34 and 67
  CHECK_THAT(run_json, Catch::Contains("\"CutInGap\": \"5\""));
  CHECK_THAT(run_json, Catch::Contains("\"weather\": \"fog=300,rain=2\""));

  const std::string pose = corsa::read_file(dir.path() / "a/poses/000005.json");
  CHECK_THAT(pose, Catch::Contains("\"name\": \"npc_pedestrian_3\""));
  CHECK_THAT(pose, Catch::Contains("\"fog_visual_range\": 300"));
  CHECK_THAT(pose, Catch::Contains("\"precipitation\": \"rain\""));

  const auto files = corsa::test::files_under(dir.path() / "a");
  REQUIRE(files == corsa::test::files_under(dir.path() / "b"));
  for (const std::string& file : files) {
    INFO(file);
    CHECK(corsa::read_file(dir.path() / "a" / file) == corsa::read_file(dir.path() / "b" / file));
  }
}

TEST_CASE("Capture windows in the dataset follow the scenario's corsa:capture actions",
          "[dataset][windows]") {
  corsa::test::TempDir dir;
  const auto result = run_corsa({"run", "tests/capture/fixtures/capture_windows.xosc", "--rig",
                                 "tests/collect/fixtures/windows_rig.xml", "-o",
                                 (dir.path() / "w").string(), "--quiet"});
  INFO(result.err);
  REQUIRE(result.exit_code == 0);
  std::set<int64_t> camera;
  for (const auto& row : corsa::test::read_index(dir.path() / "w")) {
    if (row.sensor == "camera") {
      camera.insert(row.tick);
    }
  }
  // Opened at 1 s (after tick 100) at 5 Hz, on the 5 Hz grid from tick 0 (every 20 ticks);
  // closed at 2 s; reopened after 2.5 s at 3 Hz, on the 3 Hz grid (ceil(100 k / 3)).
  REQUIRE(!camera.empty());
  CHECK(*camera.begin() == 120);
  CHECK(camera.count(140) == 1);
  CHECK(camera.count(200) == 1);
  CHECK(camera.count(220) == 0);
  CHECK(camera.count(234) == 0);
  CHECK(camera.count(267) == 1);
  CHECK(camera.count(300) == 1);
  const std::string run_json = corsa::read_file(dir.path() / "w/run.json");
  CHECK_THAT(run_json, Catch::Contains("{\"sensor\": \"camera\", \"open_tick\": 101"));
  CHECK(corsa::test::check_dataset(dir.path() / "w", 64, 36).empty());
}

TEST_CASE("--format kitti writes training/ image_2, velodyne, label_2, calib and ImageSets",
          "[dataset][kitti]") {
  corsa::test::TempDir dir;
  const auto result = run_small(dir.path() / "k", {"--duration", "0.3", "--format", "kitti"});
  INFO(result.err);
  REQUIRE(result.exit_code == 0);
  const fs::path kitti = dir.path() / "k/kitti/training";
  for (const char* stem : {"000000", "000001", "000002", "000003"}) {
    INFO(stem);
    CHECK(fs::exists(kitti / "image_2" / (std::string(stem) + ".png")));
    CHECK(fs::exists(kitti / "velodyne" / (std::string(stem) + ".bin")));
    CHECK(fs::exists(kitti / "label_2" / (std::string(stem) + ".txt")));
    CHECK(fs::exists(kitti / "calib" / (std::string(stem) + ".txt")));
  }
  CHECK(!fs::exists(kitti / "image_2/000004.png"));
  CHECK(corsa::read_file(dir.path() / "k/kitti/ImageSets/trainval.txt") ==
        "000000\n000001\n000002\n000003\n");
  const std::string calib = corsa::read_file(kitti / "calib/000000.txt");
  CHECK_THAT(calib, Catch::StartsWith("P0: ") && Catch::Contains("\nTr_velo_to_cam: "));
  // The LiDAR is 0.6 m behind and 0.45 m above the camera: in the optical frame (x right, y
  // down, z forward) its origin is at (0, -0.45, -0.6), its x axis along the optical z.
  const size_t at = calib.find("Tr_velo_to_cam: ");
  std::istringstream tr(calib.substr(at + 16));
  const double expected[12] = {0, -1, 0, 0, 0, 0, -1, -0.45, 1, 0, 0, -0.6};
  for (const double e : expected) {
    double value = 0.0;
    tr >> value;
    CHECK(value == Approx(e).margin(1e-9));
  }
}

TEST_CASE("A rig made for another scenario runs with a warning for each sensor it lacks",
          "[dataset][windows]") {
  corsa::test::TempDir dir;
  const auto run = run_corsa({"run", "tests/capture/fixtures/capture_windows.xosc", "--rig",
                              kSmallRig, "-o", (dir.path() / "y").string(), "--quiet"});
  INFO(run.err);
  CHECK(run.exit_code == 0);
  CHECK_THAT(run.err, Catch::Contains("capture_windows.xosc:") &&
                          Catch::Contains("warning: corsa:capture: the rig has no sensor "
                                          "'camera'") &&
                          Catch::Contains("no sensor 'lidar'"));
  CHECK(corsa::test::check_dataset(dir.path() / "y", 192, 108).empty());
}

TEST_CASE("A SensorReference naming no sensor of the rig warns at it, an error under --strict",
          "[dataset][visibility]") {
  corsa::test::TempDir dir;
  // The fixture's set names "front camera" and "lidar"; scenarios/rigs/small.xml has neither.
  const std::vector<std::string> args{
      "run",        "tests/engine/fixtures/visibility_sensor_refs.xosc",
      "--rig",      "scenarios/rigs/small.xml",
      "--duration", "0.2"};
  std::vector<std::string> lenient = args;
  lenient.insert(lenient.end(), {"-o", (dir.path() / "v").string()});
  const auto run = run_corsa(lenient);
  INFO(run.err);
  CHECK(run.exit_code == 0);
  CHECK_THAT(run.err, Catch::Contains("visibility_sensor_refs.xosc:39: warning: SensorReference "
                                      "'front camera': the rig has no such sensor") &&
                          Catch::Contains("SensorReference 'lidar': the rig has no such sensor"));
  std::vector<std::string> strict = args;
  strict.insert(strict.end(), {"-o", (dir.path() / "s").string(), "--strict"});
  const auto refused = run_corsa(strict);
  CHECK(refused.exit_code == 2);
  CHECK_THAT(refused.err, Catch::Contains("visibility_sensor_refs.xosc:39: error: SensorReference "
                                          "'front camera': the rig has no such sensor"));
  CHECK_FALSE(fs::exists(dir.path() / "s"));
}

TEST_CASE("Captures showing interpenetrating entities are flagged in the index and poses",
          "[dataset][collisions]") {
  corsa::test::TempDir dir;
  // Runner runs into Slow at 11.55 s and stays in contact to the end (12.01 s).
  const auto run =
      run_corsa({"run", "tests/engine/fixtures/condition_distances.xosc", "--rig",
                 "tests/collect/fixtures/runner_rig.xml", "-o", (dir.path() / "c").string()});
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  CHECK_THAT(run.out, Catch::Contains("1 collision") &&
                          Catch::Contains("  collision at 11.55 s: Runner and Slow"));
  std::set<int64_t> flagged, clean;
  for (const auto& row : corsa::test::read_index(dir.path() / "c")) {
    (row.overlap > 0 ? flagged : clean).insert(row.tick);
  }
  CHECK(flagged == std::set<int64_t>{1200});  // the capture at 12 s
  CHECK(clean.count(1100) == 1);
  CHECK(clean.count(1200) == 0);
  const std::string pose = corsa::read_file(dir.path() / "c/poses/000024.json");
  CHECK_THAT(pose, Catch::Contains("\"overlaps\": [[1, 2]]"));
  CHECK_THAT(corsa::read_file(dir.path() / "c/poses/000022.json"),
             Catch::Contains("\"overlaps\": []"));
}

TEST_CASE("Point labels use the dataset's class table: .label, PLY and PCD agree on it",
          "[dataset][labels]") {
  corsa::test::TempDir dir;
  const auto result = run_small(dir.path() / "l", {"--duration", "0.1", "--npc", "vehicles=4"});
  INFO(result.err);
  REQUIRE(result.exit_code == 0);
  // The ids of classes.json.
  std::set<uint32_t> ids;
  const std::string table = corsa::read_file(dir.path() / "l/classes.json");
  for (size_t at = table.find("\"id\": "); at != std::string::npos;
       at = table.find("\"id\": ", at + 1)) {
    ids.insert(static_cast<uint32_t>(std::stoul(table.substr(at + 6))));
  }
  REQUIRE(ids.size() > 10);
  const std::string labels = corsa::read_file(dir.path() / "l/roof_lidar/000000.label");
  const std::string pcd = corsa::read_file(dir.path() / "l/roof_lidar/000000.pcd");
  const std::string ply = corsa::read_file(dir.path() / "l/roof_lidar/000000.ply");
  CHECK_THAT(pcd, Catch::Contains("FIELDS x y z intensity ring label instance time\n"));
  CHECK_THAT(ply, Catch::Contains("property uchar label\n"));
  const size_t pcd_data = pcd.find("DATA binary\n") + 12;
  const size_t ply_data = ply.find("end_header\n") + 11;
  const size_t points = labels.size() / 4;
  REQUIRE(points > 100);
  REQUIRE(pcd.size() - pcd_data == points * 27);
  std::set<uint32_t> seen;
  for (size_t i = 0; i < points; ++i) {
    uint32_t word = 0;
    std::memcpy(&word, labels.data() + 4 * i, 4);
    const uint32_t id = word & 0xFFFFu;
    seen.insert(id);
    CHECK(ids.count(id) == 1);
    // The same id as the PCD's and PLY's label field of the same point.
    CHECK(static_cast<uint8_t>(pcd[pcd_data + 27 * i + 18]) == id);
    CHECK(static_cast<uint8_t>(ply[ply_data + 27 * i + 18]) == id);
  }
  CHECK(seen.size() >= 3);  // road, buildings, cars at least
}

TEST_CASE("Bad data-collection input is reported with exit code 2", "[dataset][errors]") {
  corsa::test::TempDir dir;
  const auto no_output = run_corsa({"run", kDemo, "--rig", kSmallRig});
  CHECK(no_output.exit_code == 2);
  CHECK_THAT(no_output.err, Catch::Contains("missing -o DIR"));

  const auto weather = run_small(dir.path() / "x", {"--weather", "hail=2"});
  CHECK(weather.exit_code == 2);
  CHECK_THAT(weather.err, Catch::Contains("unknown key 'hail'"));

  // The engine options are the same as without a rig (apps/corsa/run_options.h), checked alike.
  const auto controller = run_small(dir.path() / "c", {"--controller", "autopilot"});
  CHECK(controller.exit_code == 2);
  CHECK_THAT(controller.err, Catch::Contains("--controller expects default, acc or dynamics"));

  fs::create_directories(dir.path() / "full");
  corsa::write_file_atomic(dir.path() / "full/keep.txt", "mine");
  const auto not_empty = run_small(dir.path() / "full", {"--duration", "0.1", "--force"});
  CHECK(not_empty.exit_code == 2);
  CHECK_THAT(not_empty.err, Catch::Contains("has none"));
  CHECK(fs::exists(dir.path() / "full/keep.txt"));
}
