#pragma once

// Small 3D math for the sensors: vectors, rotations and rigid transforms in double precision.
// Frames: map (x east, y north, z up, metres); entity and sensor body frames x forward, y left,
// z up; camera optical frame x right, y down, z forward (OpenCV).

#include <cmath>

#include "corsa/core/vec.h"

namespace corsa::sensors {

using corsa::Vec3;

/// Row-major 3x3 matrix.
struct Mat3 {
  double m[3][3] = {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};

  Vec3 operator*(Vec3 v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
  Mat3 operator*(const Mat3& o) const;
  Mat3 transposed() const;
  Vec3 column(int c) const { return {m[0][c], m[1][c], m[2][c]}; }
};

/// Rotation R = Rz(yaw) * Ry(pitch) * Rx(roll) (radians), the heading/pitch/roll convention of
/// OpenDRIVE 1.8 §2.3 and OpenSCENARIO 1.2 §6.3: yaw counter-clockwise about z.
Mat3 rotation_from_euler(double roll, double pitch, double yaw);

/// Rigid transform p' = rotation * p + translation (maps a child frame into its parent).
struct Rigid {
  Mat3 rotation;
  Vec3 translation;

  Vec3 apply(Vec3 p) const { return rotation * p + translation; }
  Vec3 apply_direction(Vec3 d) const { return rotation * d; }
  Rigid inverse() const;
  /// this * other: first `other`, then this.
  Rigid operator*(const Rigid& other) const;
};

/// The transform of a pose (x, y, z metres; heading, pitch, roll radians) into its parent frame.
Rigid rigid_from_pose(double x, double y, double z, double heading, double pitch, double roll);

/// Camera optical frame (x right, y down, z forward) expressed in the sensor body frame (x forward,
/// y left, z up): optical x = -body y, optical y = -body z, optical z = body x.
Rigid optical_in_body();

}  // namespace corsa::sensors
