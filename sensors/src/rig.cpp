#include "corsa/sensors/rig.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "corsa/core/atomic_file.h"
#include "corsa/core/diagnostic.h"
#include "corsa/core/strings.h"
#include "corsa/core/xsd_validator.h"
#include "rig_schema_text.h"

namespace corsa::sensors {
namespace {

// Beams of one LiDAR revolution at most: 16 x a 128-channel, 2048-column sensor.
constexpr double kMaxBeamsPerRevolution = 4'194'304;
// What a whole rig may ask for: every camera keeps per-pixel rays and images (an 8192 x 8192
// camera alone takes about 1 GB), every LiDAR its beams, so a rig of many maximal sensors ran
// out of memory. Two maximal cameras and four maximal LiDARs fit.
constexpr double kMaxRigPixels = 2.0 * 8192 * 8192;
constexpr double kMaxRigBeams = 4.0 * kMaxBeamsPerRevolution;

/// Sums what the rig's sensors will allocate; throws at the sensor that goes past the budget.
class RigBudget {
 public:
  explicit RigBudget(const std::string& file) : file_(file) {}
  void add(const SensorSpec& s, const ValidatedElement& e) {
    if (s.kind == SensorKind::kLidar) {
      beams_ += s.lidar.points_per_second / s.lidar.rotation_frequency_hz;
      check(beams_, kMaxRigBeams, "LiDAR beams per revolution", e);
    } else {
      const bool birds_eye = s.kind == SensorKind::kBirdsEyeCamera;
      const int width = birds_eye ? s.birds_eye.width : s.camera.width;
      const int height = birds_eye ? s.birds_eye.height : s.camera.height;
      pixels_ += static_cast<double>(width) * height;
      check(pixels_, kMaxRigPixels, "camera pixels", e);
    }
  }

