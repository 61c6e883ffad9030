// LaneChangeAction (OpenSCENARIO 1.3 §7.4.2.1): the actor moves to an absolute lane or to a lane
// relative to an entity (RelativeTargetLane: lanes to the left, positive, of that entity's
// direction of travel), ending targetLaneOffset metres from the target lane's centre along the
// lane's t-axis (§6.3: lane coordinates are road-based, t pointing left of the road's +s; so to
// the right of an entity driving toward -s), along a TransitionDynamics shape over time,
// distance or rate (m/s of lateral speed).
//
// The default controller switches to following the target lane at once, with the lateral
// offset that keeps the entity where it is; the action then brings the offset to the target.
// The target lane is fixed when the action starts. A TeleportAction while it runs takes no
// lateral control from it (Annex A): the rest of the transition runs from where the teleport put
// the entity to the target lane there, along the rest of the shape in the time or distance left.

#include <cmath>

#include "actions/action_makers.h"
#include "corsa/core/strings.h"
#include "lanes/lane_follow.h"
#include "motion/transition_shape.h"
#include "positions/position_common.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class LaneChangeInstance final : public ActionInstance {
 public:
  explicit LaneChangeInstance(const xosc::LaneChangeAction& action) : action_(action) {}

  uint8_t domains() const override { return kDomainLateral; }

  void start(ActionContext& context) override {
    Entity& entity = context.entity();
    const xodr::Map* map = context.state.map;
    if (map == nullptr || !entity.lane.on_road) {
      fail(action_.source, "LaneChangeAction: entity '" + entity.info.name + "' is not on a lane");
    }
    LaneFollow& lane = entity.lane;
    const int target = target_lane(context);
    target_ = target;
    const auto target_center = followed_lane_center_t(*map, lane, target);
    const auto node = map->lane_graph().find(xodr::LaneRef{lane.road, lane.section, target});
    if (!target_center || !node) {
      fail(action_.source, "LaneChangeAction: road '" + map->road(lane.road).id + "' has no lane " +
                               std::to_string(target) + " at s = " + format_double(lane.s) +
                               " for entity '" + entity.info.name + "'");
    }
    const double t_now =
        followed_lane_center_t(*map, lane, lane.lane).value_or(0.0) + lane.dir * lane.lateral;
    lane.lane = target;
    lane.node = *node;
    lane.lateral = (t_now - *target_center) * lane.dir;
    start_lateral_ = lane.lateral;
    target_lateral_ = lane.dir * action_.target_lane_offset.value_or(0.0);  // t -> travel frame
    seen_shift_ = lane.frame_shift;
    entity.lateral_command = start_lateral_;
    start_tick_ = context.state.tick;
    start_distance_ = entity.longitudinal_distance;
    const xosc::TransitionDynamics& dynamics = action_.dynamics;
    total_ = dynamics.value;
    by_distance_ = dynamics.dimension == xosc::DynamicsDimension::kDistance;
    if (dynamics.dimension == xosc::DynamicsDimension::kRate) {
      // The rate (m/s) is the largest lateral speed on the way.
      total_ = dynamics.value > 0.0 ? std::abs(target_lateral_ - start_lateral_) *
                                          shape_peak_slope(dynamics.shape) / dynamics.value
                                    : 0.0;
    }
    if (dynamics.shape == xosc::DynamicsShape::kStep || total_ <= 0.0) {
      entity.lateral_command = target_lateral_;
      if (context.init) {
        lane.lateral = target_lateral_;
      }
      done_ = true;
    }
  }

  void step(ActionContext& context) override {
    if (done_) {
      return;
    }
    // A route carried the entity on from a neighbouring lane's end (LaneFollow::frame_shift):
    // the start and the target move with the followed lane's frame.
    const double shift = context.entity().lane.frame_shift - seen_shift_;
    seen_shift_ += shift;
    start_lateral_ += shift;
    target_lateral_ += shift;
    // Progress at the end of this step: time, or distance with this step's travel predicted.
    const double p = progress(context, 1);
    const double left = 1.0 - from_;
    const double part = left > 0.0 ? (shape_value(action_.dynamics.shape, p) - from_) / left : 1.0;
    context.entity().lateral_command = start_lateral_ + part * (target_lateral_ - start_lateral_);
    done_ = p >= 1.0;
  }

  void actor_placed(ActionContext& context) override {
    if (done_) {
      return;
    }
    Entity& entity = context.entity();
    LaneFollow& lane = entity.lane;
    const xodr::Map* map = context.state.map;
    std::optional<double> target_center;
    std::optional<xodr::LaneNode> node;
    if (map != nullptr && lane.on_road) {
      target_center = followed_lane_center_t(*map, lane, target_);
      node = map->lane_graph().find(xodr::LaneRef{lane.road, lane.section, target_});
    }
    if (!target_center || !node) {
      context.state.diagnostics.add(
          action_.source.warning("LaneChangeAction: the TeleportAction put entity '" +
                                 entity.info.name + "' where its road has no lane " +
                                 std::to_string(target_) + "; the lane change ends there"));
      entity.lateral_command = lane.lateral;
      done_ = true;
      return;
    }
    const double t_now =
        followed_lane_center_t(*map, lane, lane.lane).value_or(0.0) + lane.dir * lane.lateral;
    lane.lane = target_;
    lane.node = *node;
    lane.lateral = (t_now - *target_center) * lane.dir;
    entity.lateral_command = lane.lateral;
    start_lateral_ = lane.lateral;
    target_lateral_ = lane.dir * action_.target_lane_offset.value_or(0.0);
    seen_shift_ = lane.frame_shift;
    from_ = shape_value(action_.dynamics.shape, progress(context, 0));
  }

  bool finished() const override { return done_; }

 private:
  /// Share of the transition done `ahead` steps (0 or 1) after the current state: time, or
  /// distance with the coming step's travel predicted.
  double progress(const ActionContext& context, int ahead) const {
    const Entity& entity = context.entity();
    const double elapsed =
        by_distance_ ? entity.longitudinal_distance - start_distance_ +
                           ahead * std::abs(entity.state().speed) * context.state.time.dt()
                     : context.state.time.time(context.state.tick + ahead - start_tick_);
    return elapsed >= total_ ? 1.0 : elapsed / total_;
  }

  int target_lane(const ActionContext& context) const {
    if (const auto* absolute = std::get_if<xosc::AbsoluteTargetLane>(&action_.target)) {
      return parse_lane_id(absolute->value, absolute->source);
    }
    const auto& relative = std::get<xosc::RelativeTargetLane>(action_.target);
    const Entity& reference = need_entity(context.state, relative.entity_ref, relative.source);
    const Entity& actor = context.entity();
    if (!reference.lane.on_road || reference.lane.road != actor.lane.road) {
      fail(relative.source, "RelativeTargetLane: entity '" + relative.entity_ref +
                                "' is not on the same road as '" + actor.info.name + "'");
    }
    const int reference_lane =
        reference.state().road ? reference.state().road->lane : reference.lane.lane;
    // Positive values are to the left of the reference entity's direction of travel (1.3: the
    // positive y-axis of the reference entity). esmini adds the value to the lane id (1.0-1.2:
    // "Signed number of lanes that is offset the reference entity's current lane"), skipping 0:
    // the same on right lanes, the other way on left ones.
    const int toward =
        context.state.options.semantics == Semantics::kEsmini ? 1 : reference.lane.dir;
    return step_lane_id(reference_lane, relative.value * toward);
  }

  const xosc::LaneChangeAction& action_;
  int target_ = 0;
  double start_lateral_ = 0.0;
  /// Shape value (0..1) the transition was last started from: 0, or where a teleport put it.
  double from_ = 0.0;
  double target_lateral_ = 0.0;
  double seen_shift_ = 0.0;  ///< LaneFollow::frame_shift that start_ and target_ are measured in
  int64_t start_tick_ = 0;
  double start_distance_ = 0.0;
  double total_ = 0.0;
  bool by_distance_ = false;
  bool done_ = false;
};

}  // namespace

std::unique_ptr<ActionInstance> make_lane_change_action(const xosc::LaneChangeAction& action) {
  return std::make_unique<LaneChangeInstance>(action);
}

}  // namespace corsa::engine::detail
