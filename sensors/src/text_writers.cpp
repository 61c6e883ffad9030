#include <cmath>
#include <numbers>
#include <string>

#include "corsa/core/strings.h"
#include "corsa/sensors/camera_render.h"
#include "corsa/sensors/writers.h"

namespace corsa::sensors {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

std::string num(double v) { return format_double(v == 0.0 ? 0.0 : v); }  // no "-0"

std::string vec_json(Vec3 v) { return "[" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + "]"; }

/// Unit quaternion [w, x, y, z] of a rotation matrix (Shepperd's method).
std::string quaternion_json(const Mat3& r) {
  const auto& m = r.m;
  double w = 0, x = 0, y = 0, z = 0;
  const double trace = m[0][0] + m[1][1] + m[2][2];
  if (trace > 0.0) {
    const double s = 2.0 * std::sqrt(trace + 1.0);
    w = 0.25 * s;
    x = (m[2][1] - m[1][2]) / s;
    y = (m[0][2] - m[2][0]) / s;
    z = (m[1][0] - m[0][1]) / s;
  } else if (m[0][0] > m[1][1] && m[0][0] > m[2][2]) {
    const double s = 2.0 * std::sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]);
    w = (m[2][1] - m[1][2]) / s;
    x = 0.25 * s;
    y = (m[0][1] + m[1][0]) / s;
    z = (m[0][2] + m[2][0]) / s;
  } else if (m[1][1] > m[2][2]) {
    const double s = 2.0 * std::sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]);
    w = (m[0][2] - m[2][0]) / s;
    x = (m[0][1] + m[1][0]) / s;
    y = 0.25 * s;
    z = (m[1][2] + m[2][1]) / s;
  } else {
    const double s = 2.0 * std::sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]);
    w = (m[1][0] - m[0][1]) / s;
    x = (m[0][2] + m[2][0]) / s;
    y = (m[1][2] + m[2][1]) / s;
    z = 0.25 * s;
  }
  return "[" + num(w) + ", " + num(x) + ", " + num(y) + ", " + num(z) + "]";
}

std::string box3_json(const Box3& b) {
  return "{\"center\": " + vec_json(b.center) + ", \"size\": [" + num(b.length) + ", " +
         num(b.width) + ", " + num(b.height) + "], \"yaw\": " + num(b.yaw()) +
         ", \"rotation\": " + quaternion_json(b.rotation) + "}";
}

std::string box2_json(const Box2& b) {
  return "[" + num(b.x_min) + ", " + num(b.y_min) + ", " + num(b.x_max) + ", " + num(b.y_max) + "]";
}

double wrap_pi(double a) {
  while (a > std::numbers::pi) {
    a -= 2.0 * std::numbers::pi;
  }
  while (a < -std::numbers::pi) {
    a += 2.0 * std::numbers::pi;
  }
  return a;
}

}  // namespace

Rigid entity_from_sensor(const Mount& m) {
  return rigid_from_pose(m.x, m.y, m.z, m.yaw_deg * kDeg, m.pitch_deg * kDeg, m.roll_deg * kDeg);
}

std::string matrix_json(const Rigid& t) {
  std::string out = "[";
  for (int r = 0; r < 3; ++r) {
    const double tr = r == 0 ? t.translation.x : (r == 1 ? t.translation.y : t.translation.z);
    out += "[" + num(t.rotation.m[r][0]) + ", " + num(t.rotation.m[r][1]) + ", " +
           num(t.rotation.m[r][2]) + ", " + num(tr) + "], ";
  }
  return out + "[0, 0, 0, 1]]";
}

std::string calibration_json(const SensorSpec& s, const CameraModel* camera) {
  std::string out = "{\n  \"sensor\": " + json_quote(s.name) +
                    ",\n  \"type\": " + json_quote(sensor_kind_name(s.kind)) +
                    ",\n  \"entity\": " + json_quote(s.entity) +
                    ",\n  \"rate_hz\": " + num(s.rate_hz) +
                    ",\n  \"T_entity_sensor\": " + matrix_json(entity_from_sensor(s.mount));
  if (camera != nullptr) {
    const auto& k = camera->intrinsics();
    out += ",\n  \"T_sensor_optical\": " + matrix_json(optical_in_body()) +
           ",\n  \"width\": " + std::to_string(k.width) +
           ",\n  \"height\": " + std::to_string(k.height) + ",\n  \"K\": [[" + num(camera->fx()) +
           ", 0, " + num(camera->cx()) + "], [0, " + num(camera->fy()) + ", " + num(camera->cy()) +
           "], [0, 0, 1]],\n  \"distortion\": {\"model\": \"opencv\", \"k1\": " + num(k.k1) +
           ", \"k2\": " + num(k.k2) + ", \"p1\": " + num(k.p1) + ", \"p2\": " + num(k.p2) + "}";
  }
  if (s.kind == SensorKind::kBirdsEyeCamera) {
    const auto& b = s.birds_eye;
    out += ",\n  \"width\": " + std::to_string(b.width) +
           ",\n  \"height\": " + std::to_string(b.height) +
           ",\n  \"metres_per_pixel\": " + num(b.extent_m / b.width) +
           ",\n  \"follow_heading\": " + (b.follow_heading ? "true" : "false");
  }
  if (s.kind == SensorKind::kLidar) {
    const LidarSimulator lidar(s.lidar);
    out += ",\n  \"channels\": " + std::to_string(s.lidar.channels) +
           ",\n  \"azimuth_steps\": " + std::to_string(lidar.azimuth_steps()) +
           ",\n  \"range_m\": " + num(s.lidar.range_m) + ",\n  \"elevations_deg\": [";
    for (int c = 0; c < s.lidar.channels; ++c) {
      out += (c ? ", " : "") + num(lidar.elevation(c) / kDeg);
    }
    out += "]";
  }
  return out + "\n}\n";
}

