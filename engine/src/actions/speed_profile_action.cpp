// SpeedProfileAction (OpenSCENARIO 1.3 §7.4.1.4): the actor's speed goes through the entries in
// turn. An entry with a time reaches its speed that many seconds after the previous entry was
// reached; one without is reached as fast as the dynamic constraints allow (DynamicConstraints,
// else the entity's Performance). With an entityRef the speeds are deltas to that entity's
// speed. followingMode `position` changes speed linearly between entries. `follow` applies
// "jerk (change rate of acceleration/deceleration) and other optional constraints" (1.3
// SpeedProfileAction): with a maxAccelerationRate or maxDecelerationRate (DynamicConstraints,
// else the vehicle's Performance) the speed follows a jerk-limited plan made at the start
// (motion/jerk_profile.h: the lines between the entries with their corners rounded, a single
// entry reached on time when the limits allow, else late), with an entityRef the deltas taken
// to that entity's speed at the start; without either rate a smooth (cubic, zero acceleration
// at both ends) transition per entry. Both modes keep the acceleration within maxAcceleration /
// maxDeceleration and the speed within maxSpeed.

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "actions/action_makers.h"
#include "actions/dynamic_limits.h"
#include "motion/jerk_profile.h"
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
    begin_entry(context, entity.state().speed);
    if (!done_ && action_.following_mode == xosc::FollowingMode::kFollow) {
      plan_jerk_limited(context);
    }
  }

  void step(ActionContext& context) override {
    Entity& entity = context.entity();
    const double dt = context.state.time.dt();
    if (plan_) {
      const double elapsed = context.state.time.time(context.state.tick + 1 - entry_tick_);
      entity.speed_command =
          limits_.step_toward(entity.state().speed, plan_->speed_at(elapsed), dt);
      done_ = elapsed >= plan_->end_time() - 1e-9;
      return;
    }
    // An entry of no duration is a jump to its speed, reached at once: the next entry starts
    // from that speed in this same step (a profile that starts with {speed 0, time 0} moves in
    // its first step). The last entry, a jump or not, is commanded below.
    while (index_ + 1 < action_.entries.size() && action_.entries[index_].time &&
           *action_.entries[index_].time <= 0.0) {
      begin_entry(context, target_speed(context, action_.entries[index_]));
      ++index_;
    }
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
    speed = limits_.step_toward(entity.state().speed, speed, dt);
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

  /// The `follow` plan when a jerk limit is given (DynamicConstraints, else Performance): the
  /// entries as points (time, speed) from the start, a time-less entry as far on as the
  /// acceleration limit takes its change. A first entry of time 0 is the current speed (a jump
  /// is no follow), a later entry of no duration replaces the point before it.
  void plan_jerk_limited(const ActionContext& context) {
    const Entity& entity = context.entity();
    const auto rate = [](const std::optional<double>& given, double performance) {
      const double r = given && *given > 0.0 ? *given : performance;
      return r > 0.0 ? r : std::numeric_limits<double>::infinity();
    };
    const auto& c = action_.constraints;
    JerkLimits jerk{
        limits_.acceleration, limits_.deceleration,
        rate(c ? c->max_acceleration_rate : std::nullopt, entity.info.max_acceleration_rate),
        rate(c ? c->max_deceleration_rate : std::nullopt, entity.info.max_deceleration_rate)};
    if (std::isinf(jerk.acceleration_rate) && std::isinf(jerk.deceleration_rate)) {
      return;
    }
    const double offset =
        reference_ ? context.state.world.entities[*reference_].state().speed : 0.0;
    std::vector<SpeedVertex> points{{0.0, entity.state().speed}};
    for (size_t i = 0; i < action_.entries.size(); ++i) {
      const xosc::SpeedProfileEntry& entry = action_.entries[i];
      const double v = std::min(entry.speed + offset, limits_.speed);
      const double dv = v - points.back().v;
      double duration = 0.0;
      if (entry.time && *entry.time > 1e-9) {
        duration = *entry.time;
      } else if (entry.time && points.size() > 1) {
        points.back().v = v;
        continue;
      } else if (entry.time && i == 0) {
        continue;
      } else if (std::abs(dv) < 1e-9) {
        continue;
      } else {
        duration = std::abs(dv) / (dv > 0.0 ? limits_.acceleration : limits_.deceleration);
      }
      points.push_back({points.back().t + duration, v});
    }
    const double a0 =
        std::clamp(entity.state().acceleration, -limits_.deceleration, limits_.acceleration);
    plan_.emplace(points, a0, jerk);
  }

  double target_speed(const ActionContext& context, const xosc::SpeedProfileEntry& entry) const {
    if (reference_) {
      return context.state.world.entities[*reference_].state().speed + entry.speed;
    }
    return entry.speed;
  }

  const xosc::SpeedProfileAction& action_;
  std::optional<uint32_t> reference_;
  SpeedLimits limits_;
  std::optional<JerkProfile> plan_;
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
