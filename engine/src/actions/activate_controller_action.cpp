// ActivateControllerAction (OpenSCENARIO 1.3 §7.5.1): switches the domains of the actor's
// controller on or off; unset domains stay as they are. With every motion domain off the
// default controller moves the entity. An objectControllerRef names one of the actor's assigned
// controllers (a warning otherwise, and the action applies to its controller; none: the one
// assigned last); a domain switched
// on is taken from the other controller of a pair sharing the motion domains (ControlState::
// partner). When the action switches off the longitudinal domain of the controller that set
// the speed, and neither another controller of the scenario nor a running action sets it, the
// default controller keeps the speed the entity has then (esmini's reading; the standard says
// the default controller enforces what the actions describe, not which speed it keeps once a
// controller leaves the speed to it), not the speed an action asked for before the controller
// took over.

#include "actions/action_makers.h"
#include "controllers/alks_r157.h"
#include "controllers/controllers.h"
#include "controllers/sloppy_driver.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

// Whether a controller of the scenario (not the default controller) sets the entity's speed.
bool speed_from_scenario_controller(const ControlState& control) {
  return (control.kind != ControllerKind::kDefault && control.longitudinal) ||
         (control.partner && control.partner->kind != ControllerKind::kDefault &&
          control.partner->longitudinal);
}

class ActivateControllerInstance final : public InstantAction {
 public:
  explicit ActivateControllerInstance(const xosc::ActivateControllerAction& action)
      : action_(action) {}

  void start(ActionContext& context) override {
    ControlState& control = control_of(context.state, *context.actor);
    // The controller named, else the one assigned last.
    const bool to_partner =
        control.partner && (action_.object_controller_ref
                                ? *action_.object_controller_ref == control.partner->assigned &&
                                      *action_.object_controller_ref != control.assigned
                                : control.partner->assigned_last);
    if (to_partner) {
      swap_with_partner(control);  // the controller named is the one the action switches
    }
    const bool sets_speed = control.kind != ControllerKind::kDefault && control.longitudinal;
    if (action_.object_controller_ref && !control.assigned.empty() &&
        *action_.object_controller_ref != control.assigned) {
      context.state.diagnostics.add_once(
          "activate-controller-ref:" + *action_.object_controller_ref,
          action_.source.warning("'" + context.entity().info.name + "' has controller '" +
                                 control.assigned + "', not '" + *action_.object_controller_ref +
                                 "'"));
    }
    if (action_.longitudinal) control.longitudinal = *action_.longitudinal;
    if (action_.longitudinal.value_or(false) && control.alks &&
        control.kind == ControllerKind::kAlksR157) {
      activate_alks_r157(*control.alks);  // its set speed: the speed it then has
    }
    if (action_.lateral) control.lateral = *action_.lateral;
    if ((action_.longitudinal.value_or(false) || action_.lateral.value_or(false)) &&
        control.sloppy && control.kind == ControllerKind::kSloppyDriver) {
      // esmini's Activate: its timers and offsets start again, its reference speed the speed
      // the entity then has.
      activate_sloppy_driver(*control.sloppy, context.entity());
    }
    if (control.partner) {
      // A domain switched on is taken from the other controller (esmini deactivates the
      // controller active there first).
      if (action_.longitudinal.value_or(false)) control.partner->longitudinal = false;
      if (action_.lateral.value_or(false)) control.partner->lateral = false;
      settle_domains_at(context.state, *context.actor, action_.source);
    }
    Entity& entity = context.entity();
    if (sets_speed && !action_.longitudinal.value_or(true) &&
        !speed_from_scenario_controller(control) && entity.owners[0] == nullptr) {
      entity.speed_command = entity.state().speed;  // slot 0: the longitudinal domain
    }
    if (action_.animation) control.animation = *action_.animation;
    if (action_.lighting) control.lighting = *action_.lighting;
    if (context.state.ghost && *context.actor == context.state.ghost->entity &&
        control.kind == ControllerKind::kFollowGhost && !control.longitudinal && !control.lateral) {
      // esmini's followGhost switched off (controllers/follow_ghost.h): the default controller
      // keeps the entity's speed and lane, its motion actions still going to the ghost; a later
      // activation follows the trail again from where the entity is then.
      context.state.diagnostics.add(action_.source.warning(
          "followGhost of '" + context.entity().info.name +
          "' deactivated: its motion actions go on to its ghost, and it keeps its speed and lane "
          "until the controller is activated again"));
    }
  }

 private:
  const xosc::ActivateControllerAction& action_;
};

}  // namespace

std::unique_ptr<ActionInstance> make_activate_controller_action(
    const xosc::ActivateControllerAction& action) {
  return std::make_unique<ActivateControllerInstance>(action);
}

}  // namespace corsa::engine::detail