namespace {

std::string static_labels_json(std::span<const StaticObjectLabel> labels) {
  std::string out;
  for (size_t i = 0; i < labels.size(); ++i) {
    const StaticObjectLabel& l = labels[i];
    const ObjectInfo& o = l.info;
    out += std::string(i ? ",\n  " : "\n  ") +
           "{\"instance_id\": " + std::to_string(l.instance_id) +
           ", \"class\": " + json_quote(semantic_name(l.semantic)) +
           ", \"kind\": " + json_quote(o.kind);
    if (!o.signal_id.empty()) {
      out += ", \"signal_id\": " + json_quote(o.signal_id) +
             ", \"country\": " + json_quote(o.country) + ", \"type\": " + json_quote(o.type) +
             ", \"subtype\": " + json_quote(o.subtype) +
             ", \"value\": " + (o.value ? num(*o.value) : std::string("null")) +
             ", \"text\": " + json_quote(o.text);
    }
    if (o.kind == "traffic_light") {
      out += ", \"state\": " + json_quote(l.state);
    }
    out += ",\n   \"box_world\": " + box3_json(l.box_world) +
           ", \"box_2d_visible\": " + box2_json(l.box_2d_visible) +
           ", \"visible_pixels\": " + std::to_string(l.visible_pixels) + "}";
  }
  return out;
}

}  // namespace

std::string labels_json(std::span<const ObjectLabel> labels, bool camera,
                        std::span<const StaticObjectLabel> static_labels) {
  std::string out = "{\"objects\": [";
  for (size_t i = 0; i < labels.size(); ++i) {
    const ObjectLabel& l = labels[i];
    out += std::string(i ? ",\n  " : "\n  ") + "{\"track_id\": " + std::to_string(l.track_id) +
           ", \"instance_id\": " + std::to_string(l.instance_id) +
           ", \"name\": " + json_quote(l.name) +
           ", \"class\": " + json_quote(semantic_name(l.semantic)) +
           ", \"distance\": " + num(l.distance) + ",\n   \"box_world\": " + box3_json(l.box_world) +
           ",\n   \"box_sensor\": " + box3_json(l.box_sensor);
    if (camera) {
      out += ",\n   \"box_2d\": " + box2_json(l.box_2d) +
             ", \"box_2d_visible\": " + box2_json(l.box_2d_visible) +
             ", \"truncation\": " + num(l.truncation) + ", \"occlusion\": " + num(l.occlusion) +
             ", \"occlusion_level\": " + std::to_string(kitti_occlusion_level(l.occlusion)) +
             ", \"visible_pixels\": " + std::to_string(l.visible_pixels);
    } else {
      out += ",\n   \"lidar_points\": " + std::to_string(l.lidar_points);
    }
    out += "}";
  }
  out += labels.empty() ? "]" : "\n]";
  if (camera) {
    out += ",\n\"static_objects\": [" + static_labels_json(static_labels) +
           (static_labels.empty() ? "]" : "\n]");
  }
  return out + "}\n";
}

std::string kitti_labels(std::span<const ObjectLabel> labels) {
  std::string out;
  for (const ObjectLabel& l : labels) {
    const Box3& b = l.box_sensor;
    // KITTI location: the bottom centre of the box in camera coordinates.
    const Vec3 bottom = b.center + b.rotation * Vec3{0.0, 0.0, -0.5 * b.height};
    const double ry = kitti_rotation_y(b);
    const double alpha = wrap_pi(ry - std::atan2(bottom.x, bottom.z));
    out += std::string(kitti_type(l.semantic)) + " " + format_fixed(l.truncation, 2) + " " +
           std::to_string(kitti_occlusion_level(l.occlusion)) + " " + format_fixed(alpha, 2) + " " +
           format_fixed(l.box_2d.x_min, 2) + " " + format_fixed(l.box_2d.y_min, 2) + " " +
           format_fixed(l.box_2d.x_max, 2) + " " + format_fixed(l.box_2d.y_max, 2) + " " +
           format_fixed(b.height, 2) + " " + format_fixed(b.width, 2) + " " +
           format_fixed(b.length, 2) + " " + format_fixed(bottom.x, 2) + " " +
           format_fixed(bottom.y, 2) + " " + format_fixed(bottom.z, 2) + " " +
           format_fixed(wrap_pi(ry), 2) + "\n";
  }
  return out;
}

}  // namespace corsa::sensors
