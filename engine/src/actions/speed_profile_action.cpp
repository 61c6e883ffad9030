// SpeedProfileAction (OpenSCENARIO 1.3 §7.4.1.4): the actor's speed goes through the entries in
// turn. An entry with a time reaches its speed that many seconds after the previous entry was
// reached; one without is reached as fast as the dynamic constraints allow (DynamicConstraints,
// else the entity's Performance). With an entityRef the speeds are deltas to that entity's
// speed. followingMode `position` changes speed linearly between entries; `follow` with a
// smooth (cubic, zero acceleration at both ends) transition. Both keep the constraints: the
// acceleration never exceeds maxAcceleration / maxDeceleration, nor the speed maxSpeed.

#include <cmath>

#include "actions/action_makers.h"
#include "actions/dynamic_limits.h"
#include "motion/transition_shape.h"
#include "positions/position_common.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class SpeedProfileInstance final : public ActionInstance {
 public:
  explicit SpeedProfileInstance(const xosc::SpeedProfileAction& action) : action_(action) {}

  uint8_t domains() const override { return kDomainLongitudinal; }

  void start(ActionContext& context) override {
    const Entity& entity = context.entity();
    if (action_.entity_ref) {
      need_entity(context.state, *action_.entity_ref, action_.source);
      reference_ = *context.state.world.find(*action_.entity_ref);
    }
    limits_ = speed_limits(entity, action_.constraints);
    done_ = action_.entries.empty();
    begin_entry(context, entity.state.speed);
  }

  void step(ActionContext& context) override {
    Entity& entity = context.entity();
    const double dt = context.state.time.dt();
    const xosc::SpeedProfileEntry& entry = action_.entries[index_];
    const double target = target_speed(context, entry);
    double speed = target;
    const double elapsed = context.state.time.time(context.state.tick + 1 - entry_tick_);
    if (entry.time && *entry.time > 0.0) {
      const double p = std::min(1.0, elapsed / *entry.time);
      const xosc::DynamicsShape shape = action_.following_mode == xosc::FollowingMode::kFollow
                                            ? xosc::DynamicsShape::kCubic
                                            : xosc::DynamicsShape::kLinear;
      speed = entry_speed_ + shape_value(shape, p) * (target - entry_speed_);
    }
    speed = limits_.step_toward(entity.state.speed, speed, dt);
    entity.speed_command = speed;
    const bool timed_out = entry.time && elapsed >= *entry.time - 1e-9;
    const bool reached = std::abs(speed - target) < 1e-9;
    if ((entry.time && timed_out) || (!entry.time && reached)) {
      if (++index_ >= action_.entries.size()) {
        done_ = true;
        return;
      }
      begin_entry(context, speed);
      entry_tick_ = context.state.tick + 1;
    }
  }

  bool finished() const override { return done_; }

 private:
  void begin_entry(const ActionContext& context, double speed) {
    entry_speed_ = speed;
    entry_tick_ = context.state.tick;
  }

  double target_speed(const ActionContext& context, const xosc::SpeedProfileEntry& entry) const {
    if (reference_) {
      return context.state.world.entities[*reference_].state.speed + entry.speed;
    }
    return entry.speed;
  }

  const xosc::SpeedProfileAction& action_;
  std::optional<uint32_t> reference_;
  SpeedLimits limits_;
  size_t index_ = 0;
  double entry_speed_ = 0.0;
  int64_t entry_tick_ = 0;
  bool done_ = false;
};

}  // namespace

std::unique_ptr<ActionInstance> make_speed_profile_action(const xosc::SpeedProfileAction& action) {
  return std::make_unique<SpeedProfileInstance>(action);
}

}  // namespace corsa::engine::detail
