// Private actions (§7.4): longitudinal, lateral, visibility, synchronize, teleport, routing.
// Controller, appearance and trailer actions are in parse_controller_actions.cpp.

#include "parsers.h"

namespace corsa::xosc {

PrivateAction parse_controller_action(ParseContext& ctx, const Element* e, bool in_init);
ActivateControllerAction parse_activate_controller(ParseContext& ctx, const Element* e);
PrivateAction parse_appearance_action(ParseContext& ctx, const Element* e);
PrivateAction parse_trailer_action(ParseContext& ctx, const Element* e);

namespace {

TransitionDynamics parse_dynamics(ParseContext& ctx, const Element* e) {
  Children(ctx, e, "TransitionDynamics");
  std::optional<DynamicsDimension> dimension =
      ctx.opt_enum<DynamicsDimension>(e, "dynamicsDimension");
  const auto shape = ctx.req_enum<DynamicsShape>(e, "dynamicsShape");
  std::optional<double> value = ctx.opt_double(e, "value");
  if (shape == DynamicsShape::kStep && (!dimension || !value)) {
    // A step reaches its target at once (§7.4.1.1), whatever its dimension and value say:
    // esmini's examples write `<SpeedActionDynamics dynamicsShape="step"/>` for "at once".
    const char* absent = !dimension && !value ? "dynamicsDimension and value"
                         : !dimension         ? "dynamicsDimension"
                                              : "value";
    ctx.lenient(e, std::string("step transition dynamics without ") + absent,
                "a step: the target at once");
    dimension = dimension.value_or(DynamicsDimension::kTime);
    value = value.value_or(0.0);
  }
  if (!dimension) ctx.missing(e, "dynamicsDimension");
  if (!value) ctx.missing(e, "value");
  TransitionDynamics dynamics{*dimension, shape, *value,
                              ctx.opt_enum<FollowingMode>(e, "followingMode"), ctx.source(e)};
  if (dynamics.value < 0.0) {
    // A negative rate ("-4" for braking at 4 m/s^2) says which way the speed goes, which the
    // target says already; time, distance and rate are magnitudes (§7.4.1.1).
    ctx.lenient(e, "transition dynamics value " + format_double(dynamics.value) + " is negative",
                "its magnitude " + format_double(-dynamics.value));
    dynamics.value = -dynamics.value;
  }
  return dynamics;
}

std::optional<DynamicConstraints> optional_constraints(ParseContext& ctx, Children& kids) {
  const Element* e = kids.opt("DynamicConstraints");
  if (e == nullptr) return std::nullopt;
  Children(ctx, e, "DynamicConstraints");
  return DynamicConstraints{
      ctx.opt_double(e, "maxAcceleration"), ctx.opt_double(e, "maxAccelerationRate"),
      ctx.opt_double(e, "maxDeceleration"), ctx.opt_double(e, "maxDecelerationRate"),
      ctx.opt_double(e, "maxSpeed"),        ctx.source(e)};
}

std::string entity_attribute(ParseContext& ctx, const Element* e, const char* name) {
  std::string value = ctx.req_str(e, name);
  ctx.use_entity(e, value, name);
  return value;
}

SpeedAction parse_speed_action(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "SpeedAction");
  SpeedAction action;
  action.dynamics = parse_dynamics(ctx, kids.one("SpeedActionDynamics"));
  const Element* target = kids.one("SpeedActionTarget");
  Children target_kids(ctx, target, "SpeedActionTarget");
  const Element* t = target_kids.choice();
  if (std::string_view(t->Name()) == "AbsoluteTargetSpeed") {
    Children(ctx, t, "AbsoluteTargetSpeed");
    action.target = AbsoluteTargetSpeed{ctx.req_double(t, "value"), ctx.source(t)};
  } else {
    Children(ctx, t, "RelativeTargetSpeed");
    const std::string entity = entity_attribute(ctx, t, "entityRef");
    const double value = ctx.req_double(t, "value");
    SpeedTargetValueType type = SpeedTargetValueType::kDelta;
    if (t->Attribute("speedTargetValueType") == nullptr && value == 0.0) {
      // speedTargetValueType is required; esmini's highway_merge leaves it out of a continuous
      // target of value 0 on another car: that car's speed (a factor 0 would stop the entity
      // whatever the other car does). Any other value stays an error.
      ctx.lenient(t, "<RelativeTargetSpeed> of value 0 without speedTargetValueType",
                  "delta: the speed of '" + clip(entity) + "'");
    } else {
      type = ctx.req_enum<SpeedTargetValueType>(t, "speedTargetValueType");
    }
    action.target =
        RelativeTargetSpeed{entity, value, type, ctx.req_bool(t, "continuous"), ctx.source(t)};
  }
  action.source = ctx.source(e);
  return action;
}

LongitudinalDistanceAction parse_longitudinal_distance(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "LongitudinalDistanceAction");
  LongitudinalDistanceAction action;
  action.entity_ref = entity_attribute(ctx, e, "entityRef");
  action.continuous = ctx.req_bool(e, "continuous");
  action.freespace = ctx.req_bool(e, "freespace");
  action.distance = ctx.opt_double(e, "distance");
  action.time_gap = ctx.opt_double(e, "timeGap");
  if (action.distance.has_value() == action.time_gap.has_value()) {
    ctx.fail(e, "<LongitudinalDistanceAction> needs exactly one of distance and timeGap");
  }
  action.displacement = ctx.opt_enum<LongitudinalDisplacement>(e, "displacement");
  action.coordinate_system = ctx.opt_enum<CoordinateSystem>(e, "coordinateSystem");
  action.constraints = optional_constraints(ctx, kids);
  action.source = ctx.source(e);
  return action;
}

