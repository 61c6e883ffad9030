// --time-of-day and --weather overrides of the scenario's environment.

#include "corsa/engine/environment_override.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <stdexcept>

using corsa::engine::EnvironmentOverride;
using corsa::engine::EnvironmentState;

TEST_CASE("Times of day are read as HH:MM or HH:MM:SS", "[capture][environment]") {
  CHECK(corsa::engine::parse_time_of_day("18:30") == 18.0 * 3600 + 30 * 60);
  CHECK(corsa::engine::parse_time_of_day("06:05:30") == 6.0 * 3600 + 5 * 60 + 30);
  CHECK(corsa::engine::parse_time_of_day("24:00") == 86400.0);
  CHECK_THROWS_WITH(corsa::engine::parse_time_of_day("25:00"), Catch::Contains("HH:MM"));
  CHECK_THROWS_AS(corsa::engine::parse_time_of_day("18"), std::invalid_argument);
  CHECK_THROWS_AS(corsa::engine::parse_time_of_day("12:60"), std::invalid_argument);
}

TEST_CASE("A time of day may carry a zone; without one it is solar time",
          "[capture][environment]") {
  EnvironmentOverride solar;
  corsa::engine::parse_time_of_day("12:00", solar);
  CHECK(solar.time_of_day == 12.0 * 3600);
  CHECK_FALSE(solar.utc_offset_hours);
  EnvironmentOverride seoul;
  corsa::engine::parse_time_of_day("07:30+09:00", seoul);
  CHECK(seoul.time_of_day == 7.5 * 3600);
  CHECK(seoul.utc_offset_hours == 9.0);
  EnvironmentOverride west;
  corsa::engine::parse_time_of_day("18:00:30-05:30", west);
  CHECK(west.time_of_day == 18.0 * 3600 + 30);
  CHECK(west.utc_offset_hours == -5.5);
  EnvironmentOverride utc;
  corsa::engine::parse_time_of_day("06:00Z", utc);
  CHECK(utc.utc_offset_hours == 0.0);
  CHECK_THROWS_WITH(corsa::engine::parse_time_of_day("12:00+9", utc), Catch::Contains("+HH:MM"));
  CHECK_THROWS_WITH(corsa::engine::parse_time_of_day("12:00+15:00", utc), Catch::Contains("zone"));

  // The override's zone (or none) replaces the scenario's.
  EnvironmentState e;
  e.utc_offset_hours = 9.0;
  corsa::engine::apply_override(solar, e.time_of_day, e);
  CHECK_FALSE(e.utc_offset_hours);
  corsa::engine::apply_override(west, e.time_of_day, e);
  CHECK(e.utc_offset_hours == -5.5);
}

TEST_CASE("Weather keys override only what they name", "[capture][environment]") {
  EnvironmentOverride o;
  corsa::engine::parse_weather("fog=50,rain=0.6,clouds=0.75,wind=4,wind_dir=90", o);
  EnvironmentState e;
  e.road_friction_scale = 0.8;
  corsa::engine::apply_override(o, e.time_of_day, e);
  CHECK(e.fog_visual_range == 50.0);
  CHECK(e.precipitation == corsa::engine::PrecipitationType::kRain);
  CHECK(e.precipitation_intensity == 0.6);
  CHECK(e.wet_road);
  CHECK(e.cloud_cover == 0.75);
  CHECK(e.wind_speed == 4.0);
  CHECK(e.wind_direction == Approx(M_PI / 2));
  CHECK(e.road_friction_scale == 0.8);  // not named: the scenario's value stays

  EnvironmentOverride dry;
  corsa::engine::parse_weather("rain=0,fog=none,wet=1", dry);
  corsa::engine::apply_override(dry, e.time_of_day, e);
  CHECK(e.precipitation == corsa::engine::PrecipitationType::kDry);
  CHECK(std::isinf(e.fog_visual_range));
  CHECK(e.wet_road);
}

TEST_CASE("Bad weather items name the item", "[capture][environment]") {
  EnvironmentOverride o;
  CHECK_THROWS_WITH(corsa::engine::parse_weather("hail=3", o),
                    Catch::Contains("unknown key 'hail'"));
  CHECK_THROWS_WITH(corsa::engine::parse_weather("fgo=30", o),
                    Catch::Contains("unknown key 'fgo' (did you mean 'fog'?)"));
  CHECK_THROWS_WITH(corsa::engine::parse_weather("fog=-5", o), Catch::Contains("fog=-5"));
  CHECK_THROWS_WITH(corsa::engine::parse_weather("rain", o), Catch::Contains("KEY=VALUE"));
  CHECK_THROWS_WITH(corsa::engine::parse_weather("clouds=2", o), Catch::Contains("0 to 1"));
}

TEST_CASE("A time-of-day override keeps the scenario's clock running", "[capture][environment]") {
  EnvironmentOverride o;
  o.time_of_day = corsa::engine::parse_time_of_day("23:59:50");
  EnvironmentState e;
  e.sun_elevation = 0.3;
  e.sun_azimuth = 1.0;
  const double start = 12.0 * 3600;
  e.time_of_day = start + 20.0;  // 20 s into an animated scenario
  corsa::engine::apply_override(o, start, e);
  CHECK(e.time_of_day == Approx(10.0));  // wrapped past midnight
  CHECK(!e.sun_elevation);               // the sun follows the new time
  CHECK(!e.sun_azimuth);
}
