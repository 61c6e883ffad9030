#include "corsa/sensors/camera_model.h"

#include <cmath>
#include <numbers>

namespace corsa::sensors {

CameraModel::CameraModel(const CameraIntrinsics& intrinsics) : intrinsics_(intrinsics) {
  const double half_fov = intrinsics.fov_deg * std::numbers::pi / 360.0;
  fx_ = (intrinsics.width / 2.0) / std::tan(half_fov);
  fy_ = fx_;
  cx_ = (intrinsics.width - 1) / 2.0;
  cy_ = (intrinsics.height - 1) / 2.0;
}

bool CameraModel::distorted() const {
  return intrinsics_.k1 != 0.0 || intrinsics_.k2 != 0.0 || intrinsics_.p1 != 0.0 ||
         intrinsics_.p2 != 0.0;
}

void CameraModel::distort(double x, double y, double& xd, double& yd) const {
  const auto& k = intrinsics_;
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (k.k1 + r2 * k.k2);
  xd = x * radial + 2.0 * k.p1 * x * y + k.p2 * (r2 + 2.0 * x * x);
  yd = y * radial + k.p1 * (r2 + 2.0 * y * y) + 2.0 * k.p2 * x * y;
}

std::optional<Pixel> CameraModel::project(Vec3 p) const {
  if (p.z <= 1e-3) {
    return std::nullopt;
  }
  double xd = p.x / p.z;
  double yd = p.y / p.z;
  if (distorted()) {
    distort(p.x / p.z, p.y / p.z, xd, yd);
  }
  return Pixel{fx_ * xd + cx_, fy_ * yd + cy_};
}

Vec3 CameraModel::ray(Pixel pixel) const {
  const double xd = (pixel.u - cx_) / fx_;
  const double yd = (pixel.v - cy_) / fy_;
  double x = xd;
  double y = yd;
  if (distorted()) {
    // Fixed-point inversion of the distortion, as OpenCV's undistortPoints does; converges in
    // a few steps for the moderate coefficients the rig schema allows.
    for (int i = 0; i < 20; ++i) {
      double fx = 0.0, fy = 0.0;
      distort(x, y, fx, fy);
      const double ex = xd - fx;
      const double ey = yd - fy;
      x += ex;
      y += ey;
      if (ex * ex + ey * ey < 1e-26) {
        break;  // converged to double precision
      }
    }
  }
  return normalized({x, y, 1.0});
}

}  // namespace corsa::sensors