 private:
  void check(double total, double limit, const char* what, const ValidatedElement& e) const {
    if (total > limit) {
      throw InputError(make_error(file_, e.line,
                                  "with this sensor the rig has " + format_double(total) + " " +
                                      what + ", more than the " + format_double(limit) +
                                      " one run can hold in memory",
                                  e.path));
    }
  }
  const std::string& file_;
  double pixels_ = 0.0;
  double beams_ = 0.0;
};

// Values were validated against the schema (types, ranges, defaults) before these are called.
double number(const ValidatedElement& e, const std::string& name) {
  return *parse_double(*e.find(name));
}
int integer(const ValidatedElement& e, const std::string& name) {
  return static_cast<int>(*parse_int(*e.find(name)));
}
bool boolean(const ValidatedElement& e, const std::string& name) {
  const std::string& v = *e.find(name);
  return v == "true" || v == "1";
}

Mount read_mount(const ValidatedElement& sensor) {
  Mount m;
  for (const auto& child : sensor.children) {
    if (child.name == "Mount") {
      m.x = number(child, "x");
      m.y = number(child, "y");
      m.z = number(child, "z");
      m.roll_deg = number(child, "roll");
      m.pitch_deg = number(child, "pitch");
      m.yaw_deg = number(child, "yaw");
    }
  }
  return m;
}

CameraIntrinsics read_intrinsics(const ValidatedElement& e) {
  CameraIntrinsics c;
  c.width = integer(e, "width");
  c.height = integer(e, "height");
  c.fov_deg = number(e, "fov");
  c.k1 = number(e, "k1");
  c.k2 = number(e, "k2");
  c.p1 = number(e, "p1");
  c.p2 = number(e, "p2");
  return c;
}

LidarOptions read_lidar(const ValidatedElement& e, const std::string& file) {
  LidarOptions l;
  l.channels = integer(e, "channels");
  l.range_m = number(e, "range");
  l.points_per_second = number(e, "pointsPerSecond");
  l.rotation_frequency_hz = number(e, "rotationFrequency");
  l.upper_fov_deg = number(e, "upperFov");
  l.lower_fov_deg = number(e, "lowerFov");
  l.horizontal_fov_deg = number(e, "horizontalFov");
  l.noise_stddev_m = number(e, "noiseStddev");
  l.dropoff_general_rate = number(e, "dropoffGeneralRate");
  l.dropoff_intensity_limit = number(e, "dropoffIntensityLimit");
  l.dropoff_zero_intensity = number(e, "dropoffZeroIntensity");
  l.atmosphere_attenuation_rate = number(e, "atmosphereAttenuationRate");
  l.keep_self_returns = *e.find("selfReturns") == "keep";
  l.deskew = boolean(e, "deskew");
  if (l.lower_fov_deg > l.upper_fov_deg) {
    throw InputError(make_error(file, e.line,
                                "<Lidar> lowerFov (" + format_double(l.lower_fov_deg) +
                                    ") is above upperFov (" + format_double(l.upper_fov_deg) + ")",
                                e.path));
  }
  if (l.channels > 1 && l.lower_fov_deg == l.upper_fov_deg) {
    throw InputError(make_error(
        file, e.line, "<Lidar> with several channels needs lowerFov below upperFov", e.path));
  }
  // One revolution must hold at least one firing per channel.
  if (l.points_per_second / (l.channels * l.rotation_frequency_hz) < 0.5) {
    throw InputError(make_error(
        file, e.line, "<Lidar> pointsPerSecond is too low for one firing per channel and turn",
        e.path));
  }
  // The simulator keeps every beam direction of a revolution (and scans them per frame): 2e7
  // points per second at 0.001 Hz asked for 2e10 beams ("out of memory", exit 3), and the
  // azimuth step count overflowed an int. Real sensors have well under a million per turn.
  const double beams = l.points_per_second / l.rotation_frequency_hz;
  if (beams > kMaxBeamsPerRevolution) {
    throw InputError(make_error(file, e.line,
                                "<Lidar> pointsPerSecond / rotationFrequency gives " +
                                    format_double(std::round(beams)) +
                                    " beams per revolution, more than the " +
                                    format_double(kMaxBeamsPerRevolution) + " simulated",
                                e.path));
  }
  return l;
}

/// A schema-validated quality word.
RenderQuality quality_of(const std::string& word) {
  return word == "fast"   ? RenderQuality::kFast
         : word == "high" ? RenderQuality::kHigh
                          : RenderQuality::kDefault;
}

SensorSpec read_sensor(const ValidatedElement& e, const std::string& file,
                       RenderQuality rig_quality) {
  SensorSpec s;
  s.name = *e.find("name");
  s.entity = *e.find("entity");
  s.rate_hz = number(e, "rate");
  s.mount = read_mount(e);
  s.line = e.line;
  if (e.name == "RgbCamera") {
    s.kind = SensorKind::kRgbCamera;
    s.camera = read_intrinsics(e);
    // Either exposure attribute makes the exposure manual (the other keeps its usual value).
    s.rgb.auto_exposure = e.find("shutterSpeed") == nullptr && e.find("iso") == nullptr;
    if (e.find("shutterSpeed") != nullptr) {
      s.rgb.shutter_speed_s = number(e, "shutterSpeed");
    }
    if (e.find("iso") != nullptr) {
      s.rgb.iso = number(e, "iso");
    }
    s.rgb.gamma = number(e, "gamma");
    s.rgb.exposure_compensation_ev = number(e, "exposureCompensation");
    s.rgb.vignetting = number(e, "vignetting");
    s.rgb.noise = boolean(e, "noise");
    s.rgb.quality = e.find("quality") != nullptr ? quality_of(*e.find("quality")) : rig_quality;
  } else if (e.name == "DepthCamera") {
    s.kind = SensorKind::kDepthCamera;
    s.camera = read_intrinsics(e);
    s.depth.max_range_m = number(e, "maxRange");
  } else if (e.name == "SemanticCamera" || e.name == "InstanceCamera") {
    s.kind = e.name == "SemanticCamera" ? SensorKind::kSemanticCamera : SensorKind::kInstanceCamera;
    s.camera = read_intrinsics(e);
  } else if (e.name == "BirdsEyeCamera") {
    s.kind = SensorKind::kBirdsEyeCamera;
    s.birds_eye.width = integer(e, "width");
    s.birds_eye.height = integer(e, "height");
    s.birds_eye.extent_m = number(e, "extent");
    s.birds_eye.altitude_m = number(e, "altitude");
    s.birds_eye.follow_heading = boolean(e, "followHeading");
    s.birds_eye.style = *e.find("style") == "rgb" ? BirdsEyeStyle::kRgb : BirdsEyeStyle::kSemantic;
  } else {
    s.kind = SensorKind::kLidar;
    s.lidar = read_lidar(e, file);
  }
  return s;
}

EntityModel read_entity_model(const ValidatedElement& e, const std::string& file) {
  EntityModel m;
  const std::string* category = e.find("category");
  const std::string* entity = e.find("entity");
  m.category = category != nullptr ? *category : "";
  m.entity = entity != nullptr ? *entity : "";
  m.line = e.line;
  m.origin = file;
  if (m.category.empty() == m.entity.empty()) {
    throw InputError(make_error(file, e.line,
                                "an EntityModel names either a category or an entity (not both, "
                                "not neither)",
                                e.path));
  }
  // Relative model paths are the rig file's neighbours, as a user writes them.
  m.file = *e.find("file");
  if (m.file.is_relative()) {
    m.file = std::filesystem::path(file).parent_path() / m.file;
  }
  return m;
}

}  // namespace

std::string_view render_quality_name(RenderQuality quality) {
  switch (quality) {
    case RenderQuality::kFast:
      return "fast";
    case RenderQuality::kDefault:
      return "default";
    case RenderQuality::kHigh:
      return "high";
  }
  return "default";
}

std::string_view sensor_kind_name(SensorKind kind) {
  switch (kind) {
    case SensorKind::kRgbCamera:
      return "RgbCamera";
    case SensorKind::kDepthCamera:
      return "DepthCamera";
    case SensorKind::kSemanticCamera:
      return "SemanticCamera";
    case SensorKind::kInstanceCamera:
      return "InstanceCamera";
    case SensorKind::kBirdsEyeCamera:
      return "BirdsEyeCamera";
    case SensorKind::kLidar:
      return "Lidar";
  }
  return "Sensor";
}

int LidarOptions::azimuth_steps() const {
  const double steps = std::round(points_per_second / (channels * rotation_frequency_hz));
  return steps < 1.0 ? 1 : static_cast<int>(steps);
}

const SensorSpec* SensorRig::find(std::string_view sensor_name) const {
  for (const auto& s : sensors) {
    if (s.name == sensor_name) {
      return &s;
    }
  }
  return nullptr;
}

SensorRig parse_rig(std::string_view xml, const std::string& file) {
  const XsdSchema schema(detail::rig_schema_text());
  const ValidatedElement root = schema.validate(xml, file);
  SensorRig rig;
  rig.name = *root.find("name");
  rig.file = file;
  rig.quality = quality_of(*root.find("quality"));
  rig.generate_buildings = *root.find("buildings") == "generate";
  const std::string& parked = *root.find("parkedVehicles");
  rig.parked_vehicles = parked == "none"   ? ParkedVehicles::kNone
                        : parked == "kerb" ? ParkedVehicles::kKerb
                                           : ParkedVehicles::kMap;
  rig.parked_density = number(root, "parkedDensity");
  std::set<std::string> names;
  RigBudget budget(file);
  for (const auto& e : root.children) {
    if (e.name == "EntityModel") {
      rig.entity_models.push_back(read_entity_model(e, file));
      continue;
    }
    SensorSpec s = read_sensor(e, file, rig.quality);
    budget.add(s, e);
    if (!names.insert(s.name).second) {
      throw InputError(make_error(file, e.line,
                                  "a sensor named '" + s.name + "' is already in the rig", e.path));
    }
    rig.sensors.push_back(std::move(s));
  }
  return rig;
}

SensorRig load_rig(const std::filesystem::path& path) {
  return parse_rig(read_file(path), path.string());
}

void bind_rig(const SensorRig& rig, std::span<const std::string> entity_names) {
  for (const EntityModel& m : rig.entity_models) {
    if (!m.entity.empty() &&
        std::find(entity_names.begin(), entity_names.end(), m.entity) == entity_names.end()) {
      throw InputError(make_error(rig.file, m.line,
                                  "an EntityModel names entity '" + m.entity +
                                      "', which the scenario does not have" +
                                      did_you_mean(m.entity, entity_names),
                                  "SensorRig/EntityModel"));
    }
  }
  for (const auto& s : rig.sensors) {
    bool found = false;
    for (const auto& name : entity_names) {
      found = found || name == s.entity;
    }
    if (!found) {
      std::string known;
      for (const auto& name : entity_names) {
        known += (known.empty() ? "" : ", ") + name;
      }
      throw InputError(make_error(
          rig.file, s.line,
          "sensor '" + s.name + "' is attached to entity '" + s.entity +
              "', which the scenario does not have" + did_you_mean(s.entity, entity_names) +
              " (entities: " + (known.empty() ? std::string("none") : known) + ")",
          "SensorRig/" + std::string(sensor_kind_name(s.kind))));
    }
  }
}

}  // namespace corsa::sensors
