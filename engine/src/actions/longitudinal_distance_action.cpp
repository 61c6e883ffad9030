// LongitudinalDistanceAction (OpenSCENARIO 1.3 §7.4.1.2): the actor keeps a distance (m) or a
// time gap (s, times the follower's speed) to a reference entity along the reference's direction of
// travel, trailing or leading it (displacement; `any` keeps the side it is on when the action
// starts). The gap is measured between reference points or, with freespace, bounding boxes.
//
// The ideal controller asks for the reference's speed plus a correction that closes the gap
// error e: kOmega * e near the goal, at most sqrt(2 b |e|) far from it (b = kBrakeShare of the
// weaker of the acceleration limits), so that the approach can always be stopped in time
// within the limits; the speed tracks that with gain 4 kOmega (together a critically damped
// approach near the goal). Acceleration and speed stay within the DynamicConstraints.
// Without `continuous` the action ends once the gap is within kGapTolerance and the speeds match
// within kSpeedTolerance.
//
// Without DynamicConstraints the dynamics are unlimited (the class model: "either unlimited
// dynamics (if omitted) or limited maxAcceleration/maxDeceleration/maxSpeed"): the actor is put
// at the wanted gap at once, moved along its lanes, and takes the reference's speed, so that
// the gap holds. In Init this happens before time starts (ASAM's ALKS scenarios place their
// lead vehicle so, "the LongitudinalDistanceAction will position the Lead vehicle precisely").
// Without `continuous` it then ends; with it, it holds the gap so every step. esmini does the
// same (LongDistanceAction::Step: MoveAlongS by the gap error, the target's speed copied).

#include <cmath>

#include "actions/action_makers.h"
#include "actions/dynamic_limits.h"
#include "lanes/lane_follow.h"
#include "motion/controller.h"
#include "positions/position_common.h"
#include "positions/relative_distance.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

constexpr double kOmega = 1.0;  // rad/s
constexpr double kBrakeShare = 0.8;
constexpr double kGapTolerance = 0.1;     // m
constexpr double kSpeedTolerance = 0.05;  // m/s
// The unlimited placement measures again after a move (free-space gaps stay 0 while the boxes
// overlap, and curved lanes make the measured gap differ from the distance moved).
constexpr int kPlacementPasses = 4;
constexpr double kPlacementTolerance = 1e-3;  // m

class LongitudinalDistanceInstance final : public ActionInstance {
 public:
  explicit LongitudinalDistanceInstance(const xosc::LongitudinalDistanceAction& action)
      : action_(action) {}

  uint8_t domains() const override { return kDomainLongitudinal; }

  void start(ActionContext& context) override {
    need_entity(context.state, action_.entity_ref, action_.source);
    reference_ = *context.state.world.find(action_.entity_ref);
    if (!action_.distance && !action_.time_gap) {
      fail(action_.source, "LongitudinalDistanceAction needs a distance or a timeGap");
    }
    limits_ = speed_limits(context.entity(), action_.constraints);
    const auto displacement =
        action_.displacement.value_or(xosc::LongitudinalDisplacement::kTrailingReferencedEntity);
    if (displacement == xosc::LongitudinalDisplacement::kAny) {
      side_ = signed_offset(context) <= 0.0 ? 1 : -1;
    } else {
      side_ = displacement == xosc::LongitudinalDisplacement::kTrailingReferencedEntity ? 1 : -1;
    }
    if (!action_.constraints && context.init) {
      place_at_gap(context);  // before time starts; the first step places it again and ends
    }
  }

