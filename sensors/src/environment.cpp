#include "corsa/sensors/environment.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "air_math.h"
#include "corsa/core/det_math.h"
#include "corsa/sensors/solar.h"
#include "scalar_math.h"

namespace corsa::sensors {

using detail::kDeg;
using detail::smoothstep;
namespace {

double luminance(Color c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

/// Relative air mass (Kasten and Young 1989), elevation in degrees.
double air_mass(double elevation_deg) {
  const double el = std::max(elevation_deg, -0.5);
  return 1.0 / (std::sin(el * kDeg) + 0.50572 * std::pow(el + 6.07995, -1.6364));
}

/// Transmittance of the clear atmosphere for direct sunlight at 680, 550 and 440 nm over an air
/// mass m: Rayleigh optical depth 0.008735 lambda^-4.08 (Leckner 1978) and Angstrom's aerosol
/// law beta lambda^-1.3 with beta = 0.04608 T - 0.04586 for turbidity T (Preetham et al. 1999,
/// appendix A.3).
Color sun_transmittance(double m, double turbidity) {
  const double beta = 0.04608 * turbidity - 0.04586;
  const double lambda[3] = {0.68, 0.55, 0.44};  // micrometres
  double t[3];
  for (int k = 0; k < 3; ++k) {
    const double rayleigh = 0.008735 * std::pow(lambda[k], -4.08);
    const double aerosol = beta * std::pow(lambda[k], -1.3);
    t[k] = std::exp(-m * (rayleigh + aerosol));
  }
  return {t[0], t[1], t[2]};
}

/// (1 - e^-x) / x, 1 at 0.
double expm1_ratio(double x) {
  if (std::fabs(x) < 1e-5) {
    return 1.0 - 0.5 * x;
  }
  return -std::expm1(-x) / x;
}

/// Extinction (1/m) at height h of an exponential layer (sigma at the ground, scale height H).
double layer_start(double sigma, double scale_height, double h) {
  if (sigma <= 0.0) {
    return 0.0;
  }
  return sigma * std::exp(-std::max(h, -scale_height) / scale_height);
}

/// Optical depth of an exponential layer of scale height H along a ray that starts where its
/// extinction is `at_start`, with direction z component dz, over distance d (may be infinite).
double layer_depth(double at_start, double scale_height, double dz, double d) {
  if (at_start <= 0.0) {
    return 0.0;
  }
  if (std::isinf(d)) {
    return dz > 1e-4 ? at_start * scale_height / dz : std::numeric_limits<double>::infinity();
  }
  return at_start * d * expm1_ratio(d * dz / scale_height);
}

/// The sun's position: from the snapshot's sun angles when the scenario gives them, otherwise
/// from date, time and location.
void place_sun(const engine::EnvironmentState& env, const GeoLocation& where, Lighting& l) {
  double azimuth = 0.0;
  double elevation = 0.0;
  if (env.sun_azimuth && env.sun_elevation) {
    azimuth = *env.sun_azimuth;
    elevation = *env.sun_elevation;
  } else {
    const SolarPosition p =
        solar_position(env.year, env.month, env.day, env.time_of_day, env.utc_offset_hours,
                       where.latitude_deg, where.longitude_deg);
    azimuth = p.azimuth;
    elevation = p.elevation;
  }
  l.sun_elevation = elevation;
  // Azimuth clockwise from north: east component sin, north component cos.
  l.sun_direction = normalized({std::sin(azimuth) * std::cos(elevation),
                                std::cos(azimuth) * std::cos(elevation), std::sin(elevation)});
}

}  // namespace

double fog_extinction(double visual_range_m) {
  if (!(visual_range_m > 0.0) || std::isinf(visual_range_m)) {
    return visual_range_m > 0.0 ? 0.0 : 1e3;
  }
  return std::log(50.0) / visual_range_m;
}

namespace {

// pi N0 / Lambda^3 for an exponential size distribution N0 e^(-Lambda D) of particles much larger
// than the wavelength (extinction efficiency 2), in 1/m from N0 in 1/(m^3 mm) and Lambda in 1/mm.
// corsa::det, so that the LiDAR's draws see the same bits everywhere.
double exponential_extinction(double n0, double lambda) {
  const double n0_m = n0 * 1e3;          // 1/m^4
  const double lambda_m = lambda * 1e3;  // 1/m
  return std::numbers::pi * n0_m / (lambda_m * lambda_m * lambda_m);
}

double power(double x, double p) { return det::exp(p * det::log(x)); }

}  // namespace

double rain_extinction(double intensity_mm_per_h) {
  if (!(intensity_mm_per_h > 0.0)) {
    return 0.0;
  }
  return exponential_extinction(8000.0, 4.1 * power(intensity_mm_per_h, -0.21));
}

double snow_extinction(double intensity_mm_per_h) {
  if (!(intensity_mm_per_h > 0.0)) {
    return 0.0;
  }
  constexpr double kWaterDensity = 1000.0;                 // kg/m^3
  const double flux = intensity_mm_per_h * 1e-3 / 3600.0;  // m/s of water
  return 3.0 * kWaterDensity * flux / (kDrySnowDensityDiameter * kDrySnowFallSpeed);
}

Color Lighting::sky(Vec3 d) const {
  Color c = sky_model.radiance(d);
  // The solar disc and its aureole (forward scattering by aerosols), both from the direct sun.
  const double cos_sun = dot(d, sun_direction);
  if (cos_sun > 0.99) {
    const double a = std::acos(std::min(cos_sun, 1.0));
    // Radiance of a disc of solid angle pi r^2 giving irradiance `sun`: sun / r^2 (units).
    const double disc =
        a < sun_angular_radius ? 1.0 / (sun_angular_radius * sun_angular_radius) : 0.0;
    const double aureole = 0.4 * std::exp(-a / 0.02);
    c = c + sun * (disc + aureole);
  }
  return c;
}

double Lighting::transmittance(double height, double dir_z, double distance, bool haze) const {
  return transmittance(air_start(height), dir_z, distance, haze);
}

Lighting::AirStart Lighting::air_start(double height) const {
  return {layer_start(fog_extinction, kFogScaleHeight, height),
          layer_start(haze_extinction, kHazeScaleHeight, height)};
}

double Lighting::transmittance(const AirStart& start, double dir_z, double distance,
                               bool haze) const {
  double tau = layer_depth(start.fog, kFogScaleHeight, dir_z, distance);
  if (haze) {
    tau += layer_depth(start.haze, kHazeScaleHeight, dir_z, distance);
  }
  // Rain and snow fill the lowest 2 km evenly.
  const double falling = rain_extinction + snow_extinction;
  if (falling > 0.0) {
    const double column = dir_z > 1e-3 ? 2000.0 / dir_z : std::numeric_limits<double>::infinity();
    tau += falling * std::min(distance, column);
  }
  return std::isinf(tau) ? 0.0 : std::exp(-tau);
}

void Lighting::transmittances(const AirStart& start, const double* dir_z, const double* distance,
                              int n, double* out) const {
  using detail::AirLanes;
  // transmittance() two rays at a time, each operation in the same order.
  auto depth = [](double at_start, double scale_height, AirLanes dz, AirLanes d) {
    return at_start * d * detail::air_expm1_ratio(d * dz / scale_height);
  };
  const double falling = rain_extinction + snow_extinction;
  for (int i = 0; i < n; i += 2) {
    const int j = i + 1 < n ? i + 1 : i;  // an odd count repeats its last ray
    const AirLanes dz{dir_z[i], dir_z[j]};
    const AirLanes d{distance[i], distance[j]};
    AirLanes tau{0.0, 0.0};
    if (start.fog > 0.0) {
      tau = depth(start.fog, kFogScaleHeight, dz, d);
    }
    if (start.haze > 0.0) {
      tau += depth(start.haze, kHazeScaleHeight, dz, d);
    }
    if (falling > 0.0) {
      constexpr double kInf = std::numeric_limits<double>::infinity();
      const AirLanes column = dz > 1e-3 ? 2000.0 / dz : kInf;
      tau += falling * (column < d ? column : d);
    }
    const AirLanes t = detail::air_exp_limited(-tau);
    out[i] = t[0];
    out[j] = t[1];
  }
}

Lighting compute_lighting(const engine::EnvironmentState& env, const GeoLocation& where) {
  Lighting l;
  place_sun(env, where, l);
  const double el_deg = l.sun_elevation / kDeg;
  const bool rain =
      env.precipitation == engine::PrecipitationType::kRain && env.precipitation_intensity > 0.0;
  const bool snow =
      env.precipitation == engine::PrecipitationType::kSnow && env.precipitation_intensity > 0.0;
  const double clouds = std::clamp(std::max(env.cloud_cover, rain || snow ? 0.9 : 0.0), 0.0, 1.0);
  l.cloud_cover = clouds;
  l.fog_extinction = fog_extinction(env.fog_visual_range);
  l.rain_intensity = rain ? env.precipitation_intensity : 0.0;
  l.rain_extinction = rain_extinction(l.rain_intensity);
  l.snow_intensity = snow ? env.precipitation_intensity : 0.0;
  l.snow_extinction = snow_extinction(l.snow_intensity);
  // Clear-air turbidity (Preetham's T): a clear day, hazier in mist.
  const double turbidity =
      2.6 + std::min(4.0, std::isinf(env.fog_visual_range) ? 0.0 : 3000.0 / env.fog_visual_range);
  // Haze: the aerosol extinction of that turbidity at 550 nm (Angstrom beta, scale height
  // 1.2 km) plus air: tens of kilometres of visual range.
  l.haze_extinction =
      (0.04608 * turbidity - 0.04586) * std::pow(0.55, -1.3) / kHazeScaleHeight + 1.2e-5;

  // Direct sun: through the air mass, thinned by clouds and by the fog layer above the ground.
  const double scale = std::max(0.0, env.sun_intensity) / 100000.0;
  const double above = smoothstep(-0.8, 1.0, el_deg);
  const Color t = sun_transmittance(air_mass(el_deg), turbidity);
  const Color t_zenith = sun_transmittance(1.0, turbidity);
  const double sin_el = std::max(std::sin(l.sun_elevation), 0.0);
  const double through_fog = std::exp(-l.fog_extinction * kFogScaleHeight / std::max(sin_el, 0.05));
  const double cloud_pass = 1.0 - std::pow(clouds, 1.5);
  const Color clear_sun = t * (above * scale / luminance(t_zenith));
  l.sun = clear_sun * (cloud_pass * through_fog);

  // Sky: Preetham's clear sky, faded through twilight (the fit is held at the horizon below
  // 2 degrees and dimmed by a decade every 2.5 degrees, as horizontal illuminance falls from
  // ~700 lux at sunset to ~3 lux at the end of civil twilight).
  SkyModel& sky = l.sky_model;
  sky.sun_direction = l.sun_direction;
  sky.sun_elevation = l.sun_elevation;
  const double theta = std::min(std::numbers::pi / 2.0 - l.sun_elevation, std::numbers::pi / 2.0);
  sky.clear = make_preetham(turbidity, std::max(theta, 0.0));
  const double fade = std::pow(10.0, 0.4 * std::min(0.0, el_deg - 2.0));
  const double per_kcd = 1000.0 / kNitsPerUnit;
  sky.clear_scale = per_kcd * fade * scale;
  sky.twilight_tint = {0.55, 0.75, 1.45};
  // Night: city light scattered back by the air. Over a city centre a clear night sky is some
  // 100 times the natural sky (0.17 mcd/m^2) overhead, about 20 mcd/m^2 (17 mag/arcsec^2), and
  // ten times that in the light dome near the horizon; clouds reflect more.
  const double glow = (1.0 + 4.0 * clouds) / kNitsPerUnit;
  sky.glow_zenith = Color{0.5, 0.5, 0.6} * (0.038 * glow);
  sky.glow_horizon = Color{1.0, 0.72, 0.45} * (0.25 * glow);
  // What the clear sky alone gives, to size the overcast sky and the ground.
  const double clear_sky_up = luminance(project_sky(sky)({0.0, 0.0, 1.0}));
  const double clear_global = clear_sky_up + luminance(clear_sun) * sin_el;
  // Clouds: the CIE overcast sky takes the clear sky's place, bright as 40% of the clear day's
  // global light (25% under rain or snow clouds), plus the sunlight the fog scatters.
  const double cloud_brightness = rain || snow ? 0.25 : 0.4;
  const double scattered_sun = luminance(clear_sun) * sin_el * cloud_pass * (1.0 - through_fog);
  const double overcast_e = clouds * cloud_brightness * clear_global + 0.8 * scattered_sun;
  sky.clear_scale *= 1.0 - clouds;
  sky.overcast_zenith = overcast_e * 9.0 / 7.0;
  sky.overcast_tint = {0.96, 1.0, 1.06};
  const Color sky_up = project_sky(sky)({0.0, 0.0, 1.0});
  sky.ground = (sky_up + l.sun * sin_el) * 0.15;  // ground albedo 0.15
  l.sky_light = project_sky(sky);
  l.ambient = l.sky_light({0.0, 0.0, 1.0});
  // Fog and haze glow with the light around: thin haze takes the colour of the horizon sky,
  // a deep fog the average light of sky and ground.
  Color horizon;
  for (int k = 0; k < 8; ++k) {
    const double a = k * std::numbers::pi / 4.0;
    horizon = horizon + sky.radiance({std::cos(a) * 0.9986, std::sin(a) * 0.9986, 0.0523}) * 0.125;
  }
  const Color deep = (l.ambient + l.sky_light({0.0, 0.0, -1.0})) * 0.5 + l.sun * 0.15;
  l.fog_color = mix(horizon, deep, smoothstep(0.0005, 0.01, l.extinction()));

  const double global = luminance(l.ambient) + luminance(l.sun) * sin_el;
  // Street lamps switch on below ~50 lux (photocells), fully by ~5 lux.
  l.darkness = 1.0 - smoothstep(5e-5, 5e-4, global);
  l.wet_road = env.wet_road || rain;
  l.headlights = el_deg < 2.0 || ((rain || snow) && el_deg < 10.0) || l.fog_extinction > 0.02;
  l.wind_direction = env.wind_direction;
  l.wind_speed = env.wind_speed;
  // Every sky pixel, glossy reflection and sky ray reads the sky: from a table from now on.
  l.sky_model.tabulate();
  return l;
}

}  // namespace corsa::sensors
