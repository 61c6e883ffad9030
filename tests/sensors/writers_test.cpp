#include "corsa/sensors/writers.h"

#include <catch2/catch.hpp>
#include <cstring>
#include <opencv2/imgcodecs.hpp>

#include "corsa/core/atomic_file.h"
#include "run_corsa.h"
#include "temp_dir.h"

using namespace corsa::sensors;
namespace fs = std::filesystem;

namespace {

PointCloud two_points() {
  PointCloud c;
  LidarPoint a;
  a.x = 1.5f;
  a.y = -2.0f;
  a.z = 0.25f;
  a.intensity = 0.5f;
  a.ring = 3;
  a.semantic = SemanticClass::kCar;
  a.instance_id = 7;
  LidarPoint b = a;
  b.x = 10.0f;
  b.semantic = SemanticClass::kRoad;
  b.instance_id = 0;
  c.points = {a, b};
  return c;
}

}  // namespace

TEST_CASE("depth images are written as float EXR metres and 16-bit PNG millimetres",
          "[sensors][writers]") {
  corsa::test::TempDir dir;
  const std::vector<float> depth = {0.0f, 1.2345f, 18.0f, 70.0f};
  write_exr_float(dir.path() / "d.exr", 2, 2, depth);
  write_png_gray16(dir.path() / "d.png", 2, 2, depth_to_millimetres(depth));
  const cv::Mat exr = cv::imread((dir.path() / "d.exr").string(), cv::IMREAD_UNCHANGED);
  REQUIRE(exr.type() == CV_32FC1);
  CHECK(exr.at<float>(0, 1) == 1.2345f);
  CHECK(exr.at<float>(1, 1) == 70.0f);
  const cv::Mat png = cv::imread((dir.path() / "d.png").string(), cv::IMREAD_UNCHANGED);
  REQUIRE(png.type() == CV_16UC1);
  CHECK(png.at<uint16_t>(0, 0) == 0);
  CHECK(png.at<uint16_t>(0, 1) == 1235);
  CHECK(png.at<uint16_t>(1, 0) == 18000);
  CHECK(png.at<uint16_t>(1, 1) == 0);  // beyond 65.535 m: not representable, left empty
  // Same data, same bytes.
  write_exr_float(dir.path() / "e.exr", 2, 2, depth);
  CHECK(corsa::read_file(dir.path() / "d.exr") == corsa::read_file(dir.path() / "e.exr"));
}

TEST_CASE("RGB and class images keep their channel order and values", "[sensors][writers]") {
  corsa::test::TempDir dir;
  const std::vector<uint8_t> rgb = {255, 0, 0, 0, 255, 0, 0, 0, 255, 10, 20, 30};
  write_png_rgb8(dir.path() / "c.png", 2, 2, rgb);
  const cv::Mat img = cv::imread((dir.path() / "c.png").string(), cv::IMREAD_COLOR);
  CHECK(img.at<cv::Vec3b>(0, 0) == cv::Vec3b(0, 0, 255));  // BGR in OpenCV
  CHECK(img.at<cv::Vec3b>(1, 1) == cv::Vec3b(30, 20, 10));
  // CARLA's ids and Cityscapes' colours: road 1, sidewalk 2, traffic sign 8, car 14.
  const std::vector<uint8_t> classes = {1, 2, 8, 14};
  CHECK(static_cast<uint8_t>(SemanticClass::kCar) == 14);
  const auto colors = colorize_semantic(classes);
  CHECK(colors[0] == 128);  // road (128, 64, 128)
  CHECK(colors[1] == 64);
  CHECK(colors[6] == 220);  // traffic sign (220, 220, 0)
  CHECK(colors[8] == 0);
  CHECK(colors[9] == 0);  // car (0, 0, 142)
  CHECK(colors[11] == 142);
  CHECK_THROWS_AS(write_png_gray8(dir.path() / "x.png", 3, 2, classes), std::invalid_argument);
  CHECK_FALSE(fs::exists(dir.path() / "x.png"));
}