  [[gnu::hot]] void step(ActionContext& context) override {
    if (!action_.constraints) {
      place_at_gap(context);
      settled_ = !action_.continuous;
      return;
    }
    Entity& entity = context.entity();
    const Entity& reference = context.state.world.entities[reference_];
    const double v = entity.state().speed;
    const double v_ref = reference.state().speed;
    // A time gap is the follower's: the actor's speed when it trails, the reference's when it
    // leads.
    const double wanted =
        action_.distance ? *action_.distance : *action_.time_gap * (side_ > 0 ? v : v_ref);
    // The gap on the wanted side (negative when the actor is on the other side).
    const double gap = -side_ * step_offset(context);
    const double error = gap - wanted;
    const double brake = kBrakeShare * std::min(limits_.acceleration, limits_.deceleration);
    const double correction = std::copysign(
        std::min(kOmega * std::abs(error), std::sqrt(2.0 * brake * std::abs(error))), error);
    const double accel = 4.0 * kOmega * (v_ref + side_ * correction - v);
    const double dt = context.state.time.dt();
    const double speed = std::max(0.0, limits_.step_toward(v, v + accel * dt, dt));
    entity.speed_command = speed;
    settled_ = !action_.continuous && std::abs(error) < kGapTolerance &&
               std::abs(speed - v_ref) < kSpeedTolerance;
  }

  bool finished() const override { return settled_; }

 private:
  // Unlimited dynamics: the actor moves along its lanes (or its heading, off them) until the gap
  // is the wanted one, and drives on at the reference's speed.
  void place_at_gap(ActionContext& context) const {
    Entity& entity = context.entity();
    const Entity& reference = context.state.world.entities[reference_];
    const double v_ref = reference.state().speed;
    // Both drive at v_ref afterwards, so the follower's speed of a time gap is v_ref.
    const double wanted = action_.distance ? *action_.distance : *action_.time_gap * v_ref;
    for (int pass = 0; pass < kPlacementPasses; ++pass) {
      const double error = -side_ * signed_offset(context) - wanted;
      if (std::abs(error) < kPlacementTolerance) break;
      // Closing the gap moves the actor toward the reference's front when it trails (side +1).
      const double same_way =
          std::cos(entity.state().pose.h - reference.state().pose.h) >= 0.0 ? 1.0 : -1.0;
      move_along(context, side_ * same_way * error);
    }
    entity.speed_command = v_ref;
    if (context.init) {
      entity.write_state().speed = v_ref;
    }
  }

  // Moves the actor `distance` metres forward (negative: back) along its lanes or its heading.
  static void move_along(ActionContext& context, double distance) {
    Entity& entity = context.entity();
    const xodr::Map* map = context.state.map;
    if (map != nullptr && entity.lane.on_road) {
      advance_along_lanes(*map, entity.lane, distance, entity.chooser);
      std::vector<xodr::LaneSpan> scratch;
      update_pose_from_lane(entity, *map, scratch);
      return;
    }
    entity.write_state().pose.x += distance * std::cos(entity.state().pose.h);
    entity.write_state().pose.y += distance * std::sin(entity.state().pose.h);
    update_road_from_pose(entity, map);
  }

  // Where the actor is relative to the reference along the reference's travel direction: > 0
  // ahead of it. Freespace: between the boxes (0 while they overlap lengthwise).
  double signed_offset(const ActionContext& context) const {
    const Entity& reference = context.state.world.entities[reference_];
    DistanceSpec spec;
    spec.system = action_.coordinate_system.value_or(xosc::CoordinateSystem::kEntity);
    spec.type = xosc::RelativeDistanceType::kLongitudinal;
    spec.freespace = action_.freespace;
    return entity_distance(context.state, reference, context.entity(), spec);
  }

  // signed_offset for a step: measured again only when what it reads has changed since the
  // last step's (a continuous action behind a standing reference asks the same every step).
  double step_offset(const ActionContext& context) {
    const Entity& reference = context.state.world.entities[reference_];
    if (!offset_inputs_.same_as(reference, context.entity())) {
      offset_ = signed_offset(context);
      offset_inputs_.take(reference, context.entity());
    }
    return offset_;
  }

  const xosc::LongitudinalDistanceAction& action_;
  uint32_t reference_ = 0;
  EntityDistanceInputs offset_inputs_;  ///< what step_offset's offset_ was measured from
  double offset_ = 0.0;
  SpeedLimits limits_;
  int side_ = 1;  ///< +1 trailing the reference, -1 leading it
  bool settled_ = false;
};

}  // namespace

std::unique_ptr<ActionInstance> make_longitudinal_distance_action(
    const xosc::LongitudinalDistanceAction& action) {
  return std::make_unique<LongitudinalDistanceInstance>(action);
}

}  // namespace corsa::engine::detail
