#include "corsa/sensors/environment.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "corsa/sensors/solar.h"

namespace corsa::sensors {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

/// Relative air mass (Kasten and Young 1989), elevation in degrees.
double air_mass(double elevation_deg) {
  const double el = std::max(elevation_deg, -0.5);
  return 1.0 / (std::sin(el * kDeg) + 0.50572 * std::pow(el + 6.07995, -1.6364));
}

}  // namespace

double fog_extinction(double visual_range_m) {
  if (!(visual_range_m > 0.0) || std::isinf(visual_range_m)) {
    return visual_range_m > 0.0 ? 0.0 : 1e3;
  }
  return std::log(50.0) / visual_range_m;
}

double rain_extinction(double intensity_mm_per_h) {
  return intensity_mm_per_h > 0.0 ? 2e-4 * std::pow(intensity_mm_per_h, 0.6) : 0.0;
}

Color Lighting::sky(Vec3 d) const {
  const double up = std::clamp(d.z, 0.0, 1.0);
  Color c = mix(sky_horizon, sky_zenith, std::sqrt(up));
  // Glow around the sun.
  const double cos_sun = dot(d, sun_direction);
  if (cos_sun > 0.9 && sun_elevation > -0.05) {
    c = c + sun * (0.6 * std::pow((cos_sun - 0.9) / 0.1, 8.0));
  }
  if (d.z < 0.0) {
    c = c * 0.6;  // below the horizon: the ground beyond the scene
  }
  return c;
}

Lighting compute_lighting(const engine::EnvironmentState& env, const GeoLocation& where) {
  Lighting l;
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
  const double el_deg = elevation / kDeg;
  const bool rain =
      env.precipitation == engine::PrecipitationType::kRain && env.precipitation_intensity > 0.0;
  const bool snow =
      env.precipitation == engine::PrecipitationType::kSnow && env.precipitation_intensity > 0.0;
  const double clouds = std::clamp(std::max(env.cloud_cover, rain || snow ? 0.85 : 0.0), 0.0, 1.0);

  // Direct sun: reddened and dimmed through the air mass, blocked by clouds.
  const double above = smoothstep(-1.0, 2.0, el_deg);
  const double am = air_mass(el_deg);
  const double scale = std::max(0.0, env.sun_intensity) / 100000.0;
  const double direct = above * (1.0 - 0.85 * clouds) * scale;
  l.sun = Color{std::exp(-0.06 * (am - 1.0)), std::exp(-0.11 * (am - 1.0)),
                std::exp(-0.22 * (am - 1.0))} *
          direct;

  // Sky: day brightness fades through civil twilight (sun 6 degrees below the horizon).
  const double day = smoothstep(-6.0, 8.0, el_deg) * std::max(scale, 0.05);
  const Color night_sky{0.002, 0.003, 0.006};
  const double twilight = smoothstep(-6.0, 0.0, el_deg) * (1.0 - smoothstep(0.0, 10.0, el_deg));
  Color zenith = Color{0.18, 0.32, 0.65} * day;
  Color horizon = mix(Color{0.55, 0.62, 0.72}, Color{0.75, 0.45, 0.3}, twilight) * day;
  const Color overcast = Color{0.42, 0.44, 0.47} * day;
  zenith = mix(zenith, overcast, clouds) + night_sky;
  horizon = mix(horizon, overcast * 1.1, clouds) + night_sky;
  l.sky_zenith = zenith;
  l.sky_horizon = horizon;
  l.ambient = mix(horizon, zenith, 0.6) * 0.9;

  l.fog_extinction = fog_extinction(env.fog_visual_range);
  l.rain_intensity = rain ? env.precipitation_intensity : 0.0;
  l.rain_extinction = rain_extinction(l.rain_intensity);
  l.fog_color = mix(horizon, Color{0.6, 0.62, 0.65} * day + night_sky, 0.5);
  l.wet_road = env.wet_road || rain;
  l.headlights = el_deg < 2.0 || (rain && el_deg < 10.0) || l.fog_extinction > 0.02;
  l.wind_direction = env.wind_direction;
  l.wind_speed = env.wind_speed;
  return l;
}

}  // namespace corsa::sensors