SpeedProfileAction parse_speed_profile(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "SpeedProfileAction");
  SpeedProfileAction action;
  action.entity_ref = ctx.opt_str(e, "entityRef");
  if (action.entity_ref) ctx.use_entity(e, *action.entity_ref, "entityRef");
  action.following_mode = ctx.req_enum<FollowingMode>(e, "followingMode");
  action.constraints = optional_constraints(ctx, kids);
  for (const Element* entry : kids.at_least("SpeedProfileEntry", 1)) {
    Children(ctx, entry, "SpeedProfileEntry");
    action.entries.push_back(
        {ctx.req_double(entry, "speed"), ctx.opt_double(entry, "time"), ctx.source(entry)});
  }
  action.source = ctx.source(e);
  return action;
}

PrivateAction parse_longitudinal(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "LongitudinalAction");
  const Element* a = kids.choice();
  const std::string_view name = a->Name();
  if (name == "SpeedAction") return parse_speed_action(ctx, a);
  if (name == "LongitudinalDistanceAction") return parse_longitudinal_distance(ctx, a);
  return parse_speed_profile(ctx, a);
}

LaneChangeAction parse_lane_change(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "LaneChangeAction");
  LaneChangeAction action;
  action.target_lane_offset = ctx.opt_double(e, "targetLaneOffset");
  action.dynamics = parse_dynamics(ctx, kids.one("LaneChangeActionDynamics"));
  const Element* target = kids.one("LaneChangeTarget");
  Children target_kids(ctx, target, "LaneChangeTarget");
  const Element* t = target_kids.choice();
  if (std::string_view(t->Name()) == "RelativeTargetLane") {
    Children(ctx, t, "RelativeTargetLane");
    action.target = RelativeTargetLane{entity_attribute(ctx, t, "entityRef"),
                                       static_cast<int>(ctx.req_int(t, "value")), ctx.source(t)};
  } else {
    Children(ctx, t, "AbsoluteTargetLane");
    action.target = AbsoluteTargetLane{ctx.req_str(t, "value"), ctx.source(t)};
  }
  action.source = ctx.source(e);
  return action;
}

