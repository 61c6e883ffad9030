#include "motion/trailers.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "corsa/core/strings.h"
#include "corsa/xosc/entities.h"
#include "geometry/angle.h"
#include "motion/controller.h"
#include "motion/placement.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

const xosc::Vehicle* vehicle_of(const Entity& entity) {
  return entity.object == nullptr ? nullptr : std::get_if<xosc::Vehicle>(&entity.object->object);
}

// The point `dx` metres ahead of the reference point of a pose.
std::pair<double, double> ahead(const Pose& pose, double dx) {
  return {pose.x + dx * std::cos(pose.h), pose.y + dx * std::sin(pose.h)};
}

// The trailer does not follow a lane of its own: its road coordinates are looked up.
void relocate(SimState& state, Entity& entity) {
  entity.lane = LaneFollow{};
  update_road_from_pose(entity, state.map);
}

// Depth of an entity in its chain of towers (0: not towed).
int depth(const SimState& state, uint32_t index) {
  int n = 0;
  for (auto at = state.world.entities[index].towed_by; at && n < 64;
       at = state.world.entities[*at].towed_by) {
    ++n;
  }
  return n;
}

}  // namespace

double hitch_dx(const SimState& state, uint32_t tower) {
  const Entity& entity = state.world.entities[tower];
  if (const auto* vehicle = vehicle_of(entity); vehicle && vehicle->trailer_hitch) {
    return vehicle->trailer_hitch->dx;
  }
  return entity.info.box.center_x - entity.info.box.length / 2.0;
}

double coupler_dx(const SimState& state, uint32_t trailer) {
  const Entity& entity = state.world.entities[trailer];
  if (const auto* vehicle = vehicle_of(entity); vehicle && vehicle->trailer_coupler) {
    return vehicle->trailer_coupler->dx;
  }
  return entity.info.box.center_x + entity.info.box.length / 2.0;
}

void connect_trailer(SimState& state, uint32_t tower, uint32_t trailer, bool align) {
  disconnect_trailer(state, tower);
  Entity& towed = state.world.entities[trailer];
  if (towed.towed_by) disconnect_trailer(state, *towed.towed_by);
  state.world.entities[tower].towing = trailer;
  towed.towed_by = tower;
  state.trailers_connected = true;
  const Pose& pose = state.world.entities[tower].state().pose;
  const auto [hx, hy] = ahead(pose, hitch_dx(state, tower));
  const double back = coupler_dx(state, trailer);
  // Its coupler is put on the hitch now (hooking up), so the next step moves it smoothly: turned
  // toward the hitch from where it stands when its coupler is near the hitch (within 1 m, a
  // real hook-up), else in line behind the tower (a connection made from afar, or at Init).
  double heading = pose.h;
  if (!align && towed.state().placed) {
    const auto [cx, cy] = ahead(towed.state().pose, back);
    const double dx = hx - towed.state().pose.x, dy = hy - towed.state().pose.y;
    const double gap = std::hypot(hx - cx, hy - cy);
    if (gap <= 1.0 && std::hypot(dx, dy) > 1e-9) {
      heading = std::atan2(dy, dx);
    } else if (gap > 1.0) {
      const std::string message = "trailer '" + towed.info.name + "' is connected " +
                                  format_fixed(gap, 2) + " m away from the hitch of '" +
                                  state.world.entities[tower].info.name +
                                  "': it is put in line behind it";
      const Entity& entity = state.world.entities[tower];
      state.diagnostics.add_once("trailer-gap:" + towed.info.name,
                                 entity.object
                                     ? entity.object->source.warning(message)
                                     : Diagnostic{Severity::kWarning, "", 0, -1, "", message});
    }
  }
  const double tower_speed = state.world.entities[tower].state().speed;
  EntityState& towed_state = towed.write_state();
  towed_state.pose.x = hx - back * std::cos(heading);
  towed_state.pose.y = hy - back * std::sin(heading);
  towed_state.pose.z = pose.z;
  towed_state.pose.h = heading;
  towed_state.speed = tower_speed;
  towed_state.placed = true;
  relocate(state, towed);
  mark_jump(towed);
}

void disconnect_trailer(SimState& state, uint32_t tower) {
  Entity& entity = state.world.entities[tower];
  if (!entity.towing) return;
  Entity& trailer = state.world.entities[*entity.towing];
  trailer.towed_by.reset();
  trailer.unhitched_from = tower;
  trailer.write_state().speed = 0.0;  // a trailer has no drive: it stays where it was left
  trailer.speed_command = 0.0;
  entity.towing.reset();
}

[[gnu::hot]] void move_trailers(SimState& state, double dt) {
  if (!state.trailers_connected) {
    return;  // no entity has been towed yet
  }
  std::vector<uint32_t> towed;
  // The count read once: a push_back could allocate, after which the compiler reloads the
  // entities' vector every round.
  const auto count = static_cast<uint32_t>(state.world.entities.size());
  const Entity* entities = state.world.entities.data();
  for (uint32_t i = 0; i < count; ++i) {
    if (entities[i].towed_by) towed.push_back(i);
  }
  // Towers before their trailers.
  std::stable_sort(towed.begin(), towed.end(),
                   [&](uint32_t a, uint32_t b) { return depth(state, a) < depth(state, b); });
  for (const uint32_t index : towed) {
    Entity& trailer = state.world.entities[index];
    const Entity& tower = state.world.entities[*trailer.towed_by];
    if (!tower.state().placed) continue;
    const auto [hx, hy] = ahead(tower.state().pose, hitch_dx(state, *trailer.towed_by));
    const double length = coupler_dx(state, index);
    const Pose before = trailer.state().pose;
    const double dx = hx - before.x, dy = hy - before.y;
    const double distance = std::hypot(dx, dy);
    // The towed axle moves straight toward the hitch: the coupler stays on it.
    const double heading = distance > 1e-9 ? std::atan2(dy, dx) : before.h;
    Pose after = before;
    after.x = hx - length * std::cos(heading);
    after.y = hy - length * std::sin(heading);
    after.z = tower.state().pose.z;
    after.h = heading;
    const double moved_x = after.x - before.x, moved_y = after.y - before.y;
    const double moved = std::hypot(moved_x, moved_y);
    const double along = moved_x * std::cos(heading) + moved_y * std::sin(heading);
    const double speed = dt > 0.0 ? (along >= 0.0 ? moved : -moved) / dt : 0.0;
    EntityState& trailer_state = trailer.write_state();
    trailer_state.acceleration = dt > 0.0 ? (speed - trailer_state.speed) / dt : 0.0;
    trailer_state.yaw_rate = dt > 0.0 ? wrap_angle(heading - before.h) / dt : 0.0;
    trailer_state.speed = speed;
    trailer_state.lateral_speed = 0.0;
    trailer_state.odometer += moved;
    trailer_state.pose = after;
    trailer_state.placed = true;
    trailer.speed_command = speed;
    relocate(state, trailer);
  }
}

}  // namespace corsa::engine::detail
