#include "state/world_update.h"

#include <cmath>

#include "corsa/xodr/map.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {

namespace {

// Off the road: on no lane, or on a lane of type none. OpenDRIVE 1.8 §9.5.3: a lane of type none
// "describes the space on the outermost edge of the road and does not have actual content. Its
// only purpose is for applications to register that ASAM OpenDRIVE is still present in case the
// (human) driver leaves the road". esmini's OffroadCondition counts it off the road too (the road
// width without such lanes).
bool off_road(const SimState& state, const Entity& entity) {
  if (!entity.state().road) return true;
  if (state.map == nullptr || entity.state().road->lane == 0) return false;
  const RoadCoordinates& at = *entity.state().road;
  const LaneFollow& follow = entity.lane;
  if (follow.node != xodr::kNoLane && follow.road == at.road && follow.section == at.section &&
      follow.lane == at.lane) {
    // The lane it follows (nearly always): its type from the lane graph's node, one read
    // instead of a search through the road's lanes every step.
    return state.map->lane_graph().info(follow.node).type == xodr::LaneType::kNone;
  }
  const xodr::Lane* lane = state.map->lane(xodr::LaneRef{at.road, at.section, at.lane});
  return lane != nullptr && lane->type == xodr::LaneType::kNone;
}

// Below this speed (m/s) an entity stands still. StandStillCondition (1.3): true "if the
// triggering entity/entities stands still for a given amount of time"; the text names no speed,
// and an entity slowed by a controller or a relative target only nears 0. esmini's threshold
// (ScenarioEngine.cpp STAND_STILL_THRESHOLD, -1e-3 < v < 1e-3), taken under both readings, as
// every reading the standard leaves open.
constexpr double kStandStillSpeed = 1e-3;

}  // namespace

[[gnu::hot]] void update_timers(SimState& state, bool advance) {
  // Only the timer conditions read the timers: without one in the storyboard they are not kept
  // (a run's conditions are all compiled from it when it is built).
  if (!state.timers_wanted) {
    return;
  }
  const double dt = advance ? state.time.dt() : 0.0;
  for (Entity& entity : state.world.entities) {
    // Each timer counts the time since its condition began: 0 at the first tick it holds.
    const bool was_still = entity.standing_still;
    entity.standing_still = std::abs(entity.state().speed) < kStandStillSpeed;
    entity.standstill_time =
        entity.standing_still ? (was_still ? entity.standstill_time + dt : 0.0) : 0.0;
    const bool offroad = off_road(state, entity);
    entity.offroad_time = offroad ? (entity.was_offroad ? entity.offroad_time + dt : 0.0) : 0.0;
    entity.was_offroad = offroad;
    entity.end_of_road_time =
        entity.end_of_road ? (entity.was_at_end ? entity.end_of_road_time + dt : 0.0) : 0.0;
    entity.was_at_end = entity.end_of_road;
  }
}

}  // namespace corsa::engine::detail
