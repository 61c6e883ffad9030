#include "corsa/sensors/solar.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <optional>
#include <utility>

#include "corsa/sensors/environment.h"

using namespace corsa::sensors;

namespace {
constexpr double kDeg = M_PI / 180.0;
constexpr double kSeoulLat = 37.5665, kSeoulLon = 126.978;
}  // namespace

TEST_CASE("the noon sun stands at 90 - latitude + declination", "[sensors][solar]") {
  // June solstice 2024 (declination +23.44), Seoul (UTC+9): scan the day for the highest sun.
  double best = -1.0, best_time = 0.0, best_azimuth = 0.0;
  for (double t = 10.0 * 3600.0; t < 15.0 * 3600.0; t += 30.0) {
    const SolarPosition p = solar_position(2024, 6, 21, t, 9.0, kSeoulLat, kSeoulLon);
    if (p.elevation > best) {
      best = p.elevation;
      best_time = t;
      best_azimuth = p.azimuth;
    }
  }
  CHECK(best / kDeg == Approx(90.0 - kSeoulLat + 23.44).margin(0.05));
  CHECK(best_azimuth / kDeg == Approx(180.0).margin(1.5));  // due south
  // Solar noon: 12:00 + (135 - 126.978) * 4 min - equation of time (-1.8 min) = 12:33.9.
  CHECK(best_time / 60.0 == Approx(12.0 * 60.0 + 33.9).margin(1.0));
}

TEST_CASE("at an equinox the sun rises due east and sets due west", "[sensors][solar]") {
  // 2024-03-20 at the equator on the Greenwich meridian: rise ~06:07 UTC, set ~18:07 UTC.
  const SolarPosition morning = solar_position(2024, 3, 20, 6.0 * 3600.0 + 420.0, 0.0, 0.0, 0.0);
  CHECK(morning.elevation / kDeg == Approx(0.0).margin(0.3));
  CHECK(morning.azimuth / kDeg == Approx(90.0).margin(0.3));
  const SolarPosition evening = solar_position(2024, 3, 20, 18.0 * 3600.0 + 420.0, 0.0, 0.0, 0.0);
  CHECK(evening.azimuth / kDeg == Approx(270.0).margin(0.3));
  const SolarPosition midnight = solar_position(2024, 3, 20, 0.0, 0.0, 0.0, 0.0);
  // Solar midnight comes 7.5 min (the equation of time) after 00:00 UTC: 1.9 degrees short of
  // the nadir.
  CHECK(midnight.elevation / kDeg == Approx(-90.0 + 7.5 / 4.0).margin(0.2));
}

TEST_CASE("lighting follows the sun, the clouds, the fog and the rain", "[sensors][solar]") {
  corsa::engine::EnvironmentState env;
  env.time_of_day = 12.5 * 3600.0;
  env.utc_offset_hours = 9.0;
  const Lighting noon = compute_lighting(env, {kSeoulLat, kSeoulLon});
  CHECK(noon.sun_direction.y < 0.0);  // the sun is south (y north)
  CHECK(noon.sun_direction.z > 0.9);
  CHECK_FALSE(noon.headlights);
  CHECK(noon.fog_extinction == 0.0);
  env.time_of_day = 23.0 * 3600.0;
  const Lighting night = compute_lighting(env, {kSeoulLat, kSeoulLon});
  CHECK(night.headlights);
  CHECK(night.sun.r == 0.0);
  CHECK(night.ambient.g < 0.02 * noon.ambient.g);
  env.time_of_day = 12.5 * 3600.0;
  env.precipitation = corsa::engine::PrecipitationType::kRain;
  env.precipitation_intensity = 10.0;
  const Lighting rain = compute_lighting(env, {kSeoulLat, kSeoulLon});
  CHECK(rain.wet_road);
  CHECK(rain.sun.r < 0.3 * noon.sun.r);
  // Marshall-Palmer drops, twice their cross-section each: pi N0 / Lambda^3 = 3.65e-4 R^0.63.
  CHECK(rain.rain_extinction == Approx(3.65e-4 * std::pow(10.0, 0.63)).epsilon(0.01));
  CHECK(fog_extinction(100.0) == Approx(0.03912).epsilon(1e-3));
  env.sun_azimuth = M_PI / 2.0;  // OpenSCENARIO Sun given: east, 30 degrees up
  env.sun_elevation = M_PI / 6.0;
  const Lighting given = compute_lighting(env, {});
  CHECK(given.sun_direction.x == Approx(std::cos(M_PI / 6.0)));
  CHECK(given.sun_direction.y == Approx(0.0).margin(1e-12));
  CHECK(given.sun_direction.z == Approx(0.5));
}

