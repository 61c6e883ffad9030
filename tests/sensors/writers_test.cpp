#include "corsa/sensors/writers.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <opencv2/imgcodecs.hpp>

#include "corsa/core/atomic_file.h"
#include "corsa/sensors/kitti.h"
#include "png_codec.h"
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
  b.time = -0.025f;
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
  // The class field has PCL's name, `label`, in both formats; each point has its firing time.
  CHECK(ply.find("property uchar label\nproperty uint instance\nproperty float time\n") !=
        std::string::npos);
  CHECK(ply.find("semantic") == std::string::npos);
  CHECK(ply.size() == header + 2 * 27);
  float x = 0.0f, time = 0.0f;
  std::memcpy(&x, ply.data() + header + 27, 4);
  std::memcpy(&time, ply.data() + header + 27 + 23, 4);
  CHECK(x == 10.0f);
  CHECK(time == -0.025f);
  uint8_t label = 0;
  std::memcpy(&label, ply.data() + header + 18, 1);
  CHECK(label == static_cast<uint8_t>(SemanticClass::kCar));
  const std::string pcd = corsa::read_file(dir.path() / "p.pcd");
  CHECK(pcd.find("FIELDS x y z intensity ring label instance time\n") != std::string::npos);
  CHECK(pcd.find("POINTS 2\nDATA binary\n") != std::string::npos);
  CHECK(pcd.size() == pcd.find("DATA binary\n") + 12 + 2 * 27);
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
  // SemanticKITTI's layout with the dataset's own class ids (the class table).
  CHECK(l[0] == (static_cast<uint32_t>(SemanticClass::kCar) | (7u << 16)));
  CHECK(l[1] == static_cast<uint32_t>(SemanticClass::kRoad));
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

TEST_CASE(
    "KITTI label lines put the bottom centre in camera coordinates, the tight box "
    "from the instance mask and small or far objects in DontCare",
    "[sensors][writers][kitti]") {
  CameraIntrinsics k;
  k.width = 640;
  k.height = 360;
  k.fov_deg = 90.0;
  const CameraModel pinhole(k);
  ObjectLabel l;
  l.instance_id = 3;
  l.semantic = SemanticClass::kCar;
  l.box_sensor.center = {1.0, 0.5, 20.0};
  // Box x (forward) along the camera's z: the car drives away from the camera.
  l.box_sensor.rotation = optical_in_body().rotation.transposed();
  l.box_sensor.length = 4.0;
  l.box_sensor.width = 2.0;
  l.box_sensor.height = 1.5;
  l.distance = 20.0;
  l.occlusion = 0.3;
  // Its visible pixels: columns 330-360, rows 170-209 (40 px high).
  std::vector<uint32_t> instance(static_cast<size_t>(k.width) * k.height, 0);
  for (int r = 170; r < 210; ++r) {
    for (int c = 330; c <= 360; ++c) {
      instance[static_cast<size_t>(r) * k.width + c] = 3;
    }
  }
  KittiOptions options;
  const std::string line = kitti_label_lines(std::vector{l}, pinhole, instance, options);
  CHECK_THAT(line, Catch::StartsWith("Car 0.00 1 "));
  CHECK_THAT(line, Catch::Contains(" 330.00 170.00 360.00 209.00 1.50 2.00 4.00 1.00 1.25 20.00 "));
  CHECK_THAT(line, Catch::EndsWith(" -1.57\n"));
  // Lower than the minimum height, or farther than the maximum distance: DontCare.
  options.min_height_px = 41.0;
  CHECK(kitti_label_lines(std::vector{l}, pinhole, instance, options) ==
        "DontCare -1 -1 -10 330.00 170.00 360.00 209.00 -1 -1 -1 -1000 -1000 -1000 -10\n");
  options.min_height_px = 25.0;
  options.max_distance_m = 15.0;
  CHECK_THAT(kitti_label_lines(std::vector{l}, pinhole, instance, options),
             Catch::StartsWith("DontCare "));
}

