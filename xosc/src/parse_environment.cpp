// Environment: time of day, weather, road condition.

#include "parsers.h"

namespace corsa::xosc {
namespace {

Weather parse_weather(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "Weather");
  Weather weather;
  weather.cloud_state = ctx.opt_enum<CloudState>(e, "cloudState");
  deprecated_attribute(ctx, e, "cloudState", {"fractionalCloudCover"});
  weather.fractional_cloud_cover = ctx.opt_enum<FractionalCloudCover>(e, "fractionalCloudCover");
  weather.atmospheric_pressure = ctx.opt_double(e, "atmosphericPressure");
  weather.temperature = ctx.opt_double(e, "temperature");
  if (const Element* sun = kids.opt("Sun")) {
    Children(ctx, sun, "Sun");
    Sun value{ctx.req_double(sun, "azimuth"), ctx.req_double(sun, "elevation"),
              ctx.opt_double(sun, "illuminance"), ctx.source(sun)};
    if (deprecated_attribute(ctx, sun, "intensity", {"illuminance"})) {
      value.illuminance = value.illuminance.value_or(*ctx.opt_double(sun, "intensity"));
    }
    weather.sun = value;
  }
  if (const Element* fog = kids.opt("Fog")) {
    Children fog_kids(ctx, fog, "Fog");
    Fog value;
    value.visual_range = ctx.req_double(fog, "visualRange");
    if (const Element* box = fog_kids.opt("BoundingBox")) {
      const BoundingBox b = parse_bounding_box(ctx, box);
      value.bounding_box =
          Fog::Box{b.center_x, b.center_y, b.center_z, b.width, b.length, b.height};
    }
    value.source = ctx.source(fog);
    weather.fog = value;
  }
  if (const Element* p = kids.opt("Precipitation")) {
    Children(ctx, p, "Precipitation");
    Precipitation value{ctx.req_enum<PrecipitationType>(p, "precipitationType"),
                        ctx.opt_double(p, "precipitationIntensity"), ctx.source(p)};
    if (deprecated_attribute(ctx, p, "intensity", {"precipitationIntensity"})) {
      value.intensity = value.intensity.value_or(*ctx.opt_double(p, "intensity"));
    }
    weather.precipitation = value;
  }
  if (const Element* wind = kids.opt("Wind")) {
    Children(ctx, wind, "Wind");
    weather.wind =
        Wind{ctx.req_double(wind, "direction"), ctx.req_double(wind, "speed"), ctx.source(wind)};
  }
  if (const Element* dome = kids.opt("DomeImage")) {
    Children dome_kids(ctx, dome, "DomeImage");
    weather.dome_image = DomeImage{ctx.opt_double(dome, "azimuthOffset"),
                                   parse_file(ctx, dome_kids.one("DomeFile")), ctx.source(dome)};
  }
  weather.source = ctx.source(e);
  return weather;
}

}  // namespace

Environment parse_environment(ParseContext& ctx, const Element* e, const EntryScope& scope) {
  Children kids(ctx, e, "Environment");
  Environment environment;
  environment.parameters = open_scope(ctx, kids, scope);
  ScopeGuard guard(ctx);
  environment.name = ctx.req_str(e, "name");
  if (const Element* time = kids.opt("TimeOfDay")) {
    Children(ctx, time, "TimeOfDay");
    TimeOfDay value{ctx.req_bool(time, "animation"), ctx.req_str(time, "dateTime"),
                    ctx.source(time)};
    if (!parse_value(ParameterType::kDateTime, value.date_time)) {
      ctx.fail(time, "attribute dateTime: '" + value.date_time + "' is not a valid dateTime");
    }
    environment.time_of_day = value;
  }
  if (const Element* weather = kids.opt("Weather")) {
    environment.weather = parse_weather(ctx, weather);
  }
  if (const Element* road = kids.opt("RoadCondition")) {
    Children road_kids(ctx, road, "RoadCondition");
    RoadCondition value;
    value.friction_scale_factor = ctx.req_double(road, "frictionScaleFactor");
    if (value.friction_scale_factor < 0.0) {
      ctx.fail(road, "frictionScaleFactor must not be negative");
    }
    value.wetness = ctx.opt_enum<Wetness>(road, "wetness");
    if (const Element* properties = road_kids.opt("Properties")) {
      value.properties = parse_properties(ctx, properties);
    }
    value.source = ctx.source(road);
    environment.road_condition = value;
  }
  environment.source = ctx.source(e);
  return environment;
}

}  // namespace corsa::xosc
