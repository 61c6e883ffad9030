#pragma once

// Environment (§7.x EnvironmentAction): time of day, weather, road condition.

#include <optional>
#include <string>
#include <vector>

#include "corsa/xosc/common.h"
#include "corsa/xosc/enums.h"
#include "corsa/xosc/parameters.h"
#include "corsa/xosc/trajectories.h"

namespace corsa::xosc {

struct TimeOfDay {
  bool animation = false;
  std::string date_time;  ///< xsd:dateTime text, e.g. "2024-03-21T12:00:00"
  Source source;
};

/// Sun: azimuth in rad (0 north, pi/2 east), elevation in rad (0 horizon, pi/2 zenith);
/// illuminance in lux (the 1.0 `intensity` is read into it with a deprecation warning).
struct Sun {
  double azimuth = 0.0;
  double elevation = 0.0;
  std::optional<double> illuminance;
  Source source;
};

/// Fog: visual range in metres, optionally limited to a bounding box.
struct Fog {
  double visual_range = 0.0;
  struct Box {
    double center_x = 0.0, center_y = 0.0, center_z = 0.0;
    double width = 0.0, length = 0.0, height = 0.0;
  };
  std::optional<Box> bounding_box;
  Source source;
};

/// Precipitation: type and intensity in mm/h (1.0 `intensity` in [0,1] is kept as is, with a
/// deprecation warning).
struct Precipitation {
  PrecipitationType type = PrecipitationType::kDry;
  std::optional<double> intensity;
  Source source;
};

/// Wind: the direction the wind blows to, as a heading in the world x/y plane (rad, 0 = +x);
/// speed in m/s.
struct Wind {
  double direction = 0.0;
  double speed = 0.0;
  Source source;
};

struct DomeImage {
  std::optional<double> azimuth_offset;
  File dome_file;
  Source source;
};

struct Weather {
  std::optional<CloudState> cloud_state;  ///< deprecated 1.0/1.1 attribute
  std::optional<FractionalCloudCover> fractional_cloud_cover;
  std::optional<double> atmospheric_pressure;  ///< Pa
  std::optional<double> temperature;           ///< K
  std::optional<Sun> sun;
  std::optional<Fog> fog;
  std::optional<Precipitation> precipitation;
  std::optional<Wind> wind;
  std::optional<DomeImage> dome_image;
  Source source;
};

struct RoadCondition {
  double friction_scale_factor = 1.0;
  std::optional<Wetness> wetness;
  Properties properties;
  Source source;
};

struct Environment {
  std::string name;
  std::vector<ParameterDeclaration> parameters;
  std::optional<TimeOfDay> time_of_day;
  std::optional<Weather> weather;
  std::optional<RoadCondition> road_condition;
  std::optional<CatalogOrigin> catalog;
  Source source;
};

}  // namespace corsa::xosc