TEST_CASE("rectifying a distorted image puts every pixel where the pinhole would see it",
          "[sensors][writers][kitti]") {
  CameraIntrinsics k;
  k.width = 320;
  k.height = 180;
  k.fov_deg = 90.0;
  k.k1 = -0.05;
  k.k2 = 0.01;
  const CameraModel lens(k);
  const CameraModel pinhole = pinhole_of(lens);
  CHECK_FALSE(pinhole.distorted());
  // A distorted instance image whose ids say which pinhole pixel each distorted pixel shows.
  std::vector<uint32_t> ids(static_cast<size_t>(k.width) * k.height, 0);
  for (int r = 0; r < k.height; ++r) {
    for (int c = 0; c < k.width; ++c) {
      const Vec3 ray = lens.ray({static_cast<double>(c), static_cast<double>(r)});
      const auto seen = pinhole.project(ray);
      REQUIRE(seen);
      const auto u = static_cast<uint32_t>(std::lround(seen->u) + 1000);
      const auto v = static_cast<uint32_t>(std::lround(seen->v) + 1000);
      ids[static_cast<size_t>(r) * k.width + c] = u * 10000 + v;
    }
  }
  const std::vector<uint32_t> rectified = rectify_ids(lens, ids);
  size_t off = 0, checked = 0;
  for (int r = 10; r < k.height - 10; ++r) {
    for (int c = 10; c < k.width - 10; ++c) {
      const uint32_t id = rectified[static_cast<size_t>(r) * k.width + c];
      if (id == 0) {
        continue;
      }
      const int u = static_cast<int>(id / 10000) - 1000;
      const int v = static_cast<int>(id % 10000) - 1000;
      off += std::abs(u - c) > 1 || std::abs(v - r) > 1 ? 1 : 0;
      ++checked;
    }
  }
  CHECK(checked > 40000);
  CHECK(off == 0);  // within a pixel (nearest-pixel sampling) everywhere
}

TEST_CASE("PNG files hold exactly the pixels given, in every layout, with the same bytes each time",
          "[sensors][writers][png]") {
  corsa::test::TempDir dir;
  // An odd size, values over the whole range (16-bit values above 255 check the byte order) and
  // a run of equal values (what deflate's matcher finds in class images).
  constexpr int kWidth = 61;
  constexpr int kHeight = 17;
  constexpr size_t kPixels = static_cast<size_t>(kWidth) * kHeight;
  std::vector<uint8_t> rgb(3 * kPixels);
  std::vector<uint8_t> gray(kPixels);
  std::vector<uint16_t> wide(kPixels);
  uint32_t state = 12345;
  const auto next = [&state] { return state = state * 1664525u + 1013904223u; };
  for (size_t i = 0; i < kPixels; ++i) {
    const bool run = i >= 100 && i < 400;
    for (int c = 0; c < 3; ++c) {
      rgb[3 * i + c] = run ? static_cast<uint8_t>(40 * c) : static_cast<uint8_t>(next() >> 24);
    }
    gray[i] = run ? 7 : static_cast<uint8_t>(next() >> 24);
    wide[i] = run ? 1235 : static_cast<uint16_t>(next() >> 16);
  }
  write_png_rgb8(dir.path() / "rgb.png", kWidth, kHeight, rgb);
  write_png_gray8(dir.path() / "gray.png", kWidth, kHeight, gray);
  write_png_gray16(dir.path() / "wide.png", kWidth, kHeight, wide);

  const cv::Mat rgb_read = cv::imread((dir.path() / "rgb.png").string(), cv::IMREAD_UNCHANGED);
  const cv::Mat gray_read = cv::imread((dir.path() / "gray.png").string(), cv::IMREAD_UNCHANGED);
  const cv::Mat wide_read = cv::imread((dir.path() / "wide.png").string(), cv::IMREAD_UNCHANGED);
  REQUIRE(rgb_read.type() == CV_8UC3);
  REQUIRE(gray_read.type() == CV_8UC1);
  REQUIRE(wide_read.type() == CV_16UC1);
  REQUIRE((rgb_read.cols == kWidth && rgb_read.rows == kHeight));
  REQUIRE((wide_read.cols == kWidth && wide_read.rows == kHeight));
  size_t wrong = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const size_t i = static_cast<size_t>(y) * kWidth + x;
      const cv::Vec3b bgr = rgb_read.at<cv::Vec3b>(y, x);
      wrong += bgr[2] != rgb[3 * i] || bgr[1] != rgb[3 * i + 1] || bgr[0] != rgb[3 * i + 2];
      wrong += gray_read.at<uint8_t>(y, x) != gray[i];
      wrong += wide_read.at<uint16_t>(y, x) != wide[i];
    }
  }
  CHECK(wrong == 0);

  write_png_rgb8(dir.path() / "rgb2.png", kWidth, kHeight, rgb);
  write_png_gray16(dir.path() / "wide2.png", kWidth, kHeight, wide);
  CHECK(corsa::read_file(dir.path() / "rgb.png") == corsa::read_file(dir.path() / "rgb2.png"));
  CHECK(corsa::read_file(dir.path() / "wide.png") == corsa::read_file(dir.path() / "wide2.png"));
  // The run of equal values is found: the class image is smaller than its raw bytes.
  CHECK(fs::file_size(dir.path() / "gray.png") < kPixels);
}

