// TeleportAction (OpenSCENARIO 1.3 §7.4.3): the actor jumps to a position, instantaneously.
// The jump is at the start of the step, which the actor then drives on from there. esmini's
// reading (Semantics::kEsmini): the jump takes the whole step, at whose end the actor stands at
// the new position (esmini marks the object teleported and its default controller leaves it).

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
    const bool ideal =
        context.state.controls[*context.actor].effective() == ControllerKind::kDefault;
    if (!context.init && ideal && context.state.options.semantics == Semantics::kEsmini) {
      context.entity().pose_command = context.entity().state.pose;  // held there this step
    }
  }

 private:
  const xosc::TeleportAction& action_;
};

}  // namespace

std::unique_ptr<ActionInstance> make_teleport_action(const xosc::TeleportAction& action) {
  return std::make_unique<TeleportInstance>(action);
}

}  // namespace corsa::engine::detail
