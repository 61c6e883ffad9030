#pragma once

// What the renderer and the LiDAR need from the environment: sun direction and colour, sky,
// fog and rain extinction, wet road, night. Colours are linear RGB radiance in relative units
// (1 = a white surface facing the noon sun on a clear day).

#include "corsa/engine/world_snapshot.h"
#include "corsa/sensors/color.h"
#include "corsa/sensors/geometry.h"

namespace corsa::sensors {

/// Where the map is on Earth (for the solar position).
struct GeoLocation {
  double latitude_deg = 37.5665;  ///< default: Seoul
  double longitude_deg = 126.978;
};

/// Koschmieder: the visual range V is where contrast falls to 2%, so the extinction coefficient
/// is ln(50) / V = 3.912 / V (1/m).
double fog_extinction(double visual_range_m);
/// Extinction by rain of intensity R mm/h (1/m), an empirical power law 2e-4 * R^0.6 chosen so
/// that 10 mm/h halves a 905 nm LiDAR return at ~440 m two-way and hazes a camera at km range.
double rain_extinction(double intensity_mm_per_h);

struct Lighting {
  Vec3 sun_direction{0.0, 0.0, 1.0};  ///< unit vector towards the sun, map frame (x east, y north)
  double sun_elevation = 1.0;         ///< radians
  Color sun;                          ///< direct sunlight reaching the ground
  Color sky_zenith;
  Color sky_horizon;
  Color ambient;  ///< diffuse sky light on an upward surface
  Color fog_color;
  double fog_extinction = 0.0;   ///< 1/m, fog only
  double rain_extinction = 0.0;  ///< 1/m
  double rain_intensity = 0.0;   ///< mm/h, 0 when dry or snowing
  bool wet_road = false;
  bool headlights = false;  ///< dark enough for vehicles to drive with lights
  double wind_direction = 0.0;
  double wind_speed = 0.0;

  /// Total extinction (fog + rain) for light and LiDAR, 1/m.
  double extinction() const { return fog_extinction + rain_extinction; }
  /// Sky radiance seen in a direction (unit, map frame), without fog.
  Color sky(Vec3 direction) const;
};

/// Lighting from the environment: the sun from the snapshot's sun angles when given, otherwise
/// from date, time and location.
Lighting compute_lighting(const engine::EnvironmentState& environment, const GeoLocation& where);

}  // namespace corsa::sensors
