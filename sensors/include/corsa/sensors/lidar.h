#pragma once

// Spinning LiDAR: `channels` beams evenly spaced from lowerFov to upperFov, each fired
// azimuth_steps() times per revolution evenly over the horizontal field of view (centred on the
// sensor's x axis). One capture is one revolution at the capture time (the motion during the
// sweep is not modelled).
//
// Return model, per beam that hits something at range r <= range:
//   intensity = reflectivity(class) * |cos(incidence)| * e^(-atmosphereAttenuationRate r) * T
//   T = e^(-2 sigma r), sigma = fog + rain extinction (two-way Beer-Lambert transmission);
//   the return survives the weather with probability T (so fog and rain thin the cloud and
//   shorten its reach), then is dropped with probability dropoffGeneralRate, and, when its
//   intensity is below dropoffIntensityLimit, with probability dropoffZeroIntensity;
//   the reported range gets Gaussian noise of noiseStddev.
// Random draws come from a counter-based stream per beam, keyed by (frame seed, beam index), so
// the result is the same bytes whatever the thread count or work split.

#include <cstdint>
#include <optional>
#include <vector>

#include "corsa/sensors/box.h"
#include "corsa/sensors/geometry.h"
#include "corsa/sensors/rig.h"
#include "corsa/sensors/scene.h"
#include "corsa/sensors/semantic.h"

namespace corsa::sensors {

/// One return, in the sensor body frame (x forward, y left, z up), metres.
struct LidarPoint {
  float x = 0.0f, y = 0.0f, z = 0.0f;
  float intensity = 0.0f;  ///< 0..1
  uint16_t ring = 0;       ///< channel, 0 = lowest beam
  uint16_t azimuth_index = 0;
  SemanticClass semantic = SemanticClass::kUnlabeled;
  uint32_t instance_id = 0;
};

struct PointCloud {
  std::vector<LidarPoint> points;  ///< in firing order: azimuth by azimuth, beams bottom to top
  int channels = 0;
  int azimuth_steps = 0;
  uint64_t rays = 0;  ///< beams fired
};

/// Diffuse reflectivity of a class at 905 nm (0..1), for the intensity model.
double lidar_reflectivity(SemanticClass c);

class LidarSimulator {
 public:
  explicit LidarSimulator(const LidarOptions& options);

  /// One revolution from the sensor pose (sensor body frame to map). `weather_extinction` is
  /// fog + rain extinction in 1/m (Lighting::extinction()); `frame_seed` seeds the noise.
  /// `carrier` is the bounding box (map frame) of the entity carrying the sensor: beams start
  /// where they leave it, so a sensor inside its own vehicle does not see the vehicle.
  PointCloud scan(const Scene& scene, const Rigid& world_from_sensor, double weather_extinction,
                  uint64_t frame_seed, const std::optional<Box3>& carrier = std::nullopt) const;

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
};

}  // namespace corsa::sensors
