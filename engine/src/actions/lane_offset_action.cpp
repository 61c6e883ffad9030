// LaneOffsetAction (OpenSCENARIO 1.3 §7.4.2.2): the actor keeps its lane but moves its lateral
// offset from the lane centre to an absolute value or to another entity's offset plus a value,
// with a dynamics shape whose duration follows from maxLateralAcc. Continuous actions keep
// tracking and never end (the standard: continuous "does not end"); `--semantics esmini` ends
// them, as esmini does, once the target is reached (its smoke test: test_maneuver_groups_x_3's
// event ends at 1.12 s, test_action_dynamics's at 25.96 s). The offset is along the lane's t-axis:
// lane coordinates are road-based (§6.3; a LanePosition's offset "in the direction of the t-axis"),
// t pointing left of the road's +s, so a positive offset is to the right of an entity driving
// toward -s (esmini reads it so too). LaneFollow::lateral, left of the direction of travel, is dir
// times it. An offset relative to the actor itself is taken from the actor's offset when the
// action starts (warned): tracked every step it would move the target with the actor, and the
// actor would drift sideways without end.

#include <cmath>
#include <numbers>
#include <optional>

#include "actions/action_makers.h"
#include "motion/transition_shape.h"
#include "positions/position_common.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

// Without maxLateralAcc the offset changes with at most this lateral acceleration (m/s^2).
constexpr double kDefaultMaxLateralAcceleration = 0.5;

// Time (s) to move `distance` metres sideways with the shape's peak lateral acceleration equal
// to `acceleration`: cubic 6 d / T^2, sinusoidal pi^2 d / (2 T^2), linear taken as
// bang-bang 4 d / T^2.
double transition_time(xosc::DynamicsShape shape, double distance, double acceleration) {
  if (distance <= 0.0 || acceleration <= 0.0) {
    return 0.0;
  }
  switch (shape) {
    case xosc::DynamicsShape::kCubic:
      return std::sqrt(6.0 * distance / acceleration);
    case xosc::DynamicsShape::kSinusoidal:
      return std::numbers::pi * std::sqrt(distance / (2.0 * acceleration));
    case xosc::DynamicsShape::kLinear:
      return std::sqrt(4.0 * distance / acceleration);
    case xosc::DynamicsShape::kStep:
      return 0.0;
  }
  return 0.0;
}

class LaneOffsetInstance final : public ActionInstance {
 public:
  explicit LaneOffsetInstance(const xosc::LaneOffsetAction& action) : action_(action) {}

  uint8_t domains() const override { return kDomainLateral; }

  void start(ActionContext& context) override {
    Entity& entity = context.entity();
    if (!entity.lane.on_road) {
      fail(action_.source, "LaneOffsetAction: entity '" + entity.info.name + "' is not on a lane");
    }
    if (const auto* relative = std::get_if<xosc::RelativeTargetLaneOffset>(&action_.target)) {
      need_entity(context.state, relative->entity_ref, relative->source);
      reference_ = *context.state.world.find(relative->entity_ref);
      if (context.actor && reference_ == *context.actor) {
        const LaneFollow& own = entity.lane;
        own_start_t_ = own.dir * own.lateral;
        context.state.diagnostics.add(relative->source.warning(
            "LaneOffsetAction of '" + entity.info.name +
            "' is relative to itself: read as relative to its offset when the action starts"));
      }
    }
    ends_when_reached_ =
        !action_.continuous || context.state.options.semantics == Semantics::kEsmini;
    start_ = entity.lane.lateral;
    start_tick_ = context.state.tick;
    const double target = target_offset(context);
    duration_ = transition_time(action_.shape, std::abs(target - start_),
                                action_.max_lateral_acc.value_or(kDefaultMaxLateralAcceleration));
    if (duration_ <= 0.0) {
      entity.lateral_command = target;
      if (context.init) {
        entity.lane.lateral = target;
      }
      reached_ = true;
    }
  }

  void step(ActionContext& context) override {
    const double target = target_offset(context);
    Entity& entity = context.entity();
    if (reached_) {
      entity.lateral_command = target;  // continuous: keep tracking
      return;
    }
    const double elapsed = context.state.time.time(context.state.tick + 1 - start_tick_);
    const double p = elapsed >= duration_ ? 1.0 : elapsed / duration_;
    entity.lateral_command = start_ + shape_value(action_.shape, p) * (target - start_);
    reached_ = p >= 1.0;
  }

  bool finished() const override { return reached_ && ends_when_reached_; }

 private:
  // The target as LaneFollow::lateral (left of the actor's direction of travel).
  double target_offset(const ActionContext& context) const {
    const int dir = context.entity().lane.dir;
    if (const auto* absolute = std::get_if<xosc::AbsoluteTargetLaneOffset>(&action_.target)) {
      return dir * absolute->value;
    }
    const auto& relative = std::get<xosc::RelativeTargetLaneOffset>(action_.target);
    const LaneFollow& reference = context.state.world.entities[reference_].lane;
    const double reference_t = own_start_t_ ? *own_start_t_ : reference.dir * reference.lateral;
    return dir * (reference_t + relative.value);  // along t, then back
  }

  const xosc::LaneOffsetAction& action_;
  uint32_t reference_ = 0;
  std::optional<double> own_start_t_;  ///< along t: the actor's own offset at the start
  bool ends_when_reached_ = true;      ///< not continuous, or continuous under Semantics::kEsmini
  double start_ = 0.0;
  int64_t start_tick_ = 0;
  double duration_ = 0.0;
  bool reached_ = false;
};

}  // namespace

std::unique_ptr<ActionInstance> make_lane_offset_action(const xosc::LaneOffsetAction& action) {
  return std::make_unique<LaneOffsetInstance>(action);
}

}  // namespace corsa::engine::detail
