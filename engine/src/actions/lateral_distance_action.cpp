// LateralDistanceAction (OpenSCENARIO 1.3 §7.4.2.3): the actor keeps a lateral distance to a
// reference entity, across the reference's direction of travel, to its left or right
// (displacement; `any` keeps the side it is on when the action starts), between reference
// points or, with freespace, bounding boxes. Without a distance it keeps the one it has.
//
// The actor moves sideways within its lane frame (its lateral offset) at a lateral speed
// proportional to the error (kGain per second), capped by DynamicConstraints maxSpeed (lateral
// m/s, default kDefaultLateralSpeed) and changed by at most maxAcceleration (lateral m/s^2,
// default kDefaultLateralAcc) per second, when DynamicConstraints are given. Without them the
// dynamics are unlimited (the class model: "unlimited dynamics (if omitted)"): the actor is put
// at the wanted lateral distance at once (in Init before time starts) and follows the
// reference's lateral motion exactly while continuous. Without `continuous` it ends within
// kTolerance.

#include <algorithm>
#include <cmath>

#include "actions/action_makers.h"
#include "motion/controller.h"
#include "positions/position_common.h"
#include "positions/relative_distance.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

constexpr double kGain = 1.0;                 // 1/s
constexpr double kDefaultLateralSpeed = 1.0;  // m/s
constexpr double kDefaultLateralAcc = 2.0;    // m/s^2
constexpr double kTolerance = 0.02;           // m

class LateralDistanceInstance final : public ActionInstance {
 public:
  explicit LateralDistanceInstance(const xosc::LateralDistanceAction& action) : action_(action) {}

  uint8_t domains() const override { return kDomainLateral; }

  void start(ActionContext& context) override {
    need_entity(context.state, action_.entity_ref, action_.source);
    reference_ = *context.state.world.find(action_.entity_ref);
    const double now = offset(context);
    const auto displacement = action_.displacement.value_or(xosc::LateralDisplacement::kAny);
    if (displacement == xosc::LateralDisplacement::kAny) {
      side_ = now >= 0.0 ? 1 : -1;
    } else {
      side_ = displacement == xosc::LateralDisplacement::kLeftToReferencedEntity ? 1 : -1;
    }
    wanted_ = action_.distance ? *action_.distance : std::abs(now);
    if (action_.constraints) {
      max_speed_ = action_.constraints->max_speed.value_or(max_speed_);
      max_acc_ = action_.constraints->max_acceleration.value_or(max_acc_);
    } else if (context.init) {
      // Unlimited, before time starts: at the wanted offset from the first recorded state on.
      Entity& entity = context.entity();
      entity.lane.lateral += lane_frame_sign(context) * (side_ * wanted_ - now);
      entity.lateral_command = entity.lane.lateral;
      if (context.state.map != nullptr && entity.lane.on_road) {
        std::vector<xodr::LaneSpan> scratch;
        update_pose_from_lane(entity, *context.state.map, scratch);
      }
    }
  }

  void step(ActionContext& context) override {
    Entity& entity = context.entity();
    const double dt = context.state.time.dt();
    // Error across the reference (left positive); turned into the actor's lane frame, whose
    // left is the reference's left when both drive the same way.
    const double error = side_ * wanted_ - offset(context);
    const double same_way = lane_frame_sign(context);
    settled_ = !action_.continuous && std::abs(error) < kTolerance;
    if (!action_.constraints) {
      entity.lateral_command = entity.lane.lateral + same_way * error;  // in this one step
      return;
    }
    const double want_speed = std::clamp(kGain * error, -max_speed_, max_speed_);
    rate_ = std::clamp(want_speed, rate_ - max_acc_ * dt, rate_ + max_acc_ * dt);
    entity.lateral_command = entity.lane.lateral + same_way * rate_ * dt;
  }

  bool finished() const override { return settled_; }

 private:
  // +1 when the actor's lane frame has the reference's left as its left (both drive the same
  // way), -1 otherwise.
  double lane_frame_sign(const ActionContext& context) const {
    const Entity& reference = context.state.world.entities[reference_];
    return std::cos(context.entity().state().pose.h - reference.state().pose.h) >= 0.0 ? 1.0 : -1.0;
  }

  // The actor's lateral position relative to the reference, left of it positive.
  double offset(const ActionContext& context) const {
    DistanceSpec spec;
    spec.system = action_.coordinate_system.value_or(xosc::CoordinateSystem::kEntity);
    spec.type = xosc::RelativeDistanceType::kLateral;
    spec.freespace = action_.freespace;
    return entity_distance(context.state, context.state.world.entities[reference_],
                           context.entity(), spec);
  }

  const xosc::LateralDistanceAction& action_;
  uint32_t reference_ = 0;
  int side_ = 1;  ///< +1 left of the reference, -1 right
  double wanted_ = 0.0;
  double max_speed_ = kDefaultLateralSpeed;
  double max_acc_ = kDefaultLateralAcc;
  double rate_ = 0.0;  ///< m/s, current lateral speed toward the reference's left
  bool settled_ = false;
};

}  // namespace

std::unique_ptr<ActionInstance> make_lateral_distance_action(
    const xosc::LateralDistanceAction& action) {
  return std::make_unique<LateralDistanceInstance>(action);
}

}  // namespace corsa::engine::detail
