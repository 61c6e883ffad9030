// LightStateAction (OpenSCENARIO 1.2 §7.4.3.5): switches one of the actor's vehicle lights on,
// off or flashing; the world snapshot carries it to the sensors (EntitySnapshot::lights_on,
// lights_set). The transition time, luminous intensity and colour are not modelled (the light
// switches at once, with the renderer's lamp colour); user-defined light types warn once.

#include <memory>
#include <variant>

#include "actions/action_makers.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class LightStateInstance final : public InstantAction {
 public:
  explicit LightStateInstance(const xosc::LightStateAction& action) : action_(action) {}
  void start(ActionContext& context) override {
    const auto* type = std::get_if<xosc::VehicleLightType>(&action_.light_type);
    if (type == nullptr) {
      context.state.diagnostics.add_once(
          "light-state-user-defined",
          action_.source.warning("LightStateAction: user-defined light type '" +
                                 std::get<std::string>(action_.light_type) +
                                 "' is not drawn by the sensors"));
      return;
    }
    const xosc::LightState& state = action_.light_state;
    LightSetting setting;
    setting.mode = state.mode == xosc::LightMode::kOff  ? LightSetting::Mode::kOff
                   : state.mode == xosc::LightMode::kOn ? LightSetting::Mode::kOn
                                                        : LightSetting::Mode::kFlashing;
    // Without durations a flashing light blinks at 1.5 Hz, the middle of UN ECE R48's
    // 90 +- 30 flashes per minute.
    setting.on_s = state.flashing_on_duration.value_or(1.0 / 3.0);
    setting.off_s = state.flashing_off_duration.value_or(1.0 / 3.0);
    if (!(setting.on_s > 0.0) || !(setting.off_s >= 0.0)) {
      context.state.diagnostics.add_once(
          "light-state-durations",
          action_.source.warning("LightStateAction: flashing durations must be positive; "
                                 "using 1/3 s on and off"));
      setting.on_s = setting.off_s = 1.0 / 3.0;
    }
    setting.since = context.state.now();
    const auto index = static_cast<size_t>(*type);
    if (index < kVehicleLightCount) {
      auto& lights = context.entity().lights;
      if (!lights) {
        lights = std::make_unique<LightSettings>();
      }
      (*lights)[index] = setting;
    }
  }

 private:
  const xosc::LightStateAction& action_;
};

}  // namespace

std::unique_ptr<ActionInstance> make_light_state_action(const xosc::LightStateAction& action) {
  return std::make_unique<LightStateInstance>(action);
}

}  // namespace corsa::engine::detail
