// SynchronizeAction (OpenSCENARIO 1.3 §7.4.1.3): the actor adapts its speed so that it reaches
// its target position when the master entity reaches the master's target position, optionally
// with a final speed (absolute, or relative to the master's: delta or factor) that it holds for
// a steady-state distance or time before its target.
//
// Distances to go are measured along the lanes (the shortest lane route, laid once at the
// start and then counted down with the distance driven), or straight when an entity is off the
// lanes. Every step the master's arrival time T = d_master / v_master is re-estimated and the
// actor's speed planned anew (receding horizon): without a final speed a constant acceleration
// that covers d in T; with one, two linear ramps of T/2 through a middle speed v_p such that
// d = T/4 (v0 + 2 v_p + v_f), ending at v_f. The action ends when either entity is within its
// tolerance of its target (or has passed it); the final speed then stays commanded.
//
// The planned speed is followed within the actor's Performance (§7.4: maxSpeed, maxAcceleration,
// maxDeceleration; SynchronizeAction has no DynamicConstraints of its own): each step's speed
// moves toward the plan by at most the acceleration or deceleration limit times dt and never
// above maxSpeed. When, at the master's current speed, the actor can no longer cover its
// distance in the master's time within those limits (too far: it arrives late; too near: it
// arrives early even braking to a stop), a located warning says so, once. esmini's reading
// (Semantics::kEsmini) follows the plan without the Performance.

#include <algorithm>
#include <cmath>
#include <limits>

#include "actions/action_makers.h"
#include "actions/dynamic_limits.h"
#include "corsa/core/strings.h"
#include "corsa/xodr/route.h"
#include "positions/position_common.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

// Distance (m) left to a target: along the lanes from where the countdown started, or straight.
class DistanceToGo {
 public:
  void start(const SimState& state, const Entity& entity, const ResolvedPosition& target) {
    target_x_ = target.pose.x;
    target_y_ = target.pose.y;
    along_lanes_ = false;
    if (state.map != nullptr && entity.lane.on_road && target.road && target.road->lane) {
      const xodr::LanePoint from{entity.lane.road, entity.lane.lane, entity.lane.s};
      const xodr::LanePoint to{target.road->road, *target.road->lane, target.road->s};
      if (const auto route = xodr::find_route(*state.map, from, to)) {
        along_lanes_ = true;
        initial_ = route->length;
        driven_at_start_ = entity.longitudinal_distance;
      }
    }
  }
  double operator()(const Entity& entity) const {
    if (along_lanes_) {
      return initial_ - (entity.longitudinal_distance - driven_at_start_);
    }
    // Straight: negative once the target is behind the entity's heading.
    const double dx = target_x_ - entity.state.pose.x;
    const double dy = target_y_ - entity.state.pose.y;
    const double ahead = dx * std::cos(entity.state.pose.h) + dy * std::sin(entity.state.pose.h);
    return std::copysign(std::hypot(dx, dy), ahead);
  }

 private:
  bool along_lanes_ = false;
  double initial_ = 0.0;
  double driven_at_start_ = 0.0;
  double target_x_ = 0.0, target_y_ = 0.0;
};

class SynchronizeInstance final : public ActionInstance {
 public:
  explicit SynchronizeInstance(const xosc::SynchronizeAction& action) : action_(action) {}

  uint8_t domains() const override { return kDomainLongitudinal; }

  void start(ActionContext& context) override {
    const SimState& state = context.state;
    need_entity(state, action_.master_entity_ref, action_.source);
    master_ = *state.world.find(action_.master_entity_ref);
    const Entity& master = state.world.entities[master_];
    master_to_go_.start(state, master,
                        resolve_position(action_.target_position_master, state, master_));
    own_to_go_.start(state, context.entity(),
                     resolve_position(action_.target_position, state, context.actor));
    limits_ = speed_limits(context.entity(), std::nullopt);
    if (state.options.semantics == Semantics::kEsmini) {
      // esmini plans the speed without the Performance: the actor keeps the appointment.
      unlimited_ = true;
      limits_.acceleration = limits_.deceleration = limits_.speed =
          std::numeric_limits<double>::infinity();
    }
  }

  void step(ActionContext& context) override {
    Entity& entity = context.entity();
    const Entity& master = context.state.world.entities[master_];
    const double dt = context.state.time.dt();
    const double d_master = master_to_go_(master);
    const double d_own = own_to_go_(entity);
    const auto v_final = final_speed(master.state.speed);
    if (arrived_ || d_master <= action_.target_tolerance_master.value_or(0.0) ||
        d_own <= action_.target_tolerance.value_or(0.0)) {
      arrived_ = true;
      // The final speed, reached within the limits: the action ends when it is.
      const double target = v_final ? *v_final : entity.speed_command;
      entity.speed_command = limits_.step_toward(entity.state.speed, target, dt);
      settled_ = std::abs(entity.speed_command - std::min(target, limits_.speed)) < 1e-9;
      return;
    }
    if (master.state.speed <= 1e-6) {
      return;  // the master stands: no arrival time to aim at, keep the speed
    }
    const double t_master = d_master / master.state.speed;
    warn_if_unreachable(context, d_own, t_master);
    entity.speed_command = limits_.step_toward(
        entity.state.speed, planned_speed(entity.state.speed, d_own, t_master, v_final, dt), dt);
  }

