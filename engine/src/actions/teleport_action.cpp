// TeleportAction (OpenSCENARIO 1.3 §7.4.3): the actor jumps to a position, instantaneously.
// Whether it also drives the step in which it jumps the standard does not say: under the default
// controller the jump takes the whole step, at whose end the actor stands at the new position,
// as esmini reads it (esmini marks the object teleported and its default controller leaves it).
//
// A teleport assigns no longitudinal or lateral control strategy (Annex A, action tables), so
// the actions running on the actor go on from where it now is (a LaneChangeAction towards its
// target lane). esmini's reading: the teleport takes both domains, which stops those actions
// (esmini lists this among its known deviations from the standard).

#include "actions/action_makers.h"
#include "motion/placement.h"
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
    const ResolvedPosition at = resolve_position(action_.position, context.state, context.actor);
    place_entity(context.state, context.entity(), at, action_.position.source, context.init);
    if (!context.init) {
      carry_on_or_stop(context);
    }
    const bool ideal =
        context.state.controls[*context.actor].effective() == ControllerKind::kDefault;
    if (!context.init && ideal) {
      context.entity().pose_command = context.entity().state.pose;  // held there this step
    }
  }

 private:
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
