// EnvironmentAction (OpenSCENARIO 1.3 §7.5.1): time of day, weather and road condition. The
// engine only keeps the state (EnvironmentState of the world snapshot); the sensors render it.

#include "actions/action_makers.h"
#include "positions/position_common.h"
#include "state/date_time.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

double cloud_cover(const xosc::Weather& weather) {
  if (weather.fractional_cloud_cover) {
    // zeroOktas .. eightOktas cover 0..1; nineOktas means "sky not visible", taken as overcast.
    const int oktas = static_cast<int>(*weather.fractional_cloud_cover);
    return oktas >= 8 ? 1.0 : oktas / 8.0;
  }
  if (weather.cloud_state) {
    switch (*weather.cloud_state) {
      case xosc::CloudState::kFree:
        return 0.0;
      case xosc::CloudState::kCloudy:
        return 0.5;
      case xosc::CloudState::kOvercast:
      case xosc::CloudState::kRainy:
        return 1.0;
      case xosc::CloudState::kSkyOff:
        return 0.0;
    }
  }
  return 0.0;
}

void apply_weather(EnvironmentState& env, const xosc::Weather& weather) {
  env.cloud_cover = cloud_cover(weather);
  if (weather.sun) {
    env.sun_azimuth = weather.sun->azimuth;
    env.sun_elevation = weather.sun->elevation;
    if (weather.sun->illuminance) {
      env.sun_intensity = *weather.sun->illuminance;
    }
  }
  if (weather.fog) {
    env.fog_visual_range = weather.fog->visual_range;
  }
  if (weather.precipitation) {
    switch (weather.precipitation->type) {
      case xosc::PrecipitationType::kDry:
        env.precipitation = PrecipitationType::kDry;
        break;
      case xosc::PrecipitationType::kRain:
        env.precipitation = PrecipitationType::kRain;
        break;
      case xosc::PrecipitationType::kSnow:
        env.precipitation = PrecipitationType::kSnow;
        break;
    }
    env.precipitation_intensity = weather.precipitation->intensity.value_or(0.0);
  }
  if (weather.wind) {
    env.wind_speed = weather.wind->speed;
    env.wind_direction = weather.wind->direction;
  }
}

class EnvironmentInstance final : public InstantAction {
 public:
  explicit EnvironmentInstance(const xosc::EnvironmentAction& action) : action_(action) {}
  void start(ActionContext& context) override {
    SimState& state = context.state;
    EnvironmentState& env = state.environment;
    const xosc::Environment& environment = action_.environment;
    if (environment.time_of_day) {
      const auto when = parse_date_time(environment.time_of_day->date_time);
      if (!when) {
        fail(environment.time_of_day->source, "TimeOfDay dateTime '" +
                                                  environment.time_of_day->date_time +
                                                  "' is not an xsd:dateTime (YYYY-MM-DDThh:mm:ss)");
      }
      env.year = when->year;
      env.month = when->month;
      env.day = when->day;
      env.time_of_day = when->seconds_of_day;
      env.utc_offset_hours = when->utc_offset_hours;
      state.environment_tick = state.tick;
      state.time_of_day_animated = environment.time_of_day->animation;
    }
    if (environment.weather) {
      apply_weather(env, *environment.weather);
    }
    if (environment.road_condition) {
      env.road_friction_scale = environment.road_condition->friction_scale_factor;
      env.wet_road = environment.road_condition->wetness &&
                     *environment.road_condition->wetness != xosc::Wetness::kDry;
    }
  }

 private:
  const xosc::EnvironmentAction& action_;
};

}  // namespace

std::unique_ptr<ActionInstance> make_environment_action(const xosc::EnvironmentAction& action) {
  return std::make_unique<EnvironmentInstance>(action);
}

}  // namespace corsa::engine::detail
