// Controller, appearance and trailer actions (§7.4.5, §7.4.7, §7.4.8).

#include <limits>

#include "parsers.h"

namespace corsa::xosc {
namespace {

OverrideValue parse_override_value(ParseContext& ctx, const Element* e, const char* type) {
  Children(ctx, e, type);
  return OverrideValue{ctx.req_bool(e, "active"), ctx.req_double(e, "value"),
                       ctx.opt_double(e, "maxRate"), ctx.source(e)};
}

OverrideBrake parse_override_brake(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "OverrideBrakeAction");
  OverrideBrake brake;
  brake.active = ctx.req_bool(e, "active");
  const Element* percent = kids.opt("BrakePercent");
  const Element* force = kids.opt("BrakeForce");
  if (percent != nullptr && force != nullptr) {
    ctx.fail(e, "a brake override takes BrakePercent or BrakeForce, not both");
  }
  if (const Element* input = percent != nullptr ? percent : force) {
    Children(ctx, input, "Brake");
    brake.force = input == force;
    brake.value = ctx.req_double(input, "value");
    brake.max_rate = ctx.opt_double(input, "maxRate");
  }
  if (deprecated_attribute(ctx, e, "value", {"BrakePercent", "BrakeForce"}) && percent == nullptr &&
      force == nullptr) {
    brake.value = ctx.opt_double(e, "value");
  }
  brake.source = ctx.source(e);
  return brake;
}

OverrideGear parse_override_gear(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "OverrideGearAction");
  OverrideGear gear;
  gear.active = ctx.req_bool(e, "active");
  const Element* manual = kids.opt("ManualGear");
  const Element* automatic = kids.opt("AutomaticGear");
  if (manual != nullptr && automatic != nullptr) {
    ctx.fail(e, "a gear override takes ManualGear or AutomaticGear, not both");
  }
  if (manual != nullptr) {
    Children(ctx, manual, "ManualGear");
    gear.gear = ManualGear{static_cast<int>(ctx.req_int(manual, "number"))};
  } else if (automatic != nullptr) {
    Children(ctx, automatic, "AutomaticGear");
    gear.gear = AutomaticGear{ctx.req_enum<AutomaticGearType>(automatic, "gear")};
  }
  if (deprecated_attribute(ctx, e, "number", {"ManualGear", "AutomaticGear"}) &&
      manual == nullptr && automatic == nullptr) {
    gear.gear = ManualGear{static_cast<int>(ctx.opt_double(e, "number").value_or(0.0))};
  }
  gear.source = ctx.source(e);
  return gear;
}

OverrideControllerValueAction parse_override(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "OverrideControllerValueAction");
  OverrideControllerValueAction action;
  if (const Element* x = kids.opt("Throttle")) {
    action.throttle = parse_override_value(ctx, x, "OverrideThrottleAction");
  }
  if (const Element* x = kids.opt("Brake")) action.brake = parse_override_brake(ctx, x);
  if (const Element* x = kids.opt("Clutch")) {
    action.clutch = parse_override_value(ctx, x, "OverrideClutchAction");
  }
  if (const Element* x = kids.opt("ParkingBrake")) {
    action.parking_brake = parse_override_brake(ctx, x);
  }
  if (const Element* x = kids.opt("SteeringWheel")) {
    Children(ctx, x, "OverrideSteeringWheelAction");
    action.steering_wheel = OverrideSteeringWheel{
        ctx.req_bool(x, "active"), ctx.req_double(x, "value"), ctx.opt_double(x, "maxRate"),
        ctx.opt_double(x, "maxTorque"), ctx.source(x)};
  }
  if (const Element* x = kids.opt("Gear")) action.gear = parse_override_gear(ctx, x);
  action.source = ctx.source(e);
  return action;
}

AssignControllerAction parse_assign_controller(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "AssignControllerAction");
  AssignControllerAction action;
  action.activate_lateral = ctx.opt_bool(e, "activateLateral");
  action.activate_longitudinal = ctx.opt_bool(e, "activateLongitudinal");
  action.activate_animation = ctx.opt_bool(e, "activateAnimation");
  action.activate_lighting = ctx.opt_bool(e, "activateLighting");
  const Element* which = kids.choice();
  if (std::string_view(which->Name()) == "ObjectController") {
    action.controller = parse_object_controller(ctx, which);
  } else {
    ctx.deprecated(which,
                   "<" + std::string(which->Name()) + "> directly in <AssignControllerAction>",
                   "<ObjectController>");
    action.controller.controller = parse_controller_choice(ctx, which);
    action.controller.source = ctx.source(which);
  }
  action.source = ctx.source(e);
  return action;
}

constexpr double kNoLimit = std::numeric_limits<double>::infinity();

