#include "traffic/spawn_speed.h"

#include <charconv>
#include <cmath>
#include <string>
#include <string_view>

#include "controllers/controllers.h"
#include "corsa/core/random.h"
#include "corsa/xodr/map.h"
#include "corsa/xosc/scenario.h"
#include "positions/position_resolver.h"
#include "state/sim_state.h"
#include "traffic/spawner.h"

namespace corsa::engine::detail {
namespace {

constexpr double kSpawnDefaultSpeed = 13.9;  // m/s (50 km/h): nothing gives a speed
constexpr double kSpawnWalkingSpeed = 1.3;   // m/s

std::optional<double> spawn_speed_number(std::string_view text) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value) ||
      value < 0.0) {
    return std::nullopt;
  }
  return value;
}

// `corsa:speed`: "V" or "LO..HI" (m/s); one draw of the range per object.
double entry_spawn_speed(const xosc::Property& property, RandomStream& random) {
  const std::string_view text = property.value;
  const size_t dots = text.find("..");
  const auto lo = spawn_speed_number(text.substr(0, dots));
  const auto hi = dots == std::string_view::npos ? lo : spawn_speed_number(text.substr(dots + 2));
  if (!lo || !hi || *hi < *lo) {
    throw InputError(property.source.error("corsa:speed '" + property.value +
                                           "' is not a speed in m/s (\"V\" or \"LO..HI\", "
                                           "0 <= LO <= HI)"));
  }
  return *hi > *lo ? random.uniform(*lo, *hi) : *lo;
}

const xosc::Property* spawn_property(const xosc::Properties& properties, std::string_view name) {
  for (const xosc::Property& property : properties.properties) {
    if (property.name == name) {
      return &property;
    }
  }
  return nullptr;
}

}  // namespace

std::optional<double> speed_limit(const SimState& state, uint32_t road_index, double s, int lane) {
  if (state.map == nullptr) {
    return std::nullopt;
  }
  const xodr::Map& map = *state.map;
  const xodr::Road& road = map.road(road_index);
  const xodr::LaneSection& section = road.lane_sections[map.section_index(road_index, s)];
  for (const xodr::Lane& candidate : section.lanes) {
    if (candidate.id != lane) {
      continue;
    }
    std::optional<double> limit;
    for (const xodr::LaneSpeed& speed : candidate.speeds) {
      if (section.s + speed.s_offset <= s + 1e-9 && speed.max_speed > 0.0) {
        limit = speed.max_speed;
      }
    }
    if (limit) {
      return limit;
    }
  }
  std::optional<double> typed;
  for (const xodr::RoadType& type : road.types) {
    if (type.s > s + 1e-9) break;
    typed = type.max_speed;
  }
  if (typed && *typed > 0.0) {
    return typed;
  }
  return std::nullopt;
}

double spawn_speed(const SimState& state, RandomStream& random, const TrafficMix& mix, size_t kind,
                   const ResolvedPosition& at, std::optional<double> given) {
  if (const xosc::Properties* entry = mix.entry_properties(kind)) {
    if (const xosc::Property* property = spawn_property(*entry, "corsa:speed")) {
      return entry_spawn_speed(*property, random);
    }
  }
  if (given) {
    return *given;
  }
  for (const xosc::ObjectController& oc : mix.prototype(kind).controllers) {
    // Any controller's setSpeed, not only esmini's ACCController's in mode "override" (whose
    // set speed it is, control_state.h): a cruise speed the scenario gives its traffic.
    if (const auto value = nonnegative_property(state, oc.controller, "setSpeed", "controller")) {
      return *value;
    }
  }
  if (mix.walks(kind)) {
    return kSpawnWalkingSpeed;
  }
  if (at.road && at.road->lane) {
    if (const auto limit = speed_limit(state, at.road->road, at.road->s, *at.road->lane)) {
      return *limit;
    }
  }
  return kSpawnDefaultSpeed;
}

}  // namespace corsa::engine::detail