  bool finished() const override { return settled_; }

 private:
  std::optional<double> final_speed(double master_speed) const {
    if (!action_.final_speed) {
      return std::nullopt;
    }
    if (const auto* absolute = std::get_if<xosc::AbsoluteSpeed>(&*action_.final_speed)) {
      return absolute->value;
    }
    const auto& relative = std::get<xosc::RelativeSpeedToMaster>(*action_.final_speed);
    return relative.value_type == xosc::SpeedTargetValueType::kDelta
               ? master_speed + relative.value
               : master_speed * relative.value;
  }

  // Distances (m) the actor can cover in `t` seconds from speed v0 within its limits: at most
  // accelerating to maxSpeed and holding it, at least braking to a stop.
  std::pair<double, double> reachable(double v0, double t) const {
    const double a = limits_.acceleration, b = limits_.deceleration;
    const double v_max = std::max(v0, limits_.speed);
    const double t_up = (v_max - v0) / a;
    const double farthest =
        t <= t_up ? v0 * t + 0.5 * a * t * t : 0.5 * (v0 + v_max) * t_up + v_max * (t - t_up);
    const double nearest = v0 >= b * t ? v0 * t - 0.5 * b * t * t : v0 * v0 / (2.0 * b);
    return {nearest, farthest};
  }

  void warn_if_unreachable(ActionContext& context, double d_own, double t_master) {
    if (warned_ || unlimited_) {
      return;
    }
    const Entity& entity = context.entity();
    const auto [nearest, farthest] = reachable(entity.state.speed, t_master);
    // A little slack: the receding-horizon plan absorbs rounding and step effects.
    const double slack = 0.5 + 0.01 * d_own;
    const bool late = d_own > farthest + slack;
    const bool early = d_own < nearest - slack;
    if (!late && !early) {
      return;
    }
    warned_ = true;
    context.state.diagnostics.add_once(
        "synchronize-limits:" + entity.info.name + ":" + std::to_string(action_.source.line),
        action_.source.warning(
            "SynchronizeAction: '" + entity.info.name + "' cannot reach its target when '" +
            action_.master_entity_ref + "' reaches its own (" + format_double(d_own) + " m in " +
            format_double(t_master) + " s; within maxSpeed " + format_double(limits_.speed) +
            " m/s, maxAcceleration " + format_double(limits_.acceleration) +
            " m/s^2 and maxDeceleration " + format_double(limits_.deceleration) +
            " m/s^2 it covers " + format_double(nearest) + " to " + format_double(farthest) +
            " m): it arrives " + (late ? "late" : "early")));
  }

  // The steady state before the target: (distance m, time s) at the final speed.
  std::pair<double, double> steady_state(double v_final) const {
    std::optional<xosc::SteadyState> steady;
    if (const auto* absolute = std::get_if<xosc::AbsoluteSpeed>(&*action_.final_speed)) {
      steady = absolute->steady_state;
    } else {
      steady = std::get<xosc::RelativeSpeedToMaster>(*action_.final_speed).steady_state;
    }
    if (!steady || v_final <= 0.0) {
      return {0.0, 0.0};
    }
    if (const auto* by_distance = std::get_if<xosc::TargetDistanceSteadyState>(&*steady)) {
      return {by_distance->distance, by_distance->distance / v_final};
    }
    const double time = std::get<xosc::TargetTimeSteadyState>(*steady).time;
    return {time * v_final, time};
  }

  double planned_speed(double v0, double d, double t, std::optional<double> v_final,
                       double dt) const {
    if (!v_final) {
      if (t <= dt) {
        return std::max(0.0, d / t);
      }
      const double a = 2.0 * (d - v0 * t) / (t * t);
      return std::max(0.0, v0 + a * dt);
    }
    const auto [d_steady, t_steady] = steady_state(*v_final);
    d -= d_steady;
    t -= t_steady;
    if (d <= 0.0 || t <= dt) {
      return *v_final;  // in the steady state (or arriving this step)
    }
    const double v_mid = std::max(0.0, (4.0 * d / t - v0 - *v_final) / 2.0);
    return std::max(0.0, v0 + (v_mid - v0) * dt / (0.5 * t));
  }

  const xosc::SynchronizeAction& action_;
  uint32_t master_ = 0;
  DistanceToGo master_to_go_;
  DistanceToGo own_to_go_;
  SpeedLimits limits_;
  bool unlimited_ = false;  ///< no Performance bounds the plan (Semantics::kEsmini)
  bool arrived_ = false;
  bool settled_ = false;  ///< arrived and at the final speed
  bool warned_ = false;
};

}  // namespace

std::unique_ptr<ActionInstance> make_synchronize_action(const xosc::SynchronizeAction& action) {
  return std::make_unique<SynchronizeInstance>(action);
}

}  // namespace corsa::engine::detail
