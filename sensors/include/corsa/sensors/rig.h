#pragma once

// Sensor rig files (schemas/sensor-rig.xsd): sensors attached to scenario entities with a
// mounting pose, a capture rate and their options. Loading validates against the schema and
// reports `file:line: error: message`; binding to a scenario checks the entity names.

#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "corsa/sensors/world.h"

namespace corsa::sensors {

enum class SensorKind {
  kRgbCamera,
  kDepthCamera,
  kSemanticCamera,
  kInstanceCamera,
  kBirdsEyeCamera,
  kLidar,
};

/// The rig element name of a kind ("RgbCamera", "Lidar", ...).
std::string_view sensor_kind_name(SensorKind kind);

/// Mounting pose of the sensor body frame (x forward, y left, z up) relative to the entity's
/// reference point: metres and degrees, rotation R = Rz(yaw) Ry(pitch) Rx(roll).
struct Mount {
  double x = 0.0, y = 0.0, z = 0.0;
  double roll_deg = 0.0, pitch_deg = 0.0, yaw_deg = 0.0;
};

/// Pinhole intrinsics from the image size and the horizontal field of view, with OpenCV's
/// distortion model (radial k1, k2; tangential p1, p2).
struct CameraIntrinsics {
  int width = 1280;
  int height = 720;
  double fov_deg = 90.0;  ///< horizontal
  double k1 = 0.0, k2 = 0.0, p1 = 0.0, p2 = 0.0;
};

/// How much work the RGB image gets (docs/sensors.md, "Image formation"): `kFast` shades one
/// sample per pixel with hard sun shadows and no secondary rays; `kDefault` adds soft sun
/// shadows, sky occlusion with one bounce, reflections, see-through glass, shadowed street and
/// vehicle lights and anti-aliased edges; `kHigh` takes more of every kind of sample.
enum class RenderQuality { kFast, kDefault, kHigh };

/// The rig's word for a quality ("fast", "default", "high").
std::string_view render_quality_name(RenderQuality quality);

struct RgbOptions {
  /// Exposure time (s): brightness and motion blur. With `auto_exposure` the metering chooses
  /// it per frame and this value is unused.
  double shutter_speed_s = 0.004;
  double iso = 100.0;  ///< sensitivity: brightness and noise (auto exposure chooses it too)
  /// Meter every frame (exposure time, then gain); false when the rig gives shutterSpeed or
  /// iso, which then fix the exposure as a manual camera would.
  bool auto_exposure = true;
  double gamma = 2.2;  ///< display encoding after the tone curve
  double exposure_compensation_ev = 0.0;
  double vignetting = 0.25;  ///< share of light lost in the image corners (0: none)
  bool noise = true;
  RenderQuality quality = RenderQuality::kDefault;
};

struct DepthOptions {
  double max_range_m = 1000.0;  ///< beyond this a pixel is empty (0)
};

enum class BirdsEyeStyle { kSemantic, kRgb };

struct BirdsEyeOptions {
  int width = 640;
  int height = 640;
  double extent_m = 80.0;     ///< ground width covered by the image
  double altitude_m = 100.0;  ///< view height above the entity
  bool follow_heading = true;
  BirdsEyeStyle style = BirdsEyeStyle::kSemantic;
};

struct LidarOptions {
  int channels = 32;
  double range_m = 100.0;
  double points_per_second = 600000.0;
  double rotation_frequency_hz = 10.0;
  double upper_fov_deg = 10.0;
  double lower_fov_deg = -30.0;
  double horizontal_fov_deg = 360.0;
  double noise_stddev_m = 0.0;
  double dropoff_general_rate = 0.0;
  double dropoff_intensity_limit = 0.0;
  double dropoff_zero_intensity = 0.0;
  double atmosphere_attenuation_rate = 0.004;  ///< 1/m
  /// Keep returns from the entity carrying the sensor (default: masked, like a driver's
  /// self-filter; a beam that hits the carrier gives no point).
  bool keep_self_returns = false;
  /// Points in the sensor frame at the capture time (the sensor's own motion during the sweep
  /// removed) instead of the frame at each point's firing time.
  bool deskew = false;

  /// Firings per channel in one revolution: points_per_second / (channels * rotation_frequency),
  /// rounded, at least 1.
  int azimuth_steps() const;
};

struct SensorSpec {
  std::string name;
  SensorKind kind = SensorKind::kRgbCamera;
  std::string entity;
  double rate_hz = 10.0;
  Mount mount;
  CameraIntrinsics camera;  ///< cameras other than bird's-eye
  RgbOptions rgb;
  DepthOptions depth;
  BirdsEyeOptions birds_eye;
  LidarOptions lidar;
  int line = 0;  ///< line of the sensor element in the rig file, for messages
};

/// The user's model for entities without a model3d of their own (<EntityModel>): for one
/// scenario entity by name, or for every entity of an OpenSCENARIO category. The model is
/// stretched onto each entity's bounding box (see ModelShapeSource in model_io.h).
struct EntityModel {
  std::string category;        ///< "car", "pedestrian", ...; empty when `entity` is given
  std::string entity;          ///< a scenario entity's name; empty: the whole category
  std::filesystem::path file;  ///< as written, resolved against the rig file's folder
  int line = 0;                ///< line of the element in the rig file, for messages
  /// Where it was given, for messages: the rig file, or the command line's
  /// "--entity-model WHO=FILE" (line 0).
  std::string origin;
};

struct SensorRig {
  std::string name;
  RenderQuality quality = RenderQuality::kDefault;  ///< for RGB cameras that name none
  /// buildings="generate": the world gets generated buildings along its streets where none
  /// stands (WorldOptions::buildings).
  bool generate_buildings = false;
  /// parkedVehicles="none|map|kerb" (WorldOptions::parked) and parkedDensity.
  ParkedVehicles parked_vehicles = ParkedVehicles::kMap;
  double parked_density = 0.6;
  std::string file;  ///< as named by the user, for messages
  std::vector<SensorSpec> sensors;
  std::vector<EntityModel> entity_models;  ///< in rig order; an entity's own name first

  const SensorSpec* find(std::string_view sensor_name) const;
};

/// Reads and validates a rig file. Throws corsa::InputError (file:line) on any problem.
SensorRig load_rig(const std::filesystem::path& path);
/// The same from text; `file` names it in messages.
SensorRig parse_rig(std::string_view xml, const std::string& file);

/// Checks the rig against the scenario's entity names: an unknown entity throws InputError
/// located at the sensor's (or entity model's) line in the rig file.
void bind_rig(const SensorRig& rig, std::span<const std::string> entity_names);

}  // namespace corsa::sensors
