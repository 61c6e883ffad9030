#include "motion/refpoint_trail.h"

#include <cmath>
#include <string>

#include "corsa/core/strings.h"
#include "corsa/xosc/entities.h"
#include "geometry/angle.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

constexpr const char* kRefpointProperty = "refpoint_x_offset";

// The property's length (m), if the entity is a vehicle that gives a usable one.
std::optional<double> refpoint_length(SimState& state, const Entity& entity) {
  const auto* vehicle =
      entity.object == nullptr ? nullptr : std::get_if<xosc::Vehicle>(&entity.object->object);
  if (vehicle == nullptr) return std::nullopt;
  for (const xosc::Property& property : vehicle->properties.properties) {
    if (property.name != kRefpointProperty) continue;
    const std::optional<double> value = parse_double(property.value);
    if (!value || !std::isfinite(*value) || *value < 0.0) {
      // Once per property: a catalog vehicle serves many entities (the message names the first).
      state.diagnostics.add_once(
          std::string("refpoint:") + property.source.file_name() + ":" +
              std::to_string(property.source.line),
          property.source.warning(
              "vehicle '" + entity.info.name + "': property " + kRefpointProperty + " '" +
              property.value +
              "' is no number >= 0 (metres from the axle the body turns about forward to the "
              "reference point): ignored, the body faces the way it moves"));
      return std::nullopt;
    }
    return *value;
  }
  return std::nullopt;
}

RefpointTrail* refpoint_trail_of(SimState& state, const Entity& entity) {
  for (RefpointTrail& trail : state.refpoint_trailing) {
    if (&state.world.entities[trail.entity] == &entity) return &trail;
  }
  return nullptr;
}

}  // namespace

void read_refpoint_offsets(SimState& state) {
  for (uint32_t i = 0; i < state.world.entities.size(); ++i) {
    Entity& entity = state.world.entities[i];
    const std::optional<double> length = refpoint_length(state, entity);
    if (!length || *length == 0.0) continue;
    RefpointTrail trail;
    trail.entity = i;
    trail.length = *length;
    trail.axle_x = entity.state().pose.x - *length * std::cos(entity.state().pose.h);
    trail.axle_y = entity.state().pose.y - *length * std::sin(entity.state().pose.h);
    trail.heading = entity.state().pose.h;
    state.refpoint_trailing.push_back(trail);
  }
}

void mark_refpoint_jump(SimState& state, const Entity& entity) {
  if (RefpointTrail* trail = refpoint_trail_of(state, entity)) trail->jumped = true;
}

void mark_refpoint_moved(SimState& state, const Entity& entity) {
  if (RefpointTrail* trail = refpoint_trail_of(state, entity)) trail->jumped = false;
}

[[gnu::hot]] void trail_refpoints(SimState& state, double dt) {
  for (RefpointTrail& trail : state.refpoint_trailing) {
    Entity& entity = state.world.entities[trail.entity];
    const Pose& pose = entity.state().pose;
    if (!entity.state().placed || entity.removed) continue;
    if (!trail.jumped) {
      // The axle moves straight toward the reference point's new place.
      const double dx = pose.x - trail.axle_x, dy = pose.y - trail.axle_y;
      EntityState& written = entity.write_state();
      written.pose.h = std::hypot(dx, dy) > 1e-9 ? std::atan2(dy, dx) : trail.heading;
      written.yaw_rate = dt > 0.0 ? wrap_angle(pose.h - trail.heading) / dt : 0.0;
    }
    trail.jumped = false;
    trail.axle_x = pose.x - trail.length * std::cos(pose.h);
    trail.axle_y = pose.y - trail.length * std::sin(pose.h);
    trail.heading = pose.h;
  }
}

}  // namespace corsa::engine::detail
