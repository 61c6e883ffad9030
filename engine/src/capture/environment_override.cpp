// Command-line environment overrides (see corsa/engine/environment_override.h).

#include "corsa/engine/environment_override.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "corsa/core/strings.h"

namespace corsa::engine {
namespace {

constexpr double kDay = 86400.0;  // s

double number(std::string_view key, std::string_view value, double lo, double hi) {
  const std::optional<double> parsed = parse_double(trim(value));
  if (!parsed || !std::isfinite(*parsed) || *parsed < lo || *parsed > hi) {
    throw std::invalid_argument("--weather " + std::string(key) + "=" + std::string(value) +
                                ": expected a number from " + format_double(lo) + " to " +
                                format_double(hi));
  }
  return *parsed;
}

}  // namespace

bool EnvironmentOverride::empty() const {
  return !time_of_day && !fog_visual_range && !precipitation && !precipitation_intensity &&
         !cloud_cover && !wind_speed && !wind_direction && !wet_road && !road_friction_scale;
}

double parse_time_of_day(std::string_view text) {
  const std::vector<std::string_view> parts = split(trim(text), ':');
  const std::string message =
      "--time-of-day '" + std::string(text) +
      "': expected HH:MM or HH:MM:SS between 00:00 and 24:00 (a zone may follow: Z, +09:00)";
  if (parts.size() < 2 || parts.size() > 3) {
    throw std::invalid_argument(message);
  }
  const std::optional<int64_t> hours = parse_int(parts[0]);
  const std::optional<int64_t> minutes = parse_int(parts[1]);
  const std::optional<double> seconds =
      parts.size() == 3 ? parse_double(parts[2]) : std::optional<double>(0.0);
  if (!hours || !minutes || !seconds || *hours < 0 || *hours > 24 || *minutes < 0 ||
      *minutes > 59 || !(*seconds >= 0.0) || !(*seconds < 60.0)) {
    throw std::invalid_argument(message);
  }
  const double total = static_cast<double>(*hours * 3600 + *minutes * 60) + *seconds;
  if (total > kDay) {
    throw std::invalid_argument(message);
  }
  return total;
}

void parse_time_of_day(std::string_view text, EnvironmentOverride& out) {
  const std::string_view value = trim(text);
  std::optional<double> offset;
  std::string_view clock = value;
  if (!value.empty() && (value.back() == 'Z' || value.back() == 'z')) {
    offset = 0.0;
    clock = value.substr(0, value.size() - 1);
  } else if (const size_t sign = value.find_first_of("+-"); sign != std::string_view::npos) {
    const std::string_view zone = value.substr(sign + 1);
    const std::vector<std::string_view> parts = split(zone, ':');
    const std::optional<int64_t> hours = parts.size() == 2 ? parse_int(parts[0]) : std::nullopt;
    const std::optional<int64_t> minutes = parts.size() == 2 ? parse_int(parts[1]) : std::nullopt;
    if (!hours || !minutes || parts[0].size() != 2 || parts[1].size() != 2 || *hours > 14 ||
        *minutes > 59) {
      throw std::invalid_argument("--time-of-day '" + std::string(text) +
                                  "': the zone must read +HH:MM or -HH:MM (local minus UTC, "
                                  "e.g. 12:00+09:00), or Z for UTC");
    }
    offset = (value[sign] == '-' ? -1.0 : 1.0) * (static_cast<double>(*hours) + *minutes / 60.0);
    clock = value.substr(0, sign);
  }
  out.time_of_day = parse_time_of_day(clock);
  out.utc_offset_hours = offset;
}

void parse_weather(std::string_view text, EnvironmentOverride& out) {
  for (const std::string_view raw : split(text, ',')) {
    const std::string_view item = trim(raw);
    const size_t eq = item.find('=');
    if (eq == std::string_view::npos || eq == 0) {
      throw std::invalid_argument("--weather: expected KEY=VALUE, got '" + std::string(item) +
                                  "' (keys: fog, rain, snow, clouds, wind, wind_dir, wet, "
                                  "friction)");
    }
    const std::string key = to_lower(trim(item.substr(0, eq)));
    const std::string_view value = trim(item.substr(eq + 1));
    if (key == "fog") {
      if (iequals(value, "none") || iequals(value, "inf")) {
        out.fog_visual_range = std::numeric_limits<double>::infinity();
      } else {
        out.fog_visual_range = number(key, value, 1.0, 1e7);
      }
    } else if (key == "rain" || key == "snow") {
      const double intensity = number(key, value, 0.0, 500.0);
      out.precipitation = intensity == 0.0 ? PrecipitationType::kDry
                          : key == "rain"  ? PrecipitationType::kRain
                                           : PrecipitationType::kSnow;
      out.precipitation_intensity = intensity;
    } else if (key == "clouds") {
      out.cloud_cover = number(key, value, 0.0, 1.0);
    } else if (key == "wind") {
      out.wind_speed = number(key, value, 0.0, 100.0);
    } else if (key == "wind_dir") {
      out.wind_direction = number(key, value, -360.0, 360.0) * std::numbers::pi / 180.0;
    } else if (key == "wet") {
      out.wet_road = number(key, value, 0.0, 1.0) != 0.0;
    } else if (key == "friction") {
      out.road_friction_scale = number(key, value, 1e-3, 10.0);
    } else {
      const std::vector<std::string> keys{"fog",  "rain",     "snow", "clouds",
                                          "wind", "wind_dir", "wet",  "friction"};
      throw std::invalid_argument("--weather: unknown key '" + key + "'" + did_you_mean(key, keys) +
                                  " (keys: fog, rain, snow, clouds, wind, wind_dir, wet, "
                                  "friction)");
    }
  }
}

void apply_override(const EnvironmentOverride& o, double scenario_start_time_of_day,
                    EnvironmentState& e) {
  if (o.time_of_day) {
    double shifted = e.time_of_day - scenario_start_time_of_day + *o.time_of_day;
    shifted = std::fmod(shifted, kDay);
    e.time_of_day = shifted < 0.0 ? shifted + kDay : shifted;
    e.utc_offset_hours = o.utc_offset_hours;
    // A scenario-given sun belongs to the scenario's time; the renderer computes it instead.
    e.sun_azimuth.reset();
    e.sun_elevation.reset();
  }
  if (o.fog_visual_range) {
    e.fog_visual_range = *o.fog_visual_range;
  }
  if (o.precipitation) {
    e.precipitation = *o.precipitation;
    e.precipitation_intensity = o.precipitation_intensity.value_or(0.0);
    // Rain wets the road unless wet=0 says otherwise.
    e.wet_road = *o.precipitation == PrecipitationType::kRain && e.precipitation_intensity > 0.0;
  }
  if (o.cloud_cover) {
    e.cloud_cover = *o.cloud_cover;
  }
  if (o.wind_speed) {
    e.wind_speed = *o.wind_speed;
  }
  if (o.wind_direction) {
    e.wind_direction = *o.wind_direction;
  }
  if (o.wet_road) {
    e.wet_road = *o.wet_road;
  }
  if (o.road_friction_scale) {
    e.road_friction_scale = *o.road_friction_scale;
  }
}

}  // namespace corsa::engine
