// KITTI rectification and label lines (corsa/sensors/kitti.h).

#include "corsa/sensors/kitti.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "corsa/core/strings.h"
#include "corsa/sensors/semantic.h"

namespace corsa::sensors {
namespace {

double wrap_pi(double a) {
  while (a > std::numbers::pi) {
    a -= 2.0 * std::numbers::pi;
  }
  while (a < -std::numbers::pi) {
    a += 2.0 * std::numbers::pi;
  }
  return a;
}

/// Where pinhole pixel (c, r) lies in the distorted image of `camera`.
Pixel distorted_position(const CameraModel& camera, int c, int r) {
  const double x = (c - camera.cx()) / camera.fx();
  const double y = (r - camera.cy()) / camera.fy();
  double xd = 0.0, yd = 0.0;
  camera.distort(x, y, xd, yd);
  return {camera.fx() * xd + camera.cx(), camera.fy() * yd + camera.cy()};
}

struct PixelBox {
  int x_min = 1 << 30, y_min = 1 << 30, x_max = -1, y_max = -1;
  uint64_t count = 0;
};

std::map<uint32_t, PixelBox> tight_boxes(std::span<const uint32_t> ids, int width) {
  std::map<uint32_t, PixelBox> boxes;
  for (size_t i = 0; i < ids.size(); ++i) {
    if (ids[i] == 0) {
      continue;
    }
    PixelBox& b = boxes[ids[i]];
    const int x = static_cast<int>(i % static_cast<size_t>(width));
    const int y = static_cast<int>(i / static_cast<size_t>(width));
    b.x_min = std::min(b.x_min, x);
    b.x_max = std::max(b.x_max, x);
    b.y_min = std::min(b.y_min, y);
    b.y_max = std::max(b.y_max, y);
    ++b.count;
  }
  return boxes;
}

std::string box_text(double x_min, double y_min, double x_max, double y_max) {
  return format_fixed(x_min, 2) + " " + format_fixed(y_min, 2) + " " + format_fixed(x_max, 2) +
         " " + format_fixed(y_max, 2);
}

}  // namespace

CameraModel pinhole_of(const CameraModel& camera) {
  CameraIntrinsics k = camera.intrinsics();
  k.k1 = k.k2 = k.p1 = k.p2 = 0.0;
  return CameraModel(k);
}

std::vector<uint8_t> rectify_rgb(const CameraModel& camera, std::span<const uint8_t> rgb) {
  const int w = camera.width();
  const int h = camera.height();
  if (!camera.distorted()) {
    return {rgb.begin(), rgb.end()};
  }
  std::vector<uint8_t> out(static_cast<size_t>(w) * h * 3, 0);
  for (int r = 0; r < h; ++r) {
    for (int c = 0; c < w; ++c) {
      const Pixel p = distorted_position(camera, c, r);
      const double fx = std::floor(p.u);
      const double fy = std::floor(p.v);
      const int x0 = static_cast<int>(fx);
      const int y0 = static_cast<int>(fy);
      if (x0 < 0 || y0 < 0 || x0 + 1 >= w || y0 + 1 >= h) {
        continue;  // beyond what the lens saw
      }
      const double ax = p.u - fx;
      const double ay = p.v - fy;
      const size_t i00 = 3 * (static_cast<size_t>(y0) * w + x0);
      const size_t i10 = i00 + 3;
      const size_t i01 = i00 + 3 * static_cast<size_t>(w);
      const size_t i11 = i01 + 3;
      uint8_t* o = &out[3 * (static_cast<size_t>(r) * w + c)];
      for (int k = 0; k < 3; ++k) {
        const double top = rgb[i00 + k] + ax * (rgb[i10 + k] - rgb[i00 + k]);
        const double bottom = rgb[i01 + k] + ax * (rgb[i11 + k] - rgb[i01 + k]);
        o[k] = static_cast<uint8_t>(std::lround(std::clamp(top + ay * (bottom - top), 0.0, 255.0)));
      }
    }
  }
  return out;
}

std::vector<uint32_t> rectify_ids(const CameraModel& camera, std::span<const uint32_t> ids) {
  const int w = camera.width();
  const int h = camera.height();
  if (!camera.distorted()) {
    return {ids.begin(), ids.end()};
  }
  std::vector<uint32_t> out(static_cast<size_t>(w) * h, 0);
  for (int r = 0; r < h; ++r) {
    for (int c = 0; c < w; ++c) {
      const Pixel p = distorted_position(camera, c, r);
      const auto x = static_cast<long>(std::lround(p.u));
      const auto y = static_cast<long>(std::lround(p.v));
      if (x >= 0 && y >= 0 && x < w && y < h) {
        out[static_cast<size_t>(r) * w + c] = ids[static_cast<size_t>(y) * w + x];
      }
    }
  }
  return out;
}

std::string kitti_label_lines(std::span<const ObjectLabel> labels, const CameraModel& pinhole,
                              std::span<const uint32_t> instance, const KittiOptions& options) {
  const int w = pinhole.width();
  const int h = pinhole.height();
  const auto boxes = tight_boxes(instance, w);
  std::string out;
  for (const ObjectLabel& l : labels) {
    const Box3& b = l.box_sensor;
    const std::optional<Box2> full = projected_box(pinhole, b);
    if (!full) {
      continue;
    }
    const Box2 clipped{std::max(full->x_min, 0.0), std::max(full->y_min, 0.0),
                       std::min(full->x_max, w - 1.0), std::min(full->y_max, h - 1.0)};
    const auto tight = boxes.find(l.instance_id);
    if (clipped.x_min > clipped.x_max || clipped.y_min > clipped.y_max) {
      continue;  // outside the rectified image
    }
    const bool far = options.max_distance_m && l.distance > *options.max_distance_m;
    const bool small = tight == boxes.end() ||
                       tight->second.y_max - tight->second.y_min + 1 < options.min_height_px;
    if (far || small) {
      const std::string region =
          tight != boxes.end()
              ? box_text(tight->second.x_min, tight->second.y_min, tight->second.x_max,
                         tight->second.y_max)
              : box_text(clipped.x_min, clipped.y_min, clipped.x_max, clipped.y_max);
      out += "DontCare -1 -1 -10 " + region + " -1 -1 -1 -1000 -1000 -1000 -10\n";
      continue;
    }
    // KITTI location: the bottom centre of the box in camera coordinates.
    const Vec3 bottom = b.center + b.rotation * Vec3{0.0, 0.0, -0.5 * b.height};
    const double ry = kitti_rotation_y(b);
    const double alpha = wrap_pi(ry - std::atan2(bottom.x, bottom.z));
    const double area = (full->x_max - full->x_min) * (full->y_max - full->y_min);
    const double kept = (clipped.x_max - clipped.x_min) * (clipped.y_max - clipped.y_min);
    const double truncation = area > 0.0 ? std::clamp(1.0 - kept / area, 0.0, 1.0) : 0.0;
    const PixelBox& t = tight->second;
    out += std::string(kitti_type(l.semantic)) + " " + format_fixed(truncation, 2) + " " +
           std::to_string(kitti_occlusion_level(l.occlusion)) + " " + format_fixed(alpha, 2) + " " +
           box_text(t.x_min, t.y_min, t.x_max, t.y_max) + " " + format_fixed(b.height, 2) + " " +
           format_fixed(b.width, 2) + " " + format_fixed(b.length, 2) + " " +
           format_fixed(bottom.x, 2) + " " + format_fixed(bottom.y, 2) + " " +
           format_fixed(bottom.z, 2) + " " + format_fixed(wrap_pi(ry), 2) + "\n";
  }
  return out;
}

}  // namespace corsa::sensors
