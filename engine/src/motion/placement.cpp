#include "motion/placement.h"

#include <cmath>

#include "corsa/core/strings.h"
#include "lanes/lane_follow.h"
#include "motion/controller.h"
#include "motion/refpoint_trail.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {

namespace {

void put_entity_at_position(SimState& state, Entity& entity, const ResolvedPosition& position,
                            const xosc::Source& source, bool require_on_map) {
  entity.write_state().pose = {position.pose.x, position.pose.y, position.pose.z,
                               position.pose.h, position.pose.p, position.pose.r};
  entity.write_state().placed = true;
  entity.removed = false;
  entity.removed_road.reset();
  entity.lane = LaneFollow{};
  entity.end_of_road = false;
  entity.end_of_road_time = 0.0;
  if (state.map != nullptr && position.road && position.road->lane &&
      attach_to_lane(*state.map, entity.lane, position.road->road, position.road->s,
                     position.road->t, *position.road->lane, position.pose.h)) {
    std::vector<xodr::LaneSpan> scratch;
    update_pose_from_lane(entity, *state.map, scratch);
    entity.lateral_command = entity.lane.lateral;
    return;
  }
  entity.lateral_command = 0.0;
  if (state.map == nullptr) {
    entity.write_state().road.reset();
    return;
  }
  if (require_on_map &&
      !locate_point(*state.map, position.pose.x, position.pose.y, kOffMapDistance)) {
    throw InputError(source.error("entity '" + entity.info.name + "' is placed off the map: (" +
                                  format_double(position.pose.x) + ", " +
                                  format_double(position.pose.y) + ") is more than " +
                                  format_double(kOffMapDistance) + " m from every lane"));
  }
  update_road_from_pose(entity, state.map);
}

}  // namespace

void place_entity(SimState& state, Entity& entity, const ResolvedPosition& position,
                  const xosc::Source& source, bool require_on_map) {
  put_entity_at_position(state, entity, position, source, require_on_map);
  mark_jump(entity);
  mark_refpoint_jump(state, entity);
}

void mark_jump(Entity& entity) {
  entity.straight_from_x = entity.state().pose.x;
  entity.straight_from_y = entity.state().pose.y;
}

void sum_straight_travel(SimState& state) {
  for (Entity& entity : state.world.entities) {
    if (!entity.state().placed) {
      continue;
    }
    const double x = entity.state().pose.x, y = entity.state().pose.y;
    entity.straight_travel += std::hypot(x - entity.straight_from_x, y - entity.straight_from_y);
    entity.straight_from_x = x;
    entity.straight_from_y = y;
  }
}

}  // namespace corsa::engine::detail
