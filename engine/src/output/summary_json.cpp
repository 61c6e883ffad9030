#include <string>
#include <string_view>

#include "corsa/core/atomic_file.h"
#include "corsa/core/json.h"
#include "corsa/engine/outputs.h"
#include "corsa/xosc/scenario.h"

namespace corsa::engine {
namespace {

// -0 as 0; infinities and NaN become null in the text.
double number(double value) { return value + 0.0; }

std::string_view light_mode_name(LightMode mode) {
  return mode == LightMode::kOn ? "on" : mode == LightMode::kOff ? "off" : "flashing";
}

/// The lights LightStateActions set on entity `i`, in order: when, which, and how.
Json light_changes_json(const Simulation& simulation, size_t i) {
  Json out = Json::array();
  for (const LightChange& change : simulation.light_changes()) {
    if (change.entity != i) {
      continue;
    }
    const LightSettingView& s = change.setting;
    Json one = {{"time", number(s.since)},
                {"light", std::string(kVehicleLightNames[static_cast<size_t>(s.light)])},
                {"mode", std::string(light_mode_name(s.mode))}};
    if (s.mode == LightMode::kFlashing) {
      one["flashing"] = {number(s.on_s), number(s.off_s)};
    }
    if (s.candela) {
      one["intensity_cd"] = number(*s.candela);
    }
    if (s.rgb) {
      one["colour"] = {number((*s.rgb)[0]), number((*s.rgb)[1]), number((*s.rgb)[2])};
    }
    if (s.transition_s > 0.0) {
      one["transition_time"] = number(s.transition_s);
    }
    out.push_back(std::move(one));
  }
  return out;
}

Json entity_json(const Simulation& simulation, size_t i) {
  const EntityState& s = simulation.state(i);
  Json out = {{"name", simulation.entity(i).name},
              {"x", number(s.pose.x)},
              {"y", number(s.pose.y)},
              {"h", number(s.pose.h)},
              {"speed", number(s.speed)},
              {"odometer", number(s.odometer)}};
  if (s.road) {
    out["road"] = simulation.road_id(s.road->road);
    out["lane"] = s.road->lane;
  }
  // A controller of the scenario this engine does not have: acc drove in its place.
  if (const auto substitute = simulation.controller_substitute(i); !substitute.empty()) {
    out["controller"] = "acc";
    out["substitute_for"] = substitute;
  }
  // The lights LightStateActions set: the record of when each light state changed.
  if (Json lights = light_changes_json(simulation, i); !lights.empty()) {
    out["lights"] = std::move(lights);
  }
  // Generated entities (traffic actions, NPCs): whether present at the end, and when each
  // presence began and ended (the pose above is where it was last).
  if (const auto lives = simulation.lifetimes(i); !lives.empty()) {
    out["generated"] = true;
    out["present"] = s.placed;
    Json lifetimes = Json::array();
    for (const Lifetime& life : lives) {
      Json one = {{"spawned", number(life.spawned)}};
      if (life.removed) {
        one["removed"] = number(*life.removed);
      }
      lifetimes.push_back(std::move(one));
    }
    out["lifetimes"] = std::move(lifetimes);
  }
  return out;
}

}  // namespace

std::string summary_json(const Simulation& simulation, double wall_seconds) {
  const xosc::Scenario& scenario = simulation.scenario();
  Json parameters = Json::object();
  for (const auto& p : scenario.parameters) {
    parameters[p.name] = p.value.text();
  }
  Json entities = Json::array();
  for (size_t i = 0; i < simulation.entity_count(); ++i) {
    entities.push_back(entity_json(simulation, i));
  }
  Json collisions = Json::array();
  for (const CollisionRecord& c : simulation.collisions()) {
    collisions.push_back(
        {{"time", number(c.time)},
         {"entities", {simulation.entity(c.first).name, simulation.entity(c.second).name}}});
  }
  Json summary = {
      {"scenario", scenario.path.string()},
      {"parameters", std::move(parameters)},
      {"seed", simulation.options().seed},
      {"dt", number(simulation.dt())},
      {"end_reason", to_string(simulation.end_reason())},
      {"sim_time", number(simulation.time())},
      {"start_time", number(simulation.time_of(simulation.start_tick()))},
      {"steps", simulation.steps()},
      {"wall_time", number(wall_seconds)},
      {"real_time_factor", number(wall_seconds > 0.0 ? simulation.time() / wall_seconds : 0.0)},
      {"entities", std::move(entities)}};
  // The scenario's own verdicts (MonitorDeclarations, SetMonitorAction), by name.
  if (const auto monitors = simulation.monitors(); !monitors.empty()) {
    Json verdicts = Json::object();
    for (const auto& [name, value] : monitors) {
      verdicts[name] = value;
    }
    summary["monitors"] = std::move(verdicts);
  }
  summary["collisions"] = std::move(collisions);
  return json_document(summary);
}

void write_summary(const Simulation& simulation, const std::filesystem::path& file,
                   double wall_seconds) {
  write_file_atomic(file, summary_json(simulation, wall_seconds));
}

}  // namespace corsa::engine
