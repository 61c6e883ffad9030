// OverrideControllerValueAction (OpenSCENARIO 1.3 §7.5.3): throttle, brake, clutch, parking
// brake, steering wheel and gear values that replace the driver's while active. They are kept
// on the actor's control state; the dynamics controller applies them (with their maxRate). The
// ideal controllers have no pedals or steering wheel: a warning says so, once.

#include "actions/action_makers.h"
#include "controllers/controllers.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

void set(OverrideSlot& slot, const std::optional<xosc::OverrideValue>& value) {
  if (value) {
    slot.active = value->active;
    slot.value = value->value;
    slot.force = false;
    slot.max_rate = value->max_rate.value_or(0.0);
  }
}

void set(OverrideSlot& slot, const std::optional<xosc::OverrideBrake>& value) {
  if (value) {
    slot.active = value->active;
    slot.value = value->value.value_or(0.0);
    slot.force = value->force;
    slot.max_rate = value->max_rate.value_or(0.0);
  }
}

class OverrideControllerInstance final : public InstantAction {
 public:
  explicit OverrideControllerInstance(const xosc::OverrideControllerValueAction& action)
      : action_(action) {}

  void start(ActionContext& context) override {
    ControlState& control = control_of(context.state, *context.actor);
    ControllerOverrides& o = control.overrides;
    set(o.throttle, action_.throttle);
    set(o.brake, action_.brake);
    set(o.clutch, action_.clutch);
    set(o.parking_brake, action_.parking_brake);
    if (action_.steering_wheel) {
      o.steering_wheel.active = action_.steering_wheel->active;
      o.steering_wheel.value = action_.steering_wheel->value;
      o.steering_wheel.max_rate = action_.steering_wheel->max_rate.value_or(0.0);
    }
    if (action_.gear) {
      o.gear_active = action_.gear->active;
      if (action_.gear->gear) {
        if (const auto* manual = std::get_if<xosc::ManualGear>(&*action_.gear->gear)) {
          o.gear = manual->number;
        } else {
          const auto automatic = std::get<xosc::AutomaticGear>(*action_.gear->gear).gear;
          o.gear = automatic == xosc::AutomaticGearType::kR   ? -1
                   : automatic == xosc::AutomaticGearType::kD ? 1
                                                              : 0;
        }
      }
    }
    if (control.effective() != ControllerKind::kDynamics && o.any()) {
      context.state.diagnostics.add_once(
          "override-without-dynamics",
          action_.source.warning("'" + context.entity().info.name +
                                 "' is not under the dynamics controller: its overridden "
                                 "pedal, steering and gear values are kept but have no effect"));
    }
  }

 private:
  const xosc::OverrideControllerValueAction& action_;
};

}  // namespace

std::unique_ptr<ActionInstance> make_override_controller_action(
    const xosc::OverrideControllerValueAction& action) {
  return std::make_unique<OverrideControllerInstance>(action);
}

}  // namespace corsa::engine::detail
