#include "vehicle_lamps.h"

#include "corsa/sensors/material.h"

namespace corsa::sensors::detail {

VehicleLampState vehicle_lamp_state(const engine::EntitySnapshot& e, bool dark) {
  using engine::light_bit;
  using engine::VehicleLight;
  const auto role = [](LightRole r) { return 1u << static_cast<unsigned>(r); };
  VehicleLampState out;
  out.lit = e.lights_on;
  out.flashing = e.lights_flashing;
  const auto set = [&](VehicleLight v) { return (e.lights_set & light_bit(v)) != 0; };
  // The engine lights no beam of its own: unset, they follow the darkness.
  if (dark && !set(VehicleLight::kLowBeam) && !set(VehicleLight::kHighBeam)) {
    out.lit |= light_bit(VehicleLight::kLowBeam);
  }
  if (!set(VehicleLight::kReversing) && e.speed < -0.1) {
    out.lit |= light_bit(VehicleLight::kReversing);
  }
  const auto on = [&](VehicleLight v) { return (out.lit & light_bit(v)) != 0; };
  out.roles = role(LightRole::kAlways);
  if (on(VehicleLight::kLowBeam) || on(VehicleLight::kHighBeam)) {
    out.roles |= role(LightRole::kHeadlight) | role(LightRole::kTail);
  }
  if (on(VehicleLight::kDaytimeRunning)) {
    out.roles |= role(LightRole::kHeadlight);
  }
  if (on(VehicleLight::kBrake)) {
    out.roles |= role(LightRole::kBrake);
  }
  if (on(VehicleLight::kIndicatorLeft) || on(VehicleLight::kWarning)) {
    out.roles |= role(LightRole::kIndicatorLeft);
  }
  if (on(VehicleLight::kIndicatorRight) || on(VehicleLight::kWarning)) {
    out.roles |= role(LightRole::kIndicatorRight);
  }
  if (on(VehicleLight::kReversing)) {
    out.roles |= role(LightRole::kReversing);
  }
  return out;
}

}  // namespace corsa::sensors::detail