TEST_CASE("a time without a zone is local solar time: 12:00 is the sun's transit anywhere",
          "[sensors][solar]") {
  // Town03 (CARLA) sits at 49 N 8 E, K-City at 37.24 N 126.77 E, Seoul's default at 126.98 E;
  // read as UTC, 12:00 was 21:27 at K-City, night. As solar time it is the highest sun.
  for (const auto& [lat, lon] : {std::pair{49.0, 8.0}, std::pair{37.24, 126.77},
                                 std::pair{kSeoulLat, kSeoulLon}, std::pair{-33.9, -70.6}}) {
    INFO(lat << ", " << lon);
    const SolarPosition noon = solar_position(2024, 6, 21, 12.0 * 3600.0, std::nullopt, lat, lon);
    const SolarPosition before = solar_position(2024, 6, 21, 11.5 * 3600.0, std::nullopt, lat, lon);
    const SolarPosition after = solar_position(2024, 6, 21, 12.5 * 3600.0, std::nullopt, lat, lon);
    CHECK(noon.elevation / kDeg == Approx(90.0 - std::fabs(lat - 23.44)).margin(0.05));
    CHECK(noon.elevation > before.elevation);
    CHECK(noon.elevation > after.elevation);
    CHECK(before.elevation == Approx(after.elevation).margin(0.002));  // symmetric about noon
  }
  // The same instant given with its zone: solar noon at Seoul is 12:33.9 KST.
  const SolarPosition zoned =
      solar_position(2024, 6, 21, 12.0 * 3600.0 + 33.9 * 60.0, 9.0, kSeoulLat, kSeoulLon);
  const SolarPosition solar =
      solar_position(2024, 6, 21, 12.0 * 3600.0, std::nullopt, kSeoulLat, kSeoulLon);
  CHECK(zoned.elevation == Approx(solar.elevation).margin(0.0005));
}

TEST_CASE("the default environment (no EnvironmentAction) lights the scene as a day",
          "[sensors][solar]") {
  const corsa::engine::EnvironmentState unset;  // 12:00, no zone
  REQUIRE_FALSE(unset.utc_offset_hours);
  for (const GeoLocation where : {GeoLocation{49.0, 8.0}, GeoLocation{37.24, 126.77}}) {
    const Lighting l = compute_lighting(unset, where);
    CHECK(l.sun_elevation / kDeg > 60.0);
    CHECK_FALSE(l.headlights);
    CHECK(l.sun.g > 0.5);
  }
  // An explicit UTC zone is honoured: 12:00Z is late evening in Korea.
  corsa::engine::EnvironmentState utc;
  utc.utc_offset_hours = 0.0;
  CHECK(compute_lighting(utc, GeoLocation{37.24, 126.77}).headlights);
}

TEST_CASE(
    "the evening sun at K-City on 21 June is within a degree of NOAA's, with and without a zone",
    "[sensors][solar]") {
  // NOAA solar calculator equations worked by hand for 37.24 N, 126.77 E on 2026-06-21:
  // declination 23.44, equation of time -1.8 min. 18:30+09:00 is 17:55.3 apparent solar time,
  // hour angle 88.8: sin(el) = sin 37.24 sin 23.44 + cos 37.24 cos 23.44 cos 88.8, el = 14.8.
  // 18:30 without a zone is 18:30 apparent solar time, hour angle 97.5: el = 8.4.
  const double lat = 37.24, lon = 126.77, t = 18.5 * 3600.0;
  const SolarPosition kst = solar_position(2026, 6, 21, t, 9.0, lat, lon);
  const SolarPosition solar = solar_position(2026, 6, 21, t, std::nullopt, lat, lon);
  CHECK(kst.elevation / kDeg == Approx(14.8).margin(1.0));
  CHECK(solar.elevation / kDeg == Approx(8.4).margin(1.0));
  // Azimuths from the same triangle: 288.4 and 293.2 (west-north-west, north of west at the
  // solstice).
  CHECK(kst.azimuth / kDeg == Approx(288.4).margin(1.0));
  CHECK(solar.azimuth / kDeg == Approx(293.2).margin(1.0));
}
