// AssignControllerAction (OpenSCENARIO 1.3 §7.5.2): the actor gets a new controller, which is
// active in the domains the action's activate* attributes switch on. A Controller whose
// Properties say `corsa:controller` picks one of this engine's controllers; any other stands
// for the default controller (with a warning, once).

#include "actions/action_makers.h"
#include "controllers/controllers.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class AssignControllerInstance final : public InstantAction {
 public:
  explicit AssignControllerInstance(const xosc::AssignControllerAction& action) : action_(action) {}

  void start(ActionContext& context) override {
    ControlState& control = control_of(context.state, *context.actor);
    const xosc::ObjectController& oc = action_.controller;
    ControllerKind kind = ControllerKind::kDefault;
    if (names_external(context.state.options, oc)) {
      kind = ControllerKind::kExternal;
    } else if (!controller_kind_of(oc.controller, context.state.diagnostics, kind)) {
      context.state.diagnostics.add_once(
          "foreign-controller",
          oc.source.warning("controller '" + oc.controller.name +
                            "' is not one of this engine's (default, acc, dynamics via the "
                            "corsa:controller property): the default controller moves '" +
                            context.entity().info.name + "'"));
    }
    if (kind != control.kind) {
      control.dynamics.reset();  // a new vehicle model starts from the current motion
    }
    control.kind = kind;
    control.assigned = oc.name.value_or(oc.controller.name);
    // §7.5.2: activation as the attributes say; a 1.0-style assignment without them activates
    // nothing, which leaves the entity under the default controller until activated.
    control.longitudinal = action_.activate_longitudinal.value_or(false);
    control.lateral = action_.activate_lateral.value_or(false);
    control.animation = action_.activate_animation.value_or(false);
    control.lighting = action_.activate_lighting.value_or(false);
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
