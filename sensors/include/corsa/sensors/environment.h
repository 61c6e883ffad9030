#pragma once

// What the renderer and the LiDAR need from the environment: sun direction and colour, the sky
// (corsa/sensors/sky.h) and its light, fog, haze, rain and snow, wet road, night. Colours are
// linear RGB in relative units: radiance 1 is a white diffuse surface under 100,000 lux, and
// an irradiance E is given as E / 100,000 lux (so that a white surface's radiance equals it).

#include "corsa/engine/world_snapshot.h"
#include "corsa/sensors/color.h"
#include "corsa/sensors/geometry.h"
#include "corsa/sensors/sky.h"

namespace corsa::sensors {

/// Where the map is on Earth (for the solar position).
struct GeoLocation {
  double latitude_deg = 37.5665;  ///< default: Seoul
  double longitude_deg = 126.978;
};

/// Koschmieder: the visual range V is where contrast falls to 2%, so the extinction coefficient
/// is ln(50) / V = 3.912 / V (1/m).
double fog_extinction(double visual_range_m);
/// Extinction by rain of intensity R mm/h (1/m): drops of Marshall and Palmer's (1948) size
/// distribution N(D) = N0 e^(-Lambda D), N0 = 8000 1/(m^3 mm), Lambda = 4.1 R^-0.21 1/mm, each
/// removing twice its cross-section (geometric optics, drops >> wavelength): pi N0 / Lambda^3 =
/// 3.65e-4 R^0.63 (10 mm/h: 1.6e-3 1/m, a visual range of 2.5 km). The camera and the LiDAR
/// use the same figure, computed with corsa::det so that LiDAR draws are bit-identical anywhere.
double rain_extinction(double intensity_mm_per_h);
/// Dry snowflakes are aggregates whose bulk density falls as one over their diameter:
/// rho_s D = C3 = 0.017 g/cm^2 = 0.17 kg/m^2 (Holroyd 1971, as used by Rasmussen et al. 1999 for
/// dry unrimed aggregates). A flake is so much larger than the drop it melts to (a 1 mm drop
/// comes from a 2.4 mm flake, a 2 mm drop from a 6.9 mm one).
inline constexpr double kDrySnowDensityDiameter = 0.17;  // kg/m^2
/// Fall speed of dry aggregates, m/s (Rasmussen et al. 1999's 100 cm/s).
inline constexpr double kDrySnowFallSpeed = 1.0;
/// Extinction by dry snowfall of R mm/h water equivalent (1/m): Rasmussen, Vivekanandan, Cole,
/// Myers and Masters, "The estimation of snowfall rate using visibility", J. Appl. Meteor. 38
/// (1999), Eq. 13 for aggregates of rho_s D = C3 falling at Vt: whatever their size
/// distribution, each flake removes twice its cross-section (pi/4) D^2 and carries the water
/// (pi/6) C3 D^2 at Vt, so sigma = 3 rho_w S / (C3 Vt) with S the liquid-equivalent flux (m/s):
/// 4.9e-3 R 1/m, a visual range of 0.80 km at 1 mm/h (their Fig. 10: 0.3-0.4 km at 2 mm/h).
/// Melted drops of the same rate (Gunn and Marshall 1958) would give only 7.2e-4 R^0.57.
double snow_extinction(double intensity_mm_per_h);

/// Scale height of fog (m): its density falls by e every this many metres above the ground.
inline constexpr double kFogScaleHeight = 80.0;
/// Scale height of the clear-air haze (aerosols), m.
inline constexpr double kHazeScaleHeight = 1200.0;

struct Lighting {
  Vec3 sun_direction{0.0, 0.0, 1.0};  ///< unit vector towards the sun, map frame (x east, y north)
  double sun_elevation = 1.0;         ///< radians
  /// Direct sunlight on a surface facing the sun (after the atmosphere and the clouds).
  Color sun;
  double sun_angular_radius = 0.00465;  ///< radians (the solar disc, for soft shadows)
  SkyModel sky_model;                   ///< sky radiance by direction
  IrradianceSH sky_light;               ///< sky (and ground) light by surface orientation
  Color ambient;                        ///< sky light on an upward surface (sky_light of +z)
  Color fog_color;  ///< radiance of a deep layer of fog or haze lit by the sky and the sun
  double fog_extinction = 0.0;   ///< 1/m, fog only, at ground level (falls off with height)
  double haze_extinction = 0.0;  ///< 1/m, clear-air haze at ground level
  double rain_extinction = 0.0;  ///< 1/m
  double rain_intensity = 0.0;   ///< mm/h, 0 when dry or snowing
  double snow_intensity = 0.0;   ///< mm/h of water, 0 when not snowing
  double snow_extinction = 0.0;  ///< 1/m, falling snow
  double cloud_cover = 0.0;      ///< 0 clear .. 1 overcast
  bool wet_road = false;
  bool headlights = false;  ///< dark enough for vehicles to drive with lights
  double darkness = 0.0;    ///< 0 day .. 1 night: street lamps and lit windows switch on
  double wind_direction = 0.0;
  double wind_speed = 0.0;

  /// Total extinction at ground level (fog + rain + snow, without the haze) for light and
  /// LiDAR, 1/m.
  double extinction() const { return fog_extinction + rain_extinction + snow_extinction; }
  /// Sky radiance seen in a direction (unit, map frame), without fog, with the sun's disc.
  Color sky(Vec3 direction) const;
  /// Share of light that crosses the air from a point `height` metres above the ground along
  /// `distance` metres of a ray whose direction has z component `dir_z` (fog and haze thin out
  /// with height; rain and snow fill the lowest 2 km evenly). What is lost is replaced by
  /// fog_color: seen = radiance * t + fog_color * (1 - t). `distance` may be infinite (the
  /// sky, whose model already holds the haze: pass haze = false).
  double transmittance(double height, double dir_z, double distance, bool haze = true) const;

  /// The part of transmittance() that depends only on where rays start: the fog and haze
  /// extinction (1/m) at that height. A camera's primary rays all start at one height.
  struct AirStart {
    double fog = 0.0;
    double haze = 0.0;
  };
  AirStart air_start(double height) const;
  /// transmittance() of a ray starting where `start` was taken (the same value).
  double transmittance(const AirStart& start, double dir_z, double distance,
                       bool haze = true) const;
  /// transmittance(start, dir_z[i], distance[i]) with the haze into out[i] for n rays of finite
  /// distance, two at a time, with exponentials of its own instead of the maths library's
  /// (within a few ulp of them: sensors/src/air_math.h). Deterministic; not the same bits as
  /// transmittance() on every ray (the `fast` camera's primary rays).
  void transmittances(const AirStart& start, const double* dir_z, const double* distance, int n,
                      double* out) const;
};

/// Lighting from the environment: the sun from the snapshot's sun angles when given, otherwise
/// from date, time and location.
Lighting compute_lighting(const engine::EnvironmentState& environment, const GeoLocation& where);

}  // namespace corsa::sensors
