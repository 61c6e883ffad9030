#pragma once

// A reader of the KITTI object-detection format written from its published description (the
// devkit's readme.txt of the KITTI Vision Benchmark Suite, Geiger et al. 2012), independent of
// Corsa's writer: label_2 lines, calib files, velodyne scans, ImageSets, and the geometry the
// devkit uses (3D box corners from location, dimensions and rotation_y; projection by P2 R0_rect
// Tr_velo_to_cam). The dataset tests load Corsa's --format kitti output with it and check that
// images, labels, calibration and scans agree as a KITTI user's code would assume.

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace corsa::test::kitti {

struct Object {
  std::string type;  ///< Car, Van, Truck, Pedestrian, Person_sitting, Cyclist, Tram, Misc, DontCare
  double truncated = 0.0;
  int occluded = 0;
  double alpha = 0.0;
  std::array<double, 4> box{};         ///< left, top, right, bottom (px)
  std::array<double, 3> dimensions{};  ///< height, width, length (m)
  std::array<double, 3> location{};    ///< bottom centre in camera coordinates (m)
  double rotation_y = 0.0;
};

struct Calib {
  std::array<double, 12> p2{};              ///< 3x4, row-major
  std::array<double, 9> r0_rect{};          ///< 3x3
  std::array<double, 12> tr_velo_to_cam{};  ///< 3x4
};

struct Point {
  float x = 0, y = 0, z = 0, reflectance = 0;
};

/// Parses a label_2 file; throws std::runtime_error naming the file and line for anything that
/// is not 15 fields of the right kinds and ranges.
std::vector<Object> read_labels(const std::filesystem::path& file);
Calib read_calib(const std::filesystem::path& file);
std::vector<Point> read_velodyne(const std::filesystem::path& file);
std::vector<std::string> read_image_set(const std::filesystem::path& file);

/// A velodyne point in (rectified) camera coordinates: R0_rect Tr_velo_to_cam p.
std::array<double, 3> velo_to_rect(const Calib& calib, const Point& p);
/// Image position of a rectified-camera point through P2; false behind the camera.
bool project(const Calib& calib, const std::array<double, 3>& p, double& u, double& v);
/// The devkit's 8 box corners (camera coordinates).
std::array<std::array<double, 3>, 8> corners(const Object& object);
/// Whether a rectified-camera point lies inside the object's 3D box (with a margin, m).
bool inside(const Object& object, const std::array<double, 3>& p, double margin = 0.0);

}  // namespace corsa::test::kitti