LaneOffsetAction parse_lane_offset(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "LaneOffsetAction");
  LaneOffsetAction action;
  if (e->Attribute("continuous") == nullptr) {
    // continuous is required (1.0-1.3 XSD); esmini's lane_change leaves it out of an offset that
    // moves its car 8 m aside in a chain of events. Read as false: the action ends once the
    // target offset is reached (a continuous one would never end, holding its event).
    ctx.lenient(e, "<LaneOffsetAction> without continuous", "continuous=\"false\"");
    action.continuous = false;
  } else {
    action.continuous = ctx.req_bool(e, "continuous");
  }
  const Element* dynamics = kids.one("LaneOffsetActionDynamics");
  Children(ctx, dynamics, "LaneOffsetActionDynamics");
  action.shape = ctx.req_enum<DynamicsShape>(dynamics, "dynamicsShape");
  action.max_lateral_acc = ctx.opt_double(dynamics, "maxLateralAcc");
  const Element* target = kids.one("LaneOffsetTarget");
  Children target_kids(ctx, target, "LaneOffsetTarget");
  const Element* t = target_kids.choice();
  if (std::string_view(t->Name()) == "RelativeTargetLaneOffset") {
    Children(ctx, t, "RelativeTargetLaneOffset");
    action.target = RelativeTargetLaneOffset{entity_attribute(ctx, t, "entityRef"),
                                             ctx.req_double(t, "value"), ctx.source(t)};
  } else {
    Children(ctx, t, "AbsoluteTargetLaneOffset");
    action.target = AbsoluteTargetLaneOffset{ctx.req_double(t, "value"), ctx.source(t)};
  }
  action.source = ctx.source(e);
  return action;
}

LateralDistanceAction parse_lateral_distance(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "LateralDistanceAction");
  LateralDistanceAction action;
  action.entity_ref = entity_attribute(ctx, e, "entityRef");
  action.continuous = ctx.req_bool(e, "continuous");
  action.freespace = ctx.req_bool(e, "freespace");
  action.distance = ctx.opt_double(e, "distance");
  action.displacement = ctx.opt_enum<LateralDisplacement>(e, "displacement");
  action.coordinate_system = ctx.opt_enum<CoordinateSystem>(e, "coordinateSystem");
  action.constraints = optional_constraints(ctx, kids);
  action.source = ctx.source(e);
  return action;
}

PrivateAction parse_lateral(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "LateralAction");
  const Element* a = kids.choice();
  const std::string_view name = a->Name();
  if (name == "LaneChangeAction") return parse_lane_change(ctx, a);
  if (name == "LaneOffsetAction") return parse_lane_offset(ctx, a);
  return parse_lateral_distance(ctx, a);
}

VisibilityAction parse_visibility(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "VisibilityAction");
  VisibilityAction action;
  // All three flags are required; esmini's examples write only those the action changes
  // (<VisibilityAction sensors="false"/> hides the actor from sensors and nothing else), so an
  // absent flag leaves that visibility as it is.
  for (const char* flag : {"graphics", "sensors", "traffic"}) {
    if (e->Attribute(flag) == nullptr) {
      ctx.lenient(e, std::string("<VisibilityAction> without ") + flag,
                  std::string(flag) + " visibility unchanged");
    }
  }
  action.graphics = ctx.opt_bool(e, "graphics");
  action.sensors = ctx.opt_bool(e, "sensors");
  action.traffic = ctx.opt_bool(e, "traffic");
  if (const Element* set = kids.opt("SensorReferenceSet")) {
    Children set_kids(ctx, set, "SensorReferenceSet");
    for (const Element* ref : set_kids.at_least("SensorReference", 1)) {
      Children(ctx, ref, "SensorReference");
      action.sensor_refs.push_back({ctx.req_str(ref, "name"), ctx.source(ref)});
    }
  }
  action.source = ctx.source(e);
  return action;
}

std::optional<SteadyState> optional_steady_state(ParseContext& ctx, const Element* e,
                                                 Children& kids) {
  const Element* distance = kids.opt("TargetDistanceSteadyState");
  const Element* time = kids.opt("TargetTimeSteadyState");
  if (distance != nullptr && time != nullptr) {
    ctx.fail(e, "a final speed takes one steady state, not both");
  }
  if (distance != nullptr) {
    Children(ctx, distance, "TargetDistanceSteadyState");
    return TargetDistanceSteadyState{ctx.req_double(distance, "distance"), ctx.source(distance)};
  }
  if (time != nullptr) {
    Children(ctx, time, "TargetTimeSteadyState");
    return TargetTimeSteadyState{ctx.req_double(time, "time"), ctx.source(time)};
  }
  return std::nullopt;
}

