#pragma once

#include <optional>

#include "corsa/sensors/geometry.h"
#include "corsa/sensors/rig.h"

namespace corsa::sensors {

/// A pixel position: OpenCV convention, pixel (col c, row r) has its centre at (u, v) = (c, r).
struct Pixel {
  double u = 0.0;
  double v = 0.0;
};

/// Pinhole camera with OpenCV's distortion (k1, k2 radial; p1, p2 tangential), optical frame
/// x right, y down, z forward. fx = fy = (width / 2) / tan(fov / 2); principal point at the
/// image centre ((width - 1) / 2, (height - 1) / 2).
class CameraModel {
 public:
  explicit CameraModel(const CameraIntrinsics& intrinsics);

  const CameraIntrinsics& intrinsics() const { return intrinsics_; }
  int width() const { return intrinsics_.width; }
  int height() const { return intrinsics_.height; }
  double fx() const { return fx_; }
  double fy() const { return fy_; }
  double cx() const { return cx_; }
  double cy() const { return cy_; }
  bool distorted() const;

  /// Distorted pixel of a point in the optical frame; nullopt behind the camera (z <= 1 mm).
  std::optional<Pixel> project(Vec3 p) const;
  /// Unit ray (optical frame) whose image is pixel (u, v) of the distorted image.
  Vec3 ray(Pixel pixel) const;
  /// Applies the distortion to normalised coordinates (x/z, y/z).
  void distort(double x, double y, double& xd, double& yd) const;

 private:
  CameraIntrinsics intrinsics_;
  double fx_, fy_, cx_, cy_;
};

}  // namespace corsa::sensors
