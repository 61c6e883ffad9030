#pragma once

// Spinning LiDAR: `channels` beams evenly spaced from lowerFov to upperFov, each fired
// azimuth_steps() times per revolution evenly over the horizontal field of view (centred on the
// sensor's x axis). One capture is one revolution, swept counter-clockwise seen from above and
// centred on the capture time: the beam along the sensor's x axis (forward) fires at the capture
// time, as KITTI's cameras are triggered when its LiDAR faces forward; a point at azimuth a fires
// a / (2 pi rotationFrequency) seconds from it. The sensor moves during the sweep (the carrier's
// velocity and yaw rate) and so do the other entities (Scene::set_entities with a motion span):
// a rolling shutter. Points are in the sensor frame at their firing time, or at the capture time
// with `deskew`.
//
// Return model, per beam that hits something at range r <= range:
//   intensity = reflectivity(class) * |cos(incidence)| * e^(-atmosphereAttenuationRate r) * T
//   T = e^(-2 alpha r), alpha = fog + rain + snow extinction (two-way Beer-Lambert transmission);
//   the return survives the weather with probability T (so fog, rain and snow thin the cloud and
//   shorten its reach), then is dropped with probability dropoffGeneralRate, and, when its
//   intensity is below dropoffIntensityLimit, with probability dropoffZeroIntensity;
//   the reported range gets Gaussian noise of noiseStddev.
// Weather also gives early returns (lidar_weather.h): the fog's backscatter (Hahner et al. 2021)
// and single rain drops or snowflakes in the beam (Kilic et al. 2021) compete with the target's
// return; the strongest above the detection threshold is reported (semantic class none,
// instance 0). Hits on the carrying entity are masked unless keepSelfReturns.
// Random draws come from a counter-based stream per beam, keyed by (frame seed, beam index), so
// the result is the same bytes whatever the thread count or work split.

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "corsa/sensors/box.h"
#include "corsa/sensors/geometry.h"
#include "corsa/sensors/rig.h"
#include "corsa/sensors/scene.h"
#include "corsa/sensors/semantic.h"

namespace corsa::sensors {

namespace detail {
class LidarWeatherModel;
}

/// One return, in the sensor body frame (x forward, y left, z up), metres.
struct LidarPoint {
  float x = 0.0f, y = 0.0f, z = 0.0f;
  float intensity = 0.0f;  ///< 0..1
  uint16_t ring = 0;       ///< channel, 0 = lowest beam
  uint16_t azimuth_index = 0;
  SemanticClass semantic = SemanticClass::kUnlabeled;
  uint32_t instance_id = 0;
  float time = 0.0f;  ///< firing time relative to the capture time, s
};

struct PointCloud {
  std::vector<LidarPoint> points;  ///< in firing order: azimuth by azimuth, beams bottom to top
  int channels = 0;
  int azimuth_steps = 0;
  uint64_t rays = 0;  ///< beams fired
};

/// Diffuse reflectivity of a class at 905 nm (0..1), for the intensity model.
double lidar_reflectivity(SemanticClass c);

/// The atmosphere of a scan (from the environment at the capture).
struct LidarWeather {
  double fog_extinction = 0.0;  ///< 1/m (Koschmieder: 3.912 / visual range)
  double rain_rate = 0.0;       ///< mm/h
  double snow_rate = 0.0;       ///< mm/h, water equivalent
  bool any() const { return fog_extinction > 0.0 || rain_rate > 0.0 || snow_rate > 0.0; }
};

/// How the carrier moves during a sweep (map frame): velocity of its reference point and yaw
/// rate about the map's up axis through that point.
struct SensorMotion {
  Vec3 velocity;          ///< m/s
  double yaw_rate = 0.0;  ///< rad/s
  Vec3 pivot;             ///< the carrier's reference point, map frame
};

/// Everything one scan needs besides the scene.
struct LidarScanInput {
  Rigid world_from_sensor;  ///< sensor body frame to map at the capture time
  SensorMotion motion;      ///< zero: a still sensor
  LidarWeather weather;
  uint64_t frame_seed = 0;  ///< seeds the noise
  /// Bounding box (map frame) of the carrier: beams start where they leave it, so a sensor
  /// inside its vehicle does not see it.
  std::optional<Box3> carrier;
  uint32_t carrier_instance = 0;  ///< the carrier's instance id, for the self-return mask
  /// The scene's entity motion interval (s, centred on the capture time) given to
  /// Scene::set_entities; 0 when the entities stand still during the sweep.
  double scene_motion_span = 0.0;
};

class LidarSimulator {
 public:
  explicit LidarSimulator(const LidarOptions& options);

  /// One revolution (see the file comment).
  PointCloud scan(const Scene& scene, const LidarScanInput& input) const;
  /// The same for a still sensor in fog of extinction `fog_extinction` (1/m) only.
  PointCloud scan(const Scene& scene, const Rigid& world_from_sensor, double fog_extinction,
                  uint64_t frame_seed, const std::optional<Box3>& carrier = std::nullopt) const;

  /// Firing time of azimuth step `step` relative to the capture time, s.
  double step_time(int step) const;

  const LidarOptions& options() const { return options_; }
  int azimuth_steps() const { return steps_; }
  /// Elevation of a channel and azimuth of a step in the sensor frame, radians.
  double elevation(int channel) const;
  double azimuth(int step) const;
  /// Unit beam directions in the sensor body frame, 3 floats per beam, in firing order.
  const std::vector<float>& directions() const { return directions_; }

 private:
  LidarOptions options_;
  int steps_ = 1;
  std::vector<float> directions_;
  std::vector<float> packet_directions_;  ///< the same, per packet of 16 beams: x, y, z planes
  std::shared_ptr<const detail::LidarWeatherModel> weather_model(const LidarWeather& w) const;
  mutable std::mutex weather_mutex_;
  mutable std::shared_ptr<const detail::LidarWeatherModel> weather_cache_;  ///< the last one
};

}  // namespace corsa::sensors
