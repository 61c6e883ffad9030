#pragma once

#include <array>

#include "corsa/sensors/geometry.h"

namespace corsa::sensors {

/// An oriented box: centre, rotation (box axes x length, y width, z height into the frame), size.
struct Box3 {
  Vec3 center;
  Mat3 rotation;
  double length = 0.0, width = 0.0, height = 0.0;

  /// Yaw of the box's x axis about the frame's z axis (radians); for camera optical frames the
  /// KITTI rotation_y is the yaw about the optical y axis, see kitti_rotation_y().
  double yaw() const;
  /// The eight corners; index bits: 1 = +x (front), 2 = +y (left), 4 = +z (top).
  std::array<Vec3, 8> corners() const;
};

/// An axis-aligned pixel rectangle, OpenCV pixel-centre convention, inclusive extents.
struct Box2 {
  double x_min = 0.0, y_min = 0.0, x_max = 0.0, y_max = 0.0;
  double area() const { return (x_max - x_min) * (y_max - y_min); }
};

}  // namespace corsa::sensors
