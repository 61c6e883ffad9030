#include "corsa/sensors/geometry.h"

namespace corsa::sensors {

Mat3 Mat3::operator*(const Mat3& o) const {
  Mat3 r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      r.m[i][j] = m[i][0] * o.m[0][j] + m[i][1] * o.m[1][j] + m[i][2] * o.m[2][j];
    }
  }
  return r;
}

Mat3 Mat3::transposed() const {
  Mat3 r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      r.m[i][j] = m[j][i];
    }
  }
  return r;
}

Mat3 rotation_from_euler(double roll, double pitch, double yaw) {
  const double cr = std::cos(roll), sr = std::sin(roll);
  const double cp = std::cos(pitch), sp = std::sin(pitch);
  const double cy = std::cos(yaw), sy = std::sin(yaw);
  Mat3 r;
  r.m[0][0] = cy * cp;
  r.m[0][1] = cy * sp * sr - sy * cr;
  r.m[0][2] = cy * sp * cr + sy * sr;
  r.m[1][0] = sy * cp;
  r.m[1][1] = sy * sp * sr + cy * cr;
  r.m[1][2] = sy * sp * cr - cy * sr;
  r.m[2][0] = -sp;
  r.m[2][1] = cp * sr;
  r.m[2][2] = cp * cr;
  return r;
}

Rigid Rigid::inverse() const {
  Rigid r;
  r.rotation = rotation.transposed();
  r.translation = -(r.rotation * translation);
  return r;
}

Rigid Rigid::operator*(const Rigid& other) const {
  Rigid r;
  r.rotation = rotation * other.rotation;
  r.translation = rotation * other.translation + translation;
  return r;
}

Rigid rigid_from_pose(double x, double y, double z, double heading, double pitch, double roll) {
  Rigid r;
  r.rotation = rotation_from_euler(roll, pitch, heading);
  r.translation = {x, y, z};
  return r;
}

Rigid optical_in_body() {
  Rigid r;
  // Columns are the optical axes expressed in body coordinates.
  r.rotation.m[0][0] = 0.0;
  r.rotation.m[0][1] = 0.0;
  r.rotation.m[0][2] = 1.0;
  r.rotation.m[1][0] = -1.0;
  r.rotation.m[1][1] = 0.0;
  r.rotation.m[1][2] = 0.0;
  r.rotation.m[2][0] = 0.0;
  r.rotation.m[2][1] = -1.0;
  r.rotation.m[2][2] = 0.0;
  return r;
}

}  // namespace corsa::sensors
