// SpeedAction (OpenSCENARIO 1.3 §7.4.1.1): the actor's longitudinal speed goes to an absolute
// target or one relative to another entity (delta or factor), with a TransitionDynamics shape
// over time, distance or rate. A continuous relative target keeps tracking and never ends.
//
// The transition holds as written (TransitionDynamics followingMode `position`, the default:
// "forces the actor to strictly adhere to a given shape"). In mode `follow` "the actor tries to
// follow the shape as best as it can. This may be restricted by the 'Performance' properties
// (for vehicles)": the shape is then held to the vehicle's Performance, as esmini's reading holds
// every SpeedAction (Semantics::kEsmini): the target within maxSpeed, the transition stretched in
// time until its steepest change is within maxAcceleration / maxDeceleration, and no step
// changing the speed by more than that limit x dt. A linear `rate` toward a relative target
// changes the speed at the rate toward the reference's speed of each step until it meets it,
// however long the reference keeps moving away, as esmini reads it: the standard says only that
// such an action ends "when the target speed is reached" (1.3 RelativeTargetSpeed `continuous`),
// not which of the reference's speeds is meant.

#include <algorithm>
#include <cmath>
#include <variant>

#include "actions/action_makers.h"
#include "motion/transition_shape.h"
#include "positions/position_common.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class SpeedInstance final : public ActionInstance {
 public:
  explicit SpeedInstance(const xosc::SpeedAction& action) : action_(action) {}

  uint8_t domains() const override { return kDomainLongitudinal; }

  void start(ActionContext& context) override {
    Entity& entity = context.entity();
    performance_limits_ = context.state.options.semantics == Semantics::kEsmini ||
                          action_.dynamics.following_mode == xosc::FollowingMode::kFollow;
    if (const auto* relative = std::get_if<xosc::RelativeTargetSpeed>(&action_.target)) {
      need_entity(context.state, relative->entity_ref, relative->source);
      reference_index_ = *context.state.world.find(relative->entity_ref);
      continuous_ = relative->continuous;
    }
    start_speed_ = entity.state().speed;
    start_tick_ = context.state.tick;
    const double target = target_speed(context);
    const xosc::TransitionDynamics& dynamics = action_.dynamics;
    rate_tracking_ = std::holds_alternative<xosc::RelativeTargetSpeed>(action_.target) &&
                     dynamics.dimension == xosc::DynamicsDimension::kRate &&
                     dynamics.shape == xosc::DynamicsShape::kLinear && dynamics.value > 0.0;
    double duration = 0.0;  // s
    if (dynamics.shape != xosc::DynamicsShape::kStep) {
      switch (dynamics.dimension) {
        case xosc::DynamicsDimension::kTime:
          duration = dynamics.value;
          break;
        case xosc::DynamicsDimension::kRate:
          // The rate (m/s^2) is the largest acceleration on the way.
          duration = dynamics.value > 0.0 ? std::abs(target - start_speed_) *
                                                shape_peak_slope(dynamics.shape) / dynamics.value
                                          : 0.0;
          break;
        case xosc::DynamicsDimension::kDistance:
          // Every shape averages half way, so the distance covered is duration * mean speed.
          duration =
              start_speed_ + target > 0.0 ? 2.0 * dynamics.value / (start_speed_ + target) : 0.0;
          break;
      }
    }
    if (performance_limits_ && duration > 0.0) {
      duration = stretched_to_performance(entity, target, duration);
    }
    duration_ = duration;
    if (duration_ <= 0.0) {
      command(context, target);
      reached_ = true;
    }
  }

  [[gnu::hot]] void step(ActionContext& context) override {
    const double target = target_speed(context);
    if (reached_) {
      // Continuous: keep tracking. A step's jump stands in the step it is made in, also under
      // the Performance limits ("a step shape still jumps at once"; esmini's cut-in has
      // its OverTaker at 1.2 x the Ego's 30 m/s from the act's start on).
      const bool jumped_now = duration_ <= 0.0 && context.state.tick == start_tick_;
      command(context, jumped_now ? target : within_performance(context, target));
      return;
    }
    if (rate_tracking_) {
      const double current = context.entity().state().speed;
      const double change = action_.dynamics.value * context.state.time.dt();
      const double speed =
          within_performance(context, current + std::clamp(target - current, -change, change));
      command(context, speed);
      reached_ = std::abs(speed - target) <= 1e-9;
      return;
    }
    const double elapsed = context.state.time.time(context.state.tick + 1 - start_tick_);
    const double p = elapsed >= duration_ ? 1.0 : elapsed / duration_;
    command(context,
            within_performance(context, start_speed_ + shape_value(action_.dynamics.shape, p) *
                                                           (target - start_speed_)));
    reached_ = p >= 1.0;
  }

  bool finished() const override { return reached_ && !continuous_; }

 private:
  double target_speed(const ActionContext& context) const {
    double target = 0.0;
    if (const auto* absolute = std::get_if<xosc::AbsoluteTargetSpeed>(&action_.target)) {
      target = absolute->value;
    } else {
      const auto& relative = std::get<xosc::RelativeTargetSpeed>(action_.target);
      const double reference = context.state.world.entities[reference_index_].state().speed;
      target = relative.value_type == xosc::SpeedTargetValueType::kDelta
                   ? reference + relative.value
                   : reference * relative.value;
    }
    const double max_speed = context.entity().info.max_speed;
    if (performance_limits_ && max_speed > 0.0) {
      target = std::clamp(target, -max_speed, max_speed);  // never beyond maxSpeed
    }
    return target;
  }

  // Performance limits: a transition whose steepest speed change exceeds the
  // entity's maxAcceleration (speeding up) or maxDeceleration (slowing down) is stretched in
  // time, keeping its shape, until its steepest change equals that limit.
  double stretched_to_performance(const Entity& entity, double target, double duration) const {
    const double limit =
        target > start_speed_ ? entity.info.max_acceleration : entity.info.max_deceleration;
    const double peak =
        std::abs(target - start_speed_) * shape_peak_slope(action_.dynamics.shape) / duration;
    return limit > 0.0 && peak > limit ? duration * peak / limit : duration;
  }

  // Performance limits: no step changes the speed by more than maxAcceleration x dt
  // (or maxDeceleration x dt), whatever the transition asks.
  double within_performance(const ActionContext& context, double speed) const {
    if (!performance_limits_) {
      return speed;
    }
    const Entity& entity = context.entity();
    const double dt = context.state.time.dt();
    const double current = entity.state().speed;
    if (entity.info.max_acceleration > 0.0) {
      speed = std::min(speed, current + entity.info.max_acceleration * dt);
    }
    if (entity.info.max_deceleration > 0.0) {
      speed = std::max(speed, current - entity.info.max_deceleration * dt);
    }
    return speed;
  }

  void command(ActionContext& context, double speed) const {
    Entity& entity = context.entity();
    entity.speed_command = speed;
    if (context.init) {
      entity.write_state().speed =
          speed;  // Init happens before time starts: no transition to drive
    }
  }

  const xosc::SpeedAction& action_;
  uint32_t reference_index_ = 0;
  bool continuous_ = false;
  double start_speed_ = 0.0;
  int64_t start_tick_ = 0;
  double duration_ = 0.0;
  bool reached_ = false;
  /// Performance bounds the transition: followingMode `follow`, or Semantics::kEsmini.
  bool performance_limits_ = false;
  /// A linear rate toward a relative target: each step changes the speed by the rate toward the
  /// reference's speed of that step, until it meets it (not a duration fixed at the start).
  bool rate_tracking_ = false;
};

}  // namespace

std::unique_ptr<ActionInstance> make_speed_action(const xosc::SpeedAction& action) {
  return std::make_unique<SpeedInstance>(action);
}

}  // namespace corsa::engine::detail