// The speed element of a FinalSpeed beside esmini's <SteadyState> (which the choice of the
// schema does not allow): its one AbsoluteSpeed or RelativeSpeedToMaster.
const Element* speed_beside_steady_state(ParseContext& ctx, const Element* final_speed) {
  const Element* absolute = final_speed->FirstChildElement("AbsoluteSpeed");
  const Element* relative = final_speed->FirstChildElement("RelativeSpeedToMaster");
  if ((absolute == nullptr) == (relative == nullptr)) {
    ctx.fail(final_speed, "<FinalSpeed> needs one of: AbsoluteSpeed, RelativeSpeedToMaster");
  }
  return absolute != nullptr ? absolute : relative;
}

// In 1.1 to 1.3 SteadyState is an XSD group, not an element: its TargetDistanceSteadyState or
// TargetTimeSteadyState is a child of the final speed it belongs to. esmini's
// pedestrian_traj_synch writes it as an element beside <AbsoluteSpeed>, which says the same:
// read as that speed's steady state. esmini itself reads only a first child of the speed
// element, so it runs this file without the steady state.
std::optional<SteadyState> steady_state_beside(ParseContext& ctx, const Element* wrapper,
                                               const Element* speed,
                                               std::optional<SteadyState> own) {
  Children wrapper_kids(ctx, wrapper, "SteadyState");
  std::optional<SteadyState> steady = optional_steady_state(ctx, wrapper, wrapper_kids);
  if (own) {
    ctx.fail(wrapper, "<SteadyState> beside a <" + std::string(speed->Name()) +
                          "> that has a steady state of its own");
  }
  const std::string owner = "<" + std::string(speed->Name()) + ">";
  if (!steady) {
    ctx.lenient(wrapper, "an empty <SteadyState> in <FinalSpeed>", "no steady state");
  } else if (const auto* distance = std::get_if<TargetDistanceSteadyState>(&*steady)) {
    ctx.lenient(wrapper, "<SteadyState> in <FinalSpeed> (a group of the schema, not an element)",
                owner + "'s steady state: TargetDistanceSteadyState " +
                    format_double(distance->distance) + " m");
  } else {
    ctx.lenient(wrapper, "<SteadyState> in <FinalSpeed> (a group of the schema, not an element)",
                owner + "'s steady state: TargetTimeSteadyState " +
                    format_double(std::get<TargetTimeSteadyState>(*steady).time) + " s");
  }
  return steady;
}

std::variant<AbsoluteSpeed, RelativeSpeedToMaster> parse_final_speed(ParseContext& ctx,
                                                                     const Element* e) {
  Children kids(ctx, e, "FinalSpeed");
  const Element* wrapper = kids.opt("SteadyState");
  const Element* s = nullptr;
  if (wrapper == nullptr) {
    s = kids.choice();
  } else {
    kids.consume_all();
    s = speed_beside_steady_state(ctx, e);
  }
  const bool absolute = std::string_view(s->Name()) == "AbsoluteSpeed";
  Children speed_kids(ctx, s, absolute ? "AbsoluteSpeed" : "RelativeSpeedToMaster");
  std::optional<SteadyState> steady = optional_steady_state(ctx, s, speed_kids);
  if (wrapper != nullptr) {
    steady = steady_state_beside(ctx, wrapper, s, std::move(steady));
  }
  if (absolute) {
    return AbsoluteSpeed{ctx.req_double(s, "value"), std::move(steady), ctx.source(s)};
  }
  return RelativeSpeedToMaster{ctx.req_double(s, "value"),
                               ctx.req_enum<SpeedTargetValueType>(s, "speedTargetValueType"),
                               std::move(steady), ctx.source(s)};
}

SynchronizeAction parse_synchronize(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "SynchronizeAction");
  SynchronizeAction action;
  action.master_entity_ref = entity_attribute(ctx, e, "masterEntityRef");
  action.target_position_master = parse_position(ctx, kids.one("TargetPositionMaster"));
  action.target_position = parse_position(ctx, kids.one("TargetPosition"));
  action.target_tolerance_master = ctx.opt_double(e, "targetToleranceMaster");
  action.target_tolerance = ctx.opt_double(e, "targetTolerance");
  if (const Element* final_speed = kids.opt("FinalSpeed")) {
    action.final_speed = parse_final_speed(ctx, final_speed);
  }
  action.source = ctx.source(e);
  return action;
}