/// OpenSCENARIO 1.2 LightState: luminousIntensity (cd) and transitionTime (s) range over
/// [0..inf[, the ColorRgb and ColorCmyk components over [0..1].
void check_light_value(ParseContext& ctx, const Element* e, const char* name,
                       std::optional<double> value, double max) {
  if (value && !(*value >= 0.0 && *value <= max)) {
    ctx.error(e, std::string(name) + " " + format_double(*value) +
                     (max < 2.0 ? " is outside [0, 1]" : " must not be negative"));
  }
}

LightStateAction parse_light_state_action(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "LightStateAction");
  LightStateAction action;
  action.transition_time = ctx.opt_double(e, "transitionTime");
  check_light_value(ctx, e, "transitionTime", action.transition_time, kNoLimit);
  const Element* type = kids.one("LightType");
  Children type_kids(ctx, type, "LightType");
  const Element* t = type_kids.choice();
  if (std::string_view(t->Name()) == "VehicleLight") {
    Children(ctx, t, "VehicleLight");
    action.light_type = ctx.req_enum<VehicleLightType>(t, "vehicleLightType");
  } else {
    Children(ctx, t, "UserDefinedLight");
    action.light_type = ctx.req_str(t, "userDefinedLightType");
  }
  const Element* state = kids.one("LightState");
  Children state_kids(ctx, state, "LightState");
  LightState& light = action.light_state;
  light.mode = ctx.req_enum<LightMode>(state, "mode");
  light.luminous_intensity = ctx.opt_double(state, "luminousIntensity");
  light.flashing_on_duration = ctx.opt_double(state, "flashingOnDuration");
  light.flashing_off_duration = ctx.opt_double(state, "flashingOffDuration");
  check_light_value(ctx, state, "luminousIntensity", light.luminous_intensity, kNoLimit);
  if (const Element* color = state_kids.opt("Color")) {
    Children color_kids(ctx, color, "Color");
    Color value;
    value.type = ctx.req_enum<ColorType>(color, "colorType");
    if (const Element* rgb = color_kids.opt("ColorRgb")) {
      Children(ctx, rgb, "ColorRgb");
      const ColorRgb c{ctx.req_double(rgb, "red"), ctx.req_double(rgb, "green"),
                       ctx.req_double(rgb, "blue")};
      check_light_value(ctx, rgb, "red", c.red, 1.0);
      check_light_value(ctx, rgb, "green", c.green, 1.0);
      check_light_value(ctx, rgb, "blue", c.blue, 1.0);
      value.value = c;
    } else if (const Element* cmyk = color_kids.opt("ColorCmyk")) {
      Children(ctx, cmyk, "ColorCmyk");
      const ColorCmyk c{ctx.req_double(cmyk, "cyan"), ctx.req_double(cmyk, "magenta"),
                        ctx.req_double(cmyk, "yellow"), ctx.req_double(cmyk, "key")};
      check_light_value(ctx, cmyk, "cyan", c.cyan, 1.0);
      check_light_value(ctx, cmyk, "magenta", c.magenta, 1.0);
      check_light_value(ctx, cmyk, "yellow", c.yellow, 1.0);
      check_light_value(ctx, cmyk, "key", c.key, 1.0);
      value.value = c;
    }
    value.source = ctx.source(color);
    light.color = value;
  }
  light.source = ctx.source(state);
  action.source = ctx.source(e);
  return action;
}

AnimationType parse_animation_type(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "AnimationType");
  const Element* a = kids.choice();
  const std::string_view name = a->Name();
  if (name == "ComponentAnimation") {
    Children component_kids(ctx, a, "ComponentAnimation");
    const Element* c = component_kids.choice();
    ComponentAnimation animation;
    if (std::string_view(c->Name()) == "VehicleComponent") {
      Children(ctx, c, "VehicleComponent");
      animation.component = ctx.req_enum<VehicleComponentType>(c, "vehicleComponentType");
    } else {
      Children(ctx, c, "UserDefinedComponent");
      animation.component = ctx.req_str(c, "userDefinedComponentType");
    }
    animation.source = ctx.source(a);
    return animation;
  }
  if (name == "PedestrianAnimation") {
    Children pedestrian_kids(ctx, a, "PedestrianAnimation");
    PedestrianAnimation animation;
    animation.motion = ctx.opt_enum<PedestrianMotionType>(a, "motion");
    animation.user_defined_pedestrian_animation = ctx.opt_str(a, "userDefinedPedestrianAnimation");
    for (const Element* gesture : pedestrian_kids.all("PedestrianGesture")) {
      Children(ctx, gesture, "PedestrianGesture");
      animation.gestures.push_back(ctx.req_enum<PedestrianGestureType>(gesture, "gesture"));
    }
    animation.source = ctx.source(a);
    return animation;
  }
  if (name == "AnimationFile") {
    Children file_kids(ctx, a, "AnimationFile");
    return AnimationFile{parse_file(ctx, file_kids.one("File")), ctx.opt_double(a, "timeOffset"),
                         ctx.source(a)};
  }
  Children(ctx, a, "UserDefinedAnimation");
  return UserDefinedAnimation{ctx.req_str(a, "userDefinedAnimationType"), ctx.source(a)};
}

