// AssignControllerAction (OpenSCENARIO 1.3 §7.5.2): the actor gets a new controller, which is
// active in the domains the action's activate* attributes switch on. A Controller whose
// Properties say `corsa:controller` picks one of this engine's controllers; for any other the
// acc controller stands in (substitute_controller: warned, and listed in the run summary).

#include "actions/action_makers.h"
#include "controllers/controllers.h"
#include "controllers/follow_ghost.h"
#include "controllers/sloppy_driver.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class AssignControllerInstance final : public InstantAction {
 public:
  explicit AssignControllerInstance(const xosc::AssignControllerAction& action) : action_(action) {}

  void start(ActionContext& context) override {
    if (context.state.options.disable_controllers) {
      return;  // the run ignores the scenario's controllers (SimulationOptions)
    }
    ControlState& control = control_of(context.state, *context.actor);
    const xosc::ObjectController& oc = action_.controller;
    ControllerKind kind = ControllerKind::kDefault;
    const ControllerKind before = control.kind;
    // The controller assigned so far keeps the motion domains the new one does not take, when
    // the two may share them (controllers.h, may_share_domains); otherwise the new one replaces
    // it.
    DomainPartner earlier{control.kind, control.assigned, control.longitudinal, control.lateral};
    const bool ghosted = context.state.ghost && *context.actor == context.state.ghost->entity;
    if (ghosted && !is_follow_ghost(oc)) {
      context.state.diagnostics.add(action_.source.warning(
          "'" + context.state.world.entities[*context.actor].info.name +
          "' has a ghost (followGhost): its motion actions go on to the ghost, so under this "
          "controller it performs none of them"));
    }
    if (ghosted && is_follow_ghost(oc)) {
      // esmini's followGhost again, on the entity that has the ghost: it follows the trail.
      control.kind = ControllerKind::kFollowGhost;
      control.substitute_for.clear();
    } else if (names_external(context.state.options, oc)) {
      control.kind = ControllerKind::kExternal;
      control.substitute_for.clear();
    } else if (controller_kind_of(oc.controller, context.state.diagnostics, kind)) {
      control.kind = kind;
      control.substitute_for.clear();
    } else {
      substitute_controller(context.state, *context.actor, oc);
    }
    if (control.kind != before) {
      control.dynamics.reset();  // a new vehicle model starts from the current motion
    }
    control.assigned = oc.name.value_or(oc.controller.name);
    // §7.5.2: activation as the attributes say; a 1.0-style assignment without them activates
    // nothing, which leaves the entity under the default controller until activated.
    control.longitudinal = action_.activate_longitudinal.value_or(false);
    control.lateral = action_.activate_lateral.value_or(false);
    control.animation = action_.activate_animation.value_or(false);
    control.lighting = action_.activate_lighting.value_or(false);
    if ((control.longitudinal || control.lateral) && control.sloppy &&
        control.kind == ControllerKind::kSloppyDriver) {
      activate_sloppy_driver(*control.sloppy, context.entity());
    }
    control.partner.reset();
    earlier.longitudinal = earlier.longitudinal && !control.longitudinal;
    earlier.lateral = earlier.lateral && !control.lateral;
    if ((earlier.longitudinal || earlier.lateral) && earlier.assigned != control.assigned &&
        may_share_domains(control, earlier.kind, control.kind)) {
      control.partner = earlier;
      settle_domains_at(context.state, *context.actor, action_.source);
    }
  }

 private:
  const xosc::AssignControllerAction& action_;
};

}  // namespace

std::unique_ptr<ActionInstance> make_assign_controller_action(
    const xosc::AssignControllerAction& action) {
  return std::make_unique<AssignControllerInstance>(action);
}

}  // namespace corsa::engine::detail