FollowTrajectoryAction parse_follow_trajectory(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "FollowTrajectoryAction");
  FollowTrajectoryAction action;
  action.initial_distance_offset = ctx.opt_double(e, "initialDistanceOffset");
  const Element* inline_trajectory = kids.opt("Trajectory");
  const Element* reference = kids.opt("CatalogReference");
  const Element* trajectory_ref = kids.opt("TrajectoryRef");
  const int given =
      (inline_trajectory != nullptr) + (reference != nullptr) + (trajectory_ref != nullptr);
  if (given != 1) {
    ctx.fail(e,
             "<FollowTrajectoryAction> needs exactly one of TrajectoryRef, Trajectory or "
             "CatalogReference");
  }
  if (trajectory_ref != nullptr) {
    Children ref_kids(ctx, trajectory_ref, "TrajectoryRef");
    action.trajectory = parse_trajectory_choice(ctx, ref_kids.choice());
  } else {
    // 1.0/1.1 placed the trajectory directly in the action (deprecated in 1.2).
    const Element* direct = inline_trajectory != nullptr ? inline_trajectory : reference;
    ctx.deprecated(direct,
                   "<" + std::string(direct->Name()) + "> directly in <FollowTrajectoryAction>",
                   "<TrajectoryRef>");
    action.trajectory = parse_trajectory_choice(ctx, direct);
  }
  action.time_reference = parse_time_reference(ctx, kids.one("TimeReference"));
  if (e->FirstChildElement("TrajectoryFollowingMode") == nullptr) {
    // TrajectoryFollowingMode is required (1.0-1.3 XSD); esmini's pedestrian_traj_synch leaves it
    // out, and esmini then follows the trajectory in its `follow` mode (steered along it, "applying
    // follow"), which is how its author saw the file run: read so.
    ctx.lenient(e, "<FollowTrajectoryAction> without <TrajectoryFollowingMode>",
                "followingMode=\"follow\", esmini's default");
    action.following_mode = FollowingMode::kFollow;
  } else {
    const Element* mode = kids.one("TrajectoryFollowingMode");
    Children(ctx, mode, "TrajectoryFollowingMode");
    action.following_mode = ctx.req_enum<FollowingMode>(mode, "followingMode");
  }
  action.source = ctx.source(e);
  return action;
}

PrivateAction parse_routing(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "RoutingAction");
  const Element* a = kids.choice();
  const std::string_view name = a->Name();
  if (name == "AssignRouteAction") {
    Children route_kids(ctx, a, "AssignRouteAction");
    return AssignRouteAction{parse_route_choice(ctx, route_kids.choice()), ctx.source(a)};
  }
  if (name == "FollowTrajectoryAction") return parse_follow_trajectory(ctx, a);
  if (name == "AcquirePositionAction") {
    Children position_kids(ctx, a, "AcquirePositionAction");
    return AcquirePositionAction{parse_position(ctx, position_kids.one("Position")), ctx.source(a)};
  }
  Children(ctx, a, "RandomRouteAction");
  return RandomRouteAction{ctx.source(a)};
}

}  // namespace

PrivateAction parse_private_action(ParseContext& ctx, const Element* e, bool in_init) {
  Children kids(ctx, e, "PrivateAction");
  const Element* a = kids.choice();
  const std::string_view name = a->Name();
  if (name == "LongitudinalAction") return parse_longitudinal(ctx, a);
  if (name == "LateralAction") return parse_lateral(ctx, a);
  if (name == "VisibilityAction") return parse_visibility(ctx, a);
  if (name == "SynchronizeAction") return parse_synchronize(ctx, a);
  if (name == "ActivateControllerAction") {
    ctx.deprecated(a, "<ActivateControllerAction> directly in <PrivateAction>",
                   "<ControllerAction><ActivateControllerAction>");
    return parse_activate_controller(ctx, a);
  }
  if (name == "ControllerAction") return parse_controller_action(ctx, a, in_init);
  if (name == "TeleportAction") {
    Children teleport_kids(ctx, a, "TeleportAction");
    return TeleportAction{parse_position(ctx, teleport_kids.one("Position")), ctx.source(a)};
  }
  if (name == "RoutingAction") return parse_routing(ctx, a);
  if (name == "AppearanceAction") return parse_appearance_action(ctx, a);
  return parse_trailer_action(ctx, a);
}

}  // namespace corsa::xosc
