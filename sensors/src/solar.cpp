#include "corsa/sensors/solar.h"

#include <cmath>
#include <numbers>

#include "scalar_math.h"

namespace corsa::sensors {

using detail::kDeg;
namespace {

double wrap360(double degrees) {
  const double r = std::fmod(degrees, 360.0);
  return r < 0.0 ? r + 360.0 : r;
}

/// Julian day number at 0h UT of a Gregorian date (Fliegel and Van Flandern), as a day count
/// that starts at noon, so midnight is JDN - 0.5.
double julian_day_at_midnight(int year, int month, int day) {
  const int a = (14 - month) / 12;
  const int y = year + 4800 - a;
  const int m = month + 12 * a - 3;
  const long jdn = day + (153 * m + 2) / 5 + 365L * y + y / 4 - y / 100 + y / 400 - 32045;
  return static_cast<double>(jdn) - 0.5;
}

}  // namespace

SolarPosition solar_position(int year, int month, int day, double local_seconds,
                             std::optional<double> utc_offset_hours, double latitude_deg,
                             double longitude_deg) {
  const double local_minutes = local_seconds / 60.0;
  // Solar time: the instant is about the local mean time of the longitude (the equation of
  // time, at most 17 min, moves the declination by less than 0.005 degrees).
  const double offset = utc_offset_hours.value_or(longitude_deg / 15.0);
  const double ut_hours = local_seconds / 3600.0 - offset;
  const double jd = julian_day_at_midnight(year, month, day) + ut_hours / 24.0;
  const double t = (jd - 2451545.0) / 36525.0;  // Julian centuries since J2000.0

  const double l0 = wrap360(280.46646 + t * (36000.76983 + t * 0.0003032));
  const double m = 357.52911 + t * (35999.05029 - 0.0001537 * t);
  const double e = 0.016708634 - t * (0.000042037 + 0.0000001267 * t);
  const double c = std::sin(m * kDeg) * (1.914602 - t * (0.004817 + 0.000014 * t)) +
                   std::sin(2.0 * m * kDeg) * (0.019993 - 0.000101 * t) +
                   std::sin(3.0 * m * kDeg) * 0.000289;
  const double true_long = l0 + c;
  const double omega = 125.04 - 1934.136 * t;
  const double app_long = true_long - 0.00569 - 0.00478 * std::sin(omega * kDeg);
  const double mean_obliq =
      23.0 + (26.0 + (21.448 - t * (46.815 + t * (0.00059 - t * 0.001813))) / 60.0) / 60.0;
  const double obliq = mean_obliq + 0.00256 * std::cos(omega * kDeg);
  const double decl = std::asin(std::sin(obliq * kDeg) * std::sin(app_long * kDeg));

  const double y = std::pow(std::tan(obliq * kDeg / 2.0), 2.0);
  const double eq_time_min =
      4.0 / kDeg *
      (y * std::sin(2.0 * l0 * kDeg) - 2.0 * e * std::sin(m * kDeg) +
       4.0 * e * y * std::sin(m * kDeg) * std::cos(2.0 * l0 * kDeg) -
       0.5 * y * y * std::sin(4.0 * l0 * kDeg) - 1.25 * e * e * std::sin(2.0 * m * kDeg));

  const double true_solar_min =
      utc_offset_hours
          ? std::fmod(local_minutes + eq_time_min + 4.0 * longitude_deg - 60.0 * offset, 1440.0)
          : std::fmod(local_minutes, 1440.0);
  double hour_angle = true_solar_min / 4.0 - 180.0;
  if (hour_angle < -180.0) {
    hour_angle += 360.0;
  }
  const double lat = latitude_deg * kDeg;
  double cos_zenith =
      std::sin(lat) * std::sin(decl) + std::cos(lat) * std::cos(decl) * std::cos(hour_angle * kDeg);
  cos_zenith = std::fmax(-1.0, std::fmin(1.0, cos_zenith));
  const double zenith = std::acos(cos_zenith);

  double azimuth_deg = 0.0;
  const double denom = std::cos(lat) * std::sin(zenith);
  if (std::fabs(denom) > 1e-12) {
    double cos_az = (std::sin(lat) * std::cos(zenith) - std::sin(decl)) / denom;
    cos_az = std::fmax(-1.0, std::fmin(1.0, cos_az));
    const double a = std::acos(cos_az) / kDeg;
    azimuth_deg = hour_angle > 0.0 ? wrap360(a + 180.0) : wrap360(540.0 - a);
  } else {
    azimuth_deg = lat > 0.0 ? 180.0 : 0.0;  // sun at the zenith or a pole: any azimuth
  }
  return {azimuth_deg * kDeg, std::numbers::pi / 2.0 - zenith};
}

}  // namespace corsa::sensors
