#include <cmath>
#include <numbers>
#include <string>
#include <string_view>

#include "corsa/core/json.h"
#include "corsa/core/strings.h"
#include "corsa/sensors/camera_render.h"
#include "corsa/sensors/writers.h"
#include "scalar_math.h"

namespace corsa::sensors {

using detail::kDeg;
namespace {

double num(double v) { return v == 0.0 ? 0.0 : v; }  // no "-0"

Json vec_json(Vec3 v) { return {num(v.x), num(v.y), num(v.z)}; }

/// Unit quaternion [w, x, y, z] of a rotation matrix (Shepperd's method).
Json quaternion_json(const Mat3& r) {
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
  return {num(w), num(x), num(y), num(z)};
}

Json box3_json(const Box3& b) {
  return {{"center", vec_json(b.center)},
          {"size", {num(b.length), num(b.width), num(b.height)}},
          {"yaw", num(b.yaw())},
          {"rotation", quaternion_json(b.rotation)}};
}

Json box2_json(const Box2& b) { return {num(b.x_min), num(b.y_min), num(b.x_max), num(b.y_max)}; }

}  // namespace

Rigid entity_from_sensor(const Mount& m) {
  return rigid_from_pose(m.x, m.y, m.z, m.yaw_deg * kDeg, m.pitch_deg * kDeg, m.roll_deg * kDeg);
}

Json matrix_json(const Rigid& t) {
  Json rows = Json::array();
  for (int r = 0; r < 3; ++r) {
    const double tr = r == 0 ? t.translation.x : (r == 1 ? t.translation.y : t.translation.z);
    rows.push_back(
        {num(t.rotation.m[r][0]), num(t.rotation.m[r][1]), num(t.rotation.m[r][2]), num(tr)});
  }
  rows.push_back({0, 0, 0, 1});
  return rows;
}

std::string calibration_json(const SensorSpec& s, const CameraModel* camera) {
  Json out = {{"sensor", s.name},
              {"type", sensor_kind_name(s.kind)},
              {"entity", s.entity},
              {"rate_hz", num(s.rate_hz)},
              {"T_entity_sensor", matrix_json(entity_from_sensor(s.mount))}};
  if (camera != nullptr) {
    const auto& k = camera->intrinsics();
    out["T_sensor_optical"] = matrix_json(optical_in_body());
    out["width"] = k.width;
    out["height"] = k.height;
    out["K"] = {{num(camera->fx()), 0, num(camera->cx())},
                {0, num(camera->fy()), num(camera->cy())},
                {0, 0, 1}};
    out["distortion"] = {{"model", "opencv"},
                         {"k1", num(k.k1)},
                         {"k2", num(k.k2)},
                         {"p1", num(k.p1)},
                         {"p2", num(k.p2)}};
  }
  if (s.kind == SensorKind::kBirdsEyeCamera) {
    const auto& b = s.birds_eye;
    out["width"] = b.width;
    out["height"] = b.height;
    out["metres_per_pixel"] = num(b.extent_m / b.width);
    out["follow_heading"] = b.follow_heading;
  }
  if (s.kind == SensorKind::kLidar) {
    const LidarSimulator lidar(s.lidar);
    out["channels"] = s.lidar.channels;
    out["azimuth_steps"] = lidar.azimuth_steps();
    out["range_m"] = num(s.lidar.range_m);
    Json elevations = Json::array();
    for (int c = 0; c < s.lidar.channels; ++c) {
      elevations.push_back(num(lidar.elevation(c) / kDeg));
    }
    out["elevations_deg"] = std::move(elevations);
  }
  return json_document(out);
}

namespace {

Json static_labels_json(std::span<const StaticObjectLabel> labels) {
  Json objects = Json::array();
  for (const StaticObjectLabel& l : labels) {
    const ObjectInfo& o = l.info;
    Json object = {
        {"instance_id", l.instance_id}, {"class", semantic_name(l.semantic)}, {"kind", o.kind}};
    if (!o.signal_id.empty()) {
      object["signal_id"] = o.signal_id;
      object["country"] = o.country;
      object["type"] = o.type;
      object["subtype"] = o.subtype;
      object["value"] = o.value ? Json(num(*o.value)) : Json(nullptr);
      object["text"] = o.text;
    }
    if (o.kind == "traffic_light") {
      object["state"] = l.state;
    }
    if (o.kind == "parked_vehicle") {
      object["type"] = o.type;  // body style: sedan, hatchback, suv, van, pickup
      object["parked"] = true;
    }
    object["box_world"] = box3_json(l.box_world);
    object["box_2d_visible"] = box2_json(l.box_2d_visible);
    object["visible_pixels"] = l.visible_pixels;
    objects.push_back(std::move(object));
  }
  return objects;
}

/// Names of the lamps (LightRole) a vehicle shape has.
std::string_view lamp_name(LightRole role) {
  switch (role) {
    case LightRole::kHeadlight:
      return "headlight";
    case LightRole::kTail:
      return "tail";
    case LightRole::kBrake:
      return "brake";
    case LightRole::kIndicatorLeft:
      return "indicator_left";
    case LightRole::kIndicatorRight:
      return "indicator_right";
    case LightRole::kReversing:
      return "reversing";
    default:
      return "";
  }
}

std::string_view light_mode_text(engine::LightMode mode) {
  return mode == engine::LightMode::kOn    ? "on"
         : mode == engine::LightMode::kOff ? "off"
                                           : "flashing";
}

/// A vehicle's lights: {name: {mode, lit[, set, intensity_cd, colour]}} by OpenSCENARIO name,
/// and the lamps drawn lit.
void add_lights_json(const VehicleLightsLabel& v, Json& object) {
  Json lights = Json::object();
  for (const LightLabel& l : v.lights) {
    Json light = {{"mode", std::string(light_mode_text(l.mode))}, {"lit", l.lit}};
    if (l.set) {
      light["set"] = true;
    }
    if (l.intensity_cd) {
      light["intensity_cd"] = num(*l.intensity_cd);
    }
    if (l.rgb) {
      light["colour"] = {num((*l.rgb)[0]), num((*l.rgb)[1]), num((*l.rgb)[2])};
    }
    lights[std::string(engine::kVehicleLightNames[static_cast<size_t>(l.light)])] =
        std::move(light);
  }
  Json lamps = Json::array();
  for (unsigned r = 0; r <= static_cast<unsigned>(LightRole::kReversing); ++r) {
    if (const auto name = lamp_name(static_cast<LightRole>(r));
        (v.lamps >> r & 1u) && !name.empty()) {
      lamps.push_back(std::string(name));
    }
  }
  object["lights"] = std::move(lights);
  object["lamps"] = std::move(lamps);
}

}  // namespace

std::string labels_json(std::span<const ObjectLabel> labels, bool camera,
                        std::span<const StaticObjectLabel> static_labels) {
  Json objects = Json::array();
  for (const ObjectLabel& l : labels) {
    if (camera && l.parked) {
      continue;  // a camera lists parked vehicles among its static objects
    }
    Json object = {{"track_id", l.track_id},
                   {"instance_id", l.instance_id},
                   {"name", l.name},
                   {"class", semantic_name(l.semantic)},
                   {"distance", num(l.distance)},
                   {"box_world", box3_json(l.box_world)},
                   {"box_sensor", box3_json(l.box_sensor)}};
    if (camera) {
      object["box_2d"] = box2_json(l.box_2d);
      object["box_2d_visible"] = box2_json(l.box_2d_visible);
      object["truncation"] = num(l.truncation);
      object["occlusion"] = num(l.occlusion);
      object["occlusion_level"] = kitti_occlusion_level(l.occlusion);
      object["visible_pixels"] = l.visible_pixels;
      if (l.lights) {
        add_lights_json(*l.lights, object);
      }
    } else {
      object["lidar_points"] = l.lidar_points;
    }
    if (l.parked) {
      object["type"] = l.type;  // body style, as in a camera's static objects
      object["parked"] = true;
    }
    objects.push_back(std::move(object));
  }
  Json document = {{"objects", std::move(objects)}};
  if (camera) {
    document["static_objects"] = static_labels_json(static_labels);
  }
  return json_document(document);
}

}  // namespace corsa::sensors
