#include <cmath>

#include "corsa/core/atomic_file.h"
#include "corsa/core/strings.h"
#include "corsa/engine/outputs.h"
#include "corsa/xosc/scenario.h"

namespace corsa::engine {
namespace {

std::string number(double value) {
  // JSON has no infinities or NaN.
  return std::isfinite(value) ? format_double(value + 0.0) : "null";  // -0 as 0
}

}  // namespace

std::string summary_json(const Simulation& simulation, double wall_seconds) {
  const xosc::Scenario& scenario = simulation.scenario();
  std::string out = "{\n  \"scenario\": " + json_quote(scenario.path.string()) + ",\n";
  out += "  \"parameters\": {";
  for (size_t i = 0; i < scenario.parameters.size(); ++i) {
    const auto& p = scenario.parameters[i];
    out += (i ? ", " : "") + json_quote(p.name) + ": " + json_quote(p.value.text());
  }
  out += "},\n";
  out += "  \"seed\": " + std::to_string(simulation.options().seed) + ",\n";
  out += "  \"dt\": " + number(simulation.dt()) + ",\n";
  out += "  \"end_reason\": " + json_quote(to_string(simulation.end_reason())) + ",\n";
  out += "  \"sim_time\": " + number(simulation.time()) + ",\n";
  out += "  \"steps\": " + std::to_string(simulation.tick()) + ",\n";
  out += "  \"wall_time\": " + number(wall_seconds) + ",\n";
  out += "  \"real_time_factor\": " +
         number(wall_seconds > 0.0 ? simulation.time() / wall_seconds : 0.0) + ",\n";
  out += "  \"entities\": [";
  for (size_t i = 0; i < simulation.entity_count(); ++i) {
    const EntityState& s = simulation.state(i);
    out += std::string(i ? "," : "") + "\n    {\"name\": " + json_quote(simulation.entity(i).name) +
           ", \"x\": " + number(s.pose.x) + ", \"y\": " + number(s.pose.y) +
           ", \"h\": " + number(s.pose.h) + ", \"speed\": " + number(s.speed) +
           ", \"odometer\": " + number(s.odometer);
    if (s.road) {
      out += ", \"road\": " + json_quote(simulation.road_id(s.road->road)) +
             ", \"lane\": " + std::to_string(s.road->lane);
    }
    // Generated entities (traffic actions, NPCs): whether present at the end, and when each
    // presence began and ended (the pose above is where it was last).
    if (const auto lives = simulation.lifetimes(i); !lives.empty()) {
      out += std::string(", \"generated\": true, \"present\": ") + (s.placed ? "true" : "false") +
             ", \"lifetimes\": [";
      for (size_t k = 0; k < lives.size(); ++k) {
        out += std::string(k ? ", " : "") + "{\"spawned\": " + number(lives[k].spawned);
        if (lives[k].removed) {
          out += ", \"removed\": " + number(*lives[k].removed);
        }
        out += "}";
      }
      out += "]";
    }
    out += "}";
  }
  out += simulation.entity_count() ? "\n  ],\n" : "],\n";
  out += "  \"collisions\": [";
  const auto collisions = simulation.collisions();
  for (size_t i = 0; i < collisions.size(); ++i) {
    const CollisionRecord& c = collisions[i];
    out += std::string(i ? "," : "") + "\n    {\"time\": " + number(c.time) + ", \"entities\": [" +
           json_quote(simulation.entity(c.first).name) + ", " +
           json_quote(simulation.entity(c.second).name) + "]}";
  }
  out += collisions.empty() ? "]\n}\n" : "\n  ]\n}\n";
  return out;
}

void write_summary(const Simulation& simulation, const std::filesystem::path& file,
                   double wall_seconds) {
  write_file_atomic(file, summary_json(simulation, wall_seconds));
}

}  // namespace corsa::engine