TEST_CASE("point clouds are written as PLY, PCD, KITTI bin and point labels",
          "[sensors][writers]") {
  corsa::test::TempDir dir;
  const PointCloud cloud = two_points();
  write_ply(dir.path() / "p.ply", cloud);
  write_pcd(dir.path() / "p.pcd", cloud);
  write_kitti_bin(dir.path() / "p.bin", cloud);
  write_point_labels(dir.path() / "p.label", cloud);
  const std::string ply = corsa::read_file(dir.path() / "p.ply");
  const size_t header = ply.find("end_header\n") + 11;
  CHECK(ply.find("element vertex 2\n") != std::string::npos);
  CHECK(ply.size() == header + 2 * 23);
  float x = 0.0f;
  std::memcpy(&x, ply.data() + header + 23, 4);
  CHECK(x == 10.0f);
  const std::string pcd = corsa::read_file(dir.path() / "p.pcd");
  CHECK(pcd.find("POINTS 2\nDATA binary\n") != std::string::npos);
  CHECK(pcd.size() == pcd.find("DATA binary\n") + 12 + 2 * 23);
  const std::string bin = corsa::read_file(dir.path() / "p.bin");
  REQUIRE(bin.size() == 32);
  float v[8];
  std::memcpy(v, bin.data(), 32);
  CHECK(v[0] == 1.5f);
  CHECK(v[1] == -2.0f);
  CHECK(v[3] == 0.5f);
  CHECK(v[4] == 10.0f);
  const std::string labels = corsa::read_file(dir.path() / "p.label");
  uint32_t l[2];
  std::memcpy(l, labels.data(), 8);
  CHECK(l[0] == (static_cast<uint32_t>(SemanticClass::kCar) | (7u << 16)));
  CHECK(l[1] == 1u);
}

TEST_CASE("calibration lists intrinsics and extrinsics", "[sensors][writers]") {
  SensorSpec s;
  s.name = "front";
  s.entity = "Ego";
  s.camera.width = 640;
  s.camera.height = 480;
  s.camera.fov_deg = 90.0;
  s.mount.x = 1.5;
  s.mount.z = 1.2;
  s.mount.yaw_deg = 90.0;
  const CameraModel model(s.camera);
  const std::string json = calibration_json(s, &model);
  // fx = 320 / tan(45 degrees), a hair above 320 in double precision.
  CHECK_THAT(json, Catch::Contains("\"K\": [[320.00000000000006, 0, 319.5], [0, "));
  CHECK_THAT(json, Catch::Contains(", 239.5], [0, 0, 1]]"));
  CHECK_THAT(json, Catch::Contains("\"sensor\": \"front\""));
  CHECK_THAT(json, Catch::Contains(", 1.5], "));  // x translation in T_entity_sensor
  const Rigid t = entity_from_sensor(s.mount);
  CHECK(t.apply({1.0, 0.0, 0.0}).y == Approx(1.0));  // yaw 90: forward becomes left
  SensorSpec l;
  l.name = "lidar";
  l.kind = SensorKind::kLidar;
  l.lidar.channels = 3;
  l.lidar.lower_fov_deg = -10.0;
  l.lidar.upper_fov_deg = 10.0;
  CHECK_THAT(calibration_json(l, nullptr), Catch::Contains("\"elevations_deg\": [-10, 0, 10]"));
}

TEST_CASE("KITTI label lines put the bottom centre in camera coordinates", "[sensors][writers]") {
  ObjectLabel l;
  l.semantic = SemanticClass::kCar;
  l.box_2d = {100, 50, 200, 120};
  l.box_sensor.center = {1.0, 0.5, 20.0};
  // Box x (forward) along the camera's z: the car drives away from the camera.
  l.box_sensor.rotation = optical_in_body().rotation.transposed();
  l.box_sensor.length = 4.0;
  l.box_sensor.width = 2.0;
  l.box_sensor.height = 1.5;
  l.occlusion = 0.3;
  l.truncation = 0.0;
  const std::string line = kitti_labels(std::vector{l});
  CHECK_THAT(line, Catch::StartsWith("Car 0.00 1 "));
  CHECK_THAT(line, Catch::Contains(" 100.00 50.00 200.00 120.00 1.50 2.00 4.00 1.00 1.25 20.00 "));
  CHECK_THAT(line, Catch::EndsWith(" -1.57\n"));
}
