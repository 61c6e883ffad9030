// LightStateAction (OpenSCENARIO 1.2 §7.4.3.5): switches one of the actor's vehicle lights on,
// off or flashing, at a luminous intensity (cd) and in a colour when the LightState gives them,
// fading linearly over transitionTime from the light's state before; the world snapshot carries
// it to the sensors (EntitySnapshot::lights_on, lights_set, light_looks). User-defined light
// types warn once.

#include <array>
#include <memory>
#include <optional>
#include <variant>

#include "actions/action_makers.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

// The class model's default for flashingOnDuration and flashingOffDuration, in seconds.
constexpr double kLightDefaultFlashS = 0.5;

/// A LightState Color as linear RGB: ColorRgb as given, ColorCmyk converted (r = (1 - c)(1 - k)),
/// a colorType alone as its usual RGB; "other" without values keeps the lamp's colour.
std::optional<std::array<double, 3>> light_rgb(const xosc::Color& color) {
  if (color.value) {
    if (const auto* rgb = std::get_if<xosc::ColorRgb>(&*color.value)) {
      return std::array<double, 3>{rgb->red, rgb->green, rgb->blue};
    }
    const auto& c = std::get<xosc::ColorCmyk>(*color.value);
    return std::array<double, 3>{(1.0 - c.cyan) * (1.0 - c.key), (1.0 - c.magenta) * (1.0 - c.key),
                                 (1.0 - c.yellow) * (1.0 - c.key)};
  }
  using T = xosc::ColorType;
  switch (color.type) {
    case T::kRed:
      return std::array<double, 3>{1.0, 0.0, 0.0};
    case T::kYellow:
      return std::array<double, 3>{1.0, 1.0, 0.0};
    case T::kGreen:
      return std::array<double, 3>{0.0, 1.0, 0.0};
    case T::kBlue:
      return std::array<double, 3>{0.0, 0.0, 1.0};
    case T::kViolet:
      return std::array<double, 3>{0.5, 0.0, 1.0};
    case T::kOrange:
      return std::array<double, 3>{1.0, 0.5, 0.0};
    case T::kBrown:
      return std::array<double, 3>{0.6, 0.3, 0.1};
    case T::kBlack:
      return std::array<double, 3>{0.0, 0.0, 0.0};
    case T::kGrey:
      return std::array<double, 3>{0.5, 0.5, 0.5};
    case T::kWhite:
      return std::array<double, 3>{1.0, 1.0, 1.0};
    case T::kOther:
      return std::nullopt;
  }
  return std::nullopt;
}

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
    setting.mode = state.mode == xosc::LightMode::kOff  ? LightMode::kOff
                   : state.mode == xosc::LightMode::kOn ? LightMode::kOn
                                                        : LightMode::kFlashing;
    // Without durations a flashing light is on and off 0.5 s each, the class model's default
    // for both (1 Hz, within UN ECE R48's 90 +- 30 flashes per minute at its lower end).
    setting.on_s = state.flashing_on_duration.value_or(kLightDefaultFlashS);
    setting.off_s = state.flashing_off_duration.value_or(kLightDefaultFlashS);
    if (!(setting.on_s > 0.0) || !(setting.off_s >= 0.0)) {
      context.state.diagnostics.add_once(
          "light-state-durations",
          action_.source.warning("LightStateAction: flashing durations must be positive; "
                                 "using 0.5 s on and off"));
      setting.on_s = setting.off_s = kLightDefaultFlashS;
    }
    setting.since = context.state.now();
    setting.candela = state.luminous_intensity;
    if (state.color) {
      setting.rgb = light_rgb(*state.color);
    }
    setting.transition_s = action_.transition_time.value_or(0.0);
    const auto index = static_cast<size_t>(*type);
    if (index < kVehicleLightCount) {
      context.state.light_changes.push_back(
          {*context.actor, setting.view(static_cast<VehicleLight>(index))});
      auto& lights = context.entity().lights;
      if (!lights) {
        lights = std::make_unique<LightSettings>();
      }
      std::optional<LightSetting>& slot = (*lights)[index];
      if (setting.transition_s > 0.0 && slot) {
        // A fade starts from whatever the light shows now, itself perhaps still fading.
        setting.previous = std::make_shared<const LightSetting>(std::move(*slot));
      }
      slot = std::move(setting);
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
