// TeleportAction (OpenSCENARIO 1.3 §7.4.3): the actor jumps to a position, instantaneously.
// Whether it also drives the step in which it jumps the standard does not say: under the default
// controller the jump takes the whole step, at whose end the actor stands at the new position,
// as esmini reads it (esmini marks the object teleported and its default controller leaves it).
//
// A teleport assigns no longitudinal or lateral control strategy (Annex A, action tables), so
// the actions running on the actor go on from where it now is (a LaneChangeAction towards its
// target lane). esmini's reading: the teleport takes both domains, which stops those actions
// (esmini lists this among its known deviations from the standard).
//
// A RelativeLanePosition of the actor itself without offset (and dLane 0) is the actor's lane
// centre: 1.3 reads a missing offset as 0. esmini leaves the actor where it is across the lane
// (`--semantics esmini`; traj-heading-trig's car stays 0.48 m left of the centre).

#include "actions/action_makers.h"
#include "motion/placement.h"
#include "positions/position_common.h"
#include "positions/position_resolver.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class TeleportInstance final : public InstantAction {
 public:
  explicit TeleportInstance(const xosc::TeleportAction& action) : action_(action) {}
  // A teleport sets position and heading: it takes over neither speed nor lateral motion, but
  // an entity placed on a new lane keeps no lateral offset command of its old one.
  void start(ActionContext& context) override {
    const std::optional<xosc::Position> kept = esmini_in_place(context);
    const ResolvedPosition at =
        resolve_position(kept ? *kept : action_.position, context.state, context.actor);
    place_entity(context.state, context.entity(), at, action_.position.source, context.init);
    if (!context.init) {
      carry_on_or_stop(context);
    }
    const bool ideal =
        context.state.controls[*context.actor].effective() == ControllerKind::kDefault;
    if (!context.init && ideal) {
      context.entity().pose_command = context.entity().state().pose;  // held there this step
    }
  }

 private:
  // esmini's reading of a RelativeLanePosition of the actor itself without offset: the actor's
  // offset from its lane's centre stands in for the missing one (header).
  std::optional<xosc::Position> esmini_in_place(const ActionContext& context) const {
    const auto* relative = std::get_if<xosc::RelativeLanePosition>(&action_.position.kind);
    if (context.state.options.semantics != Semantics::kEsmini || context.init || !relative ||
        relative->offset || relative->d_lane != 0 ||
        relative->entity_ref != context.entity().info.name || context.state.map == nullptr) {
      return std::nullopt;
    }
    const auto& road = context.entity().state().road;
    if (!road || road->lane == 0) {
      return std::nullopt;
    }
    xosc::Position position = action_.position;
    std::get<xosc::RelativeLanePosition>(position.kind).offset =
        road->t -
        need_lane_center(*context.state.map, road->road, road->s, road->lane, relative->source);
    return position;
  }

  static void carry_on_or_stop(ActionContext& context) {
    Entity& entity = context.entity();
    if (context.state.options.semantics == Semantics::kEsmini) {
      stop_domain_owners(entity, kDomainLongitudinal | kDomainLateral);
      return;
    }
    // Copied first: an action told of the jump may end, and one may hold both domains.
    const auto owners = entity.owners;
    for (size_t slot = 0; slot < owners.size(); ++slot) {
      if (owners[slot] != nullptr && (slot == 0 || owners[slot] != owners[0])) {
        owners[slot]->actor_placed(context);
      }
    }
  }

  const xosc::TeleportAction& action_;
};

}  // namespace

std::unique_ptr<ActionInstance> make_teleport_action(const xosc::TeleportAction& action) {
  return std::make_unique<TeleportInstance>(action);
}

}  // namespace corsa::engine::detail
