// The `acc` controller: adaptive cruise control on top of the default controller. The set speed
// is what the actions command; when a vehicle drives ahead in the same lane the speed is held
// below that so as to keep a time gap (constant time-gap policy, e.g. Rajamani, Vehicle Dynamics
// and Control, §5.3), within the vehicle's Performance limits.

#include <algorithm>
#include <cmath>
#include <limits>

#include "controllers/controllers.h"
#include "core/sim_state.h"

namespace corsa::engine::detail {
namespace {

constexpr double kTimeGap = 1.5;       // s
constexpr double kStandstill = 3.0;    // m, bumper to bumper at rest
constexpr double kRange = 200.0;       // m, sensor range
constexpr double kGapGain = 0.25;      // 1/s^2
constexpr double kSpeedGain = 0.8;     // 1/s
constexpr double kDefaultLimit = 6.0;  // m/s^2 when the Performance gives none

struct Leader {
  double gap = std::numeric_limits<double>::infinity();  ///< m, bumper to bumper
  double speed = 0.0;
};

// The nearest present, traffic-visible entity ahead in the same lane of the same road.
Leader find_leader(const SimState& state, uint32_t self) {
  const Entity& me = state.world.entities[self];
  Leader leader;
  if (!me.state.road || !me.lane.on_road) {
    return leader;
  }
  const RoadCoordinates& mine = *me.state.road;
  const double my_front = me.info.box.center_x + 0.5 * me.info.box.length;
  for (uint32_t i = 0; i < state.world.entities.size(); ++i) {
    const Entity& other = state.world.entities[i];
    if (i == self || !other.state.placed || !other.state.road ||
        (i < state.controls.size() && !state.controls[i].traffic_visible)) {
      continue;
    }
    const RoadCoordinates& theirs = *other.state.road;
    if (theirs.road != mine.road || theirs.lane != mine.lane) {
      continue;
    }
    const double ahead = (theirs.s - mine.s) * me.lane.dir;
    const double their_rear = other.info.box.center_x - 0.5 * other.info.box.length;
    const double gap = ahead - my_front + their_rear;
    if (ahead > 0.0 && ahead < kRange && gap < leader.gap) {
      leader.gap = gap;
      leader.speed = other.state.speed * std::cos(other.state.pose.h - me.state.pose.h);
    }
  }
  return leader;
}

}  // namespace

void step_acc(SimState& state, uint32_t index, const MotionContext& motion) {
  Entity& entity = state.world.entities[index];
  const double set_speed = entity.speed_command;
  const Leader leader = find_leader(state, index);
  double command = set_speed;
  if (std::isfinite(leader.gap)) {
    const double v = entity.state.speed;
    const double desired = kStandstill + kTimeGap * std::max(v, 0.0);
    const double max_acc =
        entity.info.max_acceleration > 0.0 ? entity.info.max_acceleration : kDefaultLimit;
    const double max_dec =
        entity.info.max_deceleration > 0.0 ? entity.info.max_deceleration : kDefaultLimit;
    const double a = std::clamp(kGapGain * (leader.gap - desired) + kSpeedGain * (leader.speed - v),
                                -max_dec, max_acc);
    command = std::min(set_speed, std::max(0.0, v + a * motion.dt));
  }
  entity.speed_command = command;
  DefaultController().step(entity, motion);
  // The actions' set speed stays what they asked for (the default controller zeroes it at a
  // road end, which stands).
  if (entity.speed_command == command) {
    entity.speed_command = set_speed;
  }
}

}  // namespace corsa::engine::detail
