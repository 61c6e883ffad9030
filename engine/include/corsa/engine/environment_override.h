#pragma once

// Command-line overrides of the scenario's environment for data collection (`corsa run --rig`):
//   --time-of-day HH:MM[:SS][ZONE] local time of day, ZONE = Z or +HH:MM / -HH:MM (local minus
//                                  UTC); without a zone, local solar time at the map's place
//                                  (12:00 = the sun at its highest). The scenario's animation
//                                  (if any) keeps running from there
//   --weather KEY=VALUE[,...]      keys (docs/datasets.md):
//     fog=M            fog visual range, metres (> 0; "none" or "inf" for no fog)
//     rain=MM_PER_H    rain intensity, mm/h (0 = dry), as OpenSCENARIO precipitationIntensity
//     snow=MM_PER_H    snowfall intensity, mm/h water equivalent
//     clouds=C         cloud cover 0..1 (OpenSCENARIO fractionalCloudCover oktas / 8)
//     wind=M_PER_S     wind speed
//     wind_dir=DEG     wind direction, degrees (OpenSCENARIO Wind/direction, radians, as degrees)
//     wet=0|1          wet road surface
//     friction=SCALE   road friction scale factor (> 0)
// Values not named keep what the scenario (EnvironmentAction, EnvironmentCatalog) says.

#include <optional>
#include <string>
#include <string_view>

#include "corsa/engine/world_snapshot.h"

namespace corsa::engine {

struct EnvironmentOverride {
  std::optional<double> time_of_day;  ///< seconds since local midnight
  /// The zone given with time_of_day (local minus UTC, hours); nothing: local solar time.
  std::optional<double> utc_offset_hours;
  std::optional<double> fog_visual_range;
  std::optional<PrecipitationType> precipitation;
  std::optional<double> precipitation_intensity;
  std::optional<double> cloud_cover;
  std::optional<double> wind_speed;
  std::optional<double> wind_direction;  ///< radians
  std::optional<bool> wet_road;
  std::optional<double> road_friction_scale;

  bool empty() const;
};

/// Parses "HH:MM" or "HH:MM:SS" (00:00 .. 24:00) into seconds. Throws std::invalid_argument with
/// a message for the user.
double parse_time_of_day(std::string_view text);
/// Parses the --time-of-day value "HH:MM[:SS]" with an optional zone suffix ("Z", "+09:00",
/// "-05:30", as in xsd:dateTime) into out.time_of_day and out.utc_offset_hours. Throws
/// std::invalid_argument with a message for the user.
void parse_time_of_day(std::string_view text, EnvironmentOverride& out);
/// Parses the --weather list into `out`. Throws std::invalid_argument naming the bad item.
void parse_weather(std::string_view text, EnvironmentOverride& out);

/// Applies the override. `scenario_start_time_of_day` is the scenario's time of day at tick 0:
/// a time-of-day override shifts the scenario's clock so that it starts at the given time and
/// keeps its animation (wrapping at midnight), and its zone (or none) replaces the scenario's.
void apply_override(const EnvironmentOverride& override_values, double scenario_start_time_of_day,
                    EnvironmentState& environment);

}  // namespace corsa::engine