AnimationAction parse_animation_action(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "AnimationAction");
  AnimationAction action;
  action.animation_type = parse_animation_type(ctx, kids.one("AnimationType"));
  if (const Element* state = kids.opt("AnimationState")) {
    Children(ctx, state, "AnimationState");
    action.state = ctx.req_double(state, "state");
  }
  action.loop = ctx.opt_bool(e, "loop");
  action.animation_duration = ctx.opt_double(e, "animationDuration");
  action.source = ctx.source(e);
  return action;
}

}  // namespace

ActivateControllerAction parse_activate_controller(ParseContext& ctx, const Element* e) {
  Children(ctx, e, "ActivateControllerAction");
  ActivateControllerAction action;
  action.object_controller_ref = ctx.opt_str(e, "objectControllerRef");
  if (deprecated_attribute(ctx, e, "controllerRef", {"objectControllerRef"})) {
    action.object_controller_ref =
        action.object_controller_ref.value_or(ctx.opt_str(e, "controllerRef").value_or(""));
  }
  action.lateral = ctx.opt_bool(e, "lateral");
  action.longitudinal = ctx.opt_bool(e, "longitudinal");
  action.animation = ctx.opt_bool(e, "animation");
  action.lighting = ctx.opt_bool(e, "lighting");
  action.source = ctx.source(e);
  return action;
}

const Element* controller_override_pair(const Element* private_action) {
  const Element* c = private_action->FirstChildElement("ControllerAction");
  if (c == nullptr || c->FirstChildElement("AssignControllerAction") == nullptr) return nullptr;
  const Element* override_values = c->FirstChildElement("OverrideControllerValueAction");
  int children = 0;
  for (const Element* k = c->FirstChildElement(); k != nullptr; k = k->NextSiblingElement()) {
    ++children;
  }
  return children == 2 ? override_values : nullptr;
}

PrivateAction parse_controller_override(ParseContext& ctx, const Element* e) {
  return parse_override(ctx, e);
}

PrivateAction parse_controller_action(ParseContext& ctx, const Element* e, bool in_init) {
  Children kids(ctx, e, "ControllerAction");
  // 1.0's ControllerAction holds an AssignControllerAction and an OverrideControllerValueAction
  // together (both required); 1.1 made it a choice. In Init the pair is two actions (the caller
  // adds the override, controller_override_pair); an Action of an event holds one action, so
  // there the override is checked and left out, a lenient reading.
  if (const Element* override_values = controller_override_pair(e->Parent()->ToElement())) {
    PrivateAction assign = parse_assign_controller(ctx, kids.one("AssignControllerAction"));
    parse_override(ctx, kids.opt("OverrideControllerValueAction"));
    if (!in_init) {
      ctx.lenient(override_values,
                  "OpenSCENARIO 1.0 <OverrideControllerValueAction> beside an "
                  "<AssignControllerAction> in an event's Action",
                  "the AssignControllerAction alone: the override is not applied");
    }
    return assign;
  }
  const Element* a = kids.choice();
  const std::string_view name = a->Name();
  if (name == "AssignControllerAction") return parse_assign_controller(ctx, a);
  if (name == "OverrideControllerValueAction") return parse_override(ctx, a);
  return parse_activate_controller(ctx, a);
}

PrivateAction parse_appearance_action(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "AppearanceAction");
  const Element* a = kids.choice();
  if (std::string_view(a->Name()) == "LightStateAction") return parse_light_state_action(ctx, a);
  return parse_animation_action(ctx, a);
}

PrivateAction parse_trailer_action(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "TrailerAction");
  const Element* a = kids.choice();
  if (std::string_view(a->Name()) == "ConnectTrailerAction") {
    Children(ctx, a, "ConnectTrailerAction");
    ConnectTrailerAction action{ctx.req_str(a, "trailerRef"), ctx.source(a)};
    if (action.trailer_ref.empty()) {
      // A trailer parameter left empty: there is no trailer to connect.
      ctx.lenient(a, "trailerRef is empty", "no trailer: the action connects nothing");
    } else {
      ctx.use_entity(a, action.trailer_ref, "trailerRef");
    }
    return action;
  }
  Children(ctx, a, "DisconnectTrailerAction");
  return DisconnectTrailerAction{ctx.source(a)};
}

}  // namespace corsa::xosc
