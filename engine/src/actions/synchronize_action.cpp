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
// The actor follows the plan whatever its Performance: the action gives each entity a position
// "which shall be reached at the same time", has no DynamicConstraints, and the default
// controller enforces the control strategies "exactly as they are described by the actions"
// (§6.6.1); the standard never bounds it by maxSpeed, maxAcceleration or maxDeceleration. So
// the actor keeps the appointment (esmini reads it so too).

#include <algorithm>
#include <cmath>

#include "actions/action_makers.h"
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
    const double dx = target_x_ - entity.state().pose.x;
    const double dy = target_y_ - entity.state().pose.y;
    const double ahead =
        dx * std::cos(entity.state().pose.h) + dy * std::sin(entity.state().pose.h);
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
  }

  void step(ActionContext& context) override {
    Entity& entity = context.entity();
    const Entity& master = context.state.world.entities[master_];
    const double dt = context.state.time.dt();
    const double d_master = master_to_go_(master);
    const double d_own = own_to_go_(entity);
    const auto v_final = final_speed(master.state().speed);
    if (arrived_ || d_master <= action_.target_tolerance_master.value_or(0.0) ||
        d_own <= action_.target_tolerance.value_or(0.0)) {
      // The final speed, taken at once: the action ends.
      if (v_final) {
        entity.speed_command = *v_final;
      }
      arrived_ = true;
      return;
    }
    if (master.state().speed <= 1e-6) {
      return;  // the master stands: no arrival time to aim at, keep the speed
    }
    const double t_master = d_master / master.state().speed;
    entity.speed_command = planned_speed(entity.state().speed, d_own, t_master, v_final, dt);
  }

  bool finished() const override { return arrived_; }

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
  bool arrived_ = false;  ///< within a tolerance of a target: at the final speed, the action ends
};

}  // namespace

std::unique_ptr<ActionInstance> make_synchronize_action(const xosc::SynchronizeAction& action) {
  return std::make_unique<SynchronizeInstance>(action);
}

}  // namespace corsa::engine::detail