TEST_CASE("the preview's PNG reader gives OpenCV's pixels for any filter and refuses bad files",
          "[sensors][writers][png]") {
  // A gradient with noise in places, written by OpenCV at compression 6: libpng's adaptive
  // filtering chooses a filter row by row, not only Sub as our encoder.
  cv::Mat bgr(23, 41, CV_8UC3);
  uint32_t state = 777;
  for (int y = 0; y < bgr.rows; ++y) {
    for (int x = 0; x < bgr.cols; ++x) {
      state = state * 1664525u + 1013904223u;
      const int noise = y % 3 == 0 ? static_cast<int>(state >> 28) : 0;
      bgr.at<cv::Vec3b>(y, x) = cv::Vec3b(static_cast<uint8_t>(5 * x + noise),
                                          static_cast<uint8_t>(7 * y), static_cast<uint8_t>(x * y));
    }
  }
  std::vector<uchar> by_opencv;
  REQUIRE(cv::imencode(".png", bgr, by_opencv, {cv::IMWRITE_PNG_COMPRESSION, 6}));
  const std::optional<cv::Mat> decoded = corsa::sensors::detail::decode_png_rgb8(
      std::string_view(reinterpret_cast<const char*>(by_opencv.data()), by_opencv.size()));
  REQUIRE(decoded.has_value());
  CHECK(cv::norm(*decoded, bgr, cv::NORM_INF) == 0);

  // Our own encoder's files, read back.
  std::vector<uint8_t> rgb(3 * bgr.total());
  for (size_t i = 0; i < bgr.total(); ++i) {
    for (int c = 0; c < 3; ++c) {
      rgb[3 * i + c] = bgr.data[3 * i + 2 - c];
    }
  }
  std::string ours = corsa::sensors::detail::encode_png(
      bgr.cols, bgr.rows, corsa::sensors::detail::PngPixels::kRgb8, rgb);
  const std::optional<cv::Mat> ours_decoded = corsa::sensors::detail::decode_png_rgb8(ours);
  REQUIRE(ours_decoded.has_value());
  CHECK(cv::norm(*ours_decoded, bgr, cv::NORM_INF) == 0);

  // A flipped bit in the data fails its CRC; a grey image is left to OpenCV.
  ours[ours.size() / 2] = static_cast<char>(ours[ours.size() / 2] ^ 0x10);
  CHECK_FALSE(corsa::sensors::detail::decode_png_rgb8(ours).has_value());
  const std::vector<uint8_t> gray(bgr.total(), 9);
  CHECK_FALSE(corsa::sensors::detail::decode_png_rgb8(
                  corsa::sensors::detail::encode_png(
                      bgr.cols, bgr.rows, corsa::sensors::detail::PngPixels::kGray8, gray))
                  .has_value());
  CHECK_FALSE(corsa::sensors::detail::decode_png_rgb8("not a png").has_value());
}
