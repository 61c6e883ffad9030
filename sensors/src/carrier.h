#pragma once

// Rays of a sensor mounted inside its own entity's bounding box (a camera behind the windscreen)
// must not hit that entity: they start where they leave its box.

#include <algorithm>
#include <cmath>
#include <optional>

#include "corsa/sensors/labels.h"

namespace corsa::sensors::detail {

class CarrierExit {
 public:
  CarrierExit() = default;
  /// `origin` in the same frame as the box (map frame).
  CarrierExit(const std::optional<Box3>& box, Vec3 origin) {
    if (!box) {
      return;
    }
    to_box_ = box->rotation.transposed();
    origin_ = to_box_ * (origin - box->center);
    // One centimetre of margin so that faces lying on the box are skipped too.
    half_ = {0.5 * box->length + 0.01, 0.5 * box->width + 0.01, 0.5 * box->height + 0.01};
    active_ = std::fabs(origin_.x) < half_.x && std::fabs(origin_.y) < half_.y &&
              std::fabs(origin_.z) < half_.z;
  }

  bool active() const { return active_; }

  /// Distance along the unit direction `dir` (map frame) at which the ray leaves the box.
  float exit(Vec3 dir) const {
    if (!active_) {
      return 0.0f;
    }
    const Vec3 d = to_box_ * dir;
    const double o[3] = {origin_.x, origin_.y, origin_.z};
    const double v[3] = {d.x, d.y, d.z};
    const double h[3] = {half_.x, half_.y, half_.z};
    double t = 1e30;
    for (int i = 0; i < 3; ++i) {
      if (v[i] > 1e-12) {
        t = std::min(t, (h[i] - o[i]) / v[i]);
      } else if (v[i] < -1e-12) {
        t = std::min(t, (-h[i] - o[i]) / v[i]);
      }
    }
    return static_cast<float>(std::max(0.0, t));
  }

 private:
  bool active_ = false;
  Mat3 to_box_;
  Vec3 origin_;
  Vec3 half_;
};

}  // namespace corsa::sensors::detail
