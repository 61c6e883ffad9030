// The 0.9-to-1.0 mapping (osc09_rewriter.h) of private actions, their dynamics, and positions.

#include "osc09_rewriter.h"

namespace corsa::xosc {

void Osc09Rewriter::private_action(Element* e) {
  const std::string_view name = e->Name();
  if (name == "Position") {
    wrap(e, "TeleportAction");
    position(e);
    note("Position");
  } else if (name == "Longitudinal") {
    longitudinal_action(e);
  } else if (name == "Lateral") {
    lateral_action(e);
  } else if (name == "Visibility") {
    rename(e, "VisibilityAction");  // graphics, traffic, sensors as in 1.0
  } else if (name == "Autonomous") {
    autonomous(e);
  } else if (name == "Controller") {
    controller_action(e);
  } else if (name == "Routing") {
    routing(e);
  } else if (name == "Meeting") {
    meeting(e);
  } else if (name == "EXT_Synchronize") {
    synchronize(e);
  }
}

void Osc09Rewriter::longitudinal_action(Element* e) {
  rename(e, "LongitudinalAction");
  for (Element* speed : osc09_children(e, "Speed")) speed_action(speed);
  for (Element* d : osc09_children(e, "Distance")) distance_action(d, "LongitudinalDistanceAction");
}

void Osc09Rewriter::lateral_action(Element* e) {
  rename(e, "LateralAction");
  for (Element* change : osc09_children(e, "LaneChange")) lane_change_action(change);
  for (Element* offset : osc09_children(e, "LaneOffset")) lane_offset_action(offset);
  for (Element* d : osc09_children(e, "Distance")) distance_action(d, "LateralDistanceAction");
}

// 0.9 Longitudinal/Distance and Lateral/Distance (object, distance, timeGap, freespace; Dynamics
// of None or Limited limits): 1.0's distance actions, continuous as ASAM's 0.9.1-to-1.0
// migration writes them (0.9 had no attribute for it: the distance is kept), Limited as their
// DynamicConstraints.
void Osc09Rewriter::distance_action(Element* e, const char* name) {
  rename(e, name);
  move_attribute(e, "object", "entityRef");
  default_attribute(e, "continuous", "true");
  for (Element* dynamics : osc09_children(e, "Dynamics")) {
    if (Element* limited = dynamics->FirstChildElement("Limited")) {
      Element* constraints = new_element("DynamicConstraints", limited);
      for (const char* limit : {"maxAcceleration", "maxDeceleration", "maxSpeed"}) {
        if (const char* value = limited->Attribute(limit)) constraints->SetAttribute(limit, value);
      }
      e->InsertAfterChild(dynamics, constraints);
    }
    e->DeleteChild(dynamics);
  }
}

// 0.9 LaneOffset: Dynamics maxLateralAcc, duration, shape; Target Relative object value or
// Absolute value. 1.0's LaneOffsetAction has no duration: a duration is dropped with a warning
// (ASAM's migration drops it too); continuous as that migration writes it.
void Osc09Rewriter::lane_offset_action(Element* e) {
  rename(e, "LaneOffsetAction");
  default_attribute(e, "continuous", "true");
  for (Element* d : osc09_children(e, "Dynamics")) {
    rename(d, "LaneOffsetActionDynamics");
    move_attribute(d, "shape", "dynamicsShape");
    if (const char* duration = d->Attribute("duration")) {
      ctx_.lenient(attribute_source(d, "duration"),
                   "0.9 LaneOffset Dynamics duration=\"" + clip(duration) +
                       "\" (1.0's LaneOffsetActionDynamics has none)",
                   "the offset's shape and maxLateralAcc alone, the duration dropped");
      d->DeleteAttribute("duration");
    }
  }
  targets(e, "LaneOffsetTarget", "AbsoluteTargetLaneOffset", "RelativeTargetLaneOffset");
}

// 0.9 Autonomous activate domain (longitudinal, lateral, both): 1.0's ActivateControllerAction
// with that domain's attribute (both: the two) set to activate.
void Osc09Rewriter::autonomous(Element* e) {
  rename(e, "ActivateControllerAction");
  const std::string domain = value_of(e, "domain").value_or("");
  const std::string activate = e->Attribute("activate") != nullptr ? e->Attribute("activate") : "";
  if (!activate.empty() && (domain == "longitudinal" || domain == "both")) {
    e->SetAttribute("longitudinal", activate.c_str());
  }
  if (!activate.empty() && (domain == "lateral" || domain == "both")) {
    e->SetAttribute("lateral", activate.c_str());
  }
  e->DeleteAttribute("activate");
  e->DeleteAttribute("domain");
}

// 0.9 Controller of Assign (a Driver, PedestrianController or CatalogReference) and Override
// (Throttle, Brake, ... with 1.0's names and attributes): 1.0's ControllerAction.
void Osc09Rewriter::controller_action(Element* e) {
  rename(e, "ControllerAction");
  for (Element* assign : osc09_children(e, "Assign")) {
    rename(assign, "AssignControllerAction");
    controllers(assign);
  }
  for (Element* o : osc09_children(e, "Override")) rename(o, "OverrideControllerValueAction");
}

// 1.0's Controller describes no driver or pedestrian: the Description goes.
void Osc09Rewriter::controllers(Element* e) {
  for (Element* c : osc09_children(e)) {
    const std::string_view name = c->Name();
    if (name != "Driver" && name != "PedestrianController") continue;
    rename(c, "Controller");
    for (Element* d : osc09_children(c, "Description")) c->DeleteChild(d);
  }
}

// 0.9 Dynamics carried the shape and one of time, rate or distance; a step has none. A Dynamics
// giving more than one keeps the one esmini's 0.9 reader kept, the first of `precedence`, with
// a warning at the Dynamics (an error under --strict).
void Osc09Rewriter::dynamics(Element* e, const char* name,
                             const std::vector<const char*>& precedence) {
  rename(e, name);
  move_attribute(e, "shape", "dynamicsShape");
  std::vector<const char*> given;
  for (const char* dimension : precedence) {
    if (e->Attribute(dimension) != nullptr) given.push_back(dimension);
  }
  if (given.empty()) {
    e->SetAttribute("dynamicsDimension", "time");
    e->SetAttribute("value", "0");
    return;
  }
  const char* kept = given.front();
  if (given.size() > 1) {
    std::string all;
    for (const char* dimension : given) {
      all += (all.empty() ? "" : ", ") + std::string(dimension) + "=\"" +
             clip(e->Attribute(dimension)) + "\"";
    }
    ctx_.lenient(e, "0.9 Dynamics gives " + all,
                 std::string(kept) + " " + clip(e->Attribute(kept)) +
                     ", as esmini's 0.9 reader, the others dropped");
  }
  for (const char* dimension : given) {
    if (dimension != kept) e->DeleteAttribute(dimension);
  }
  move_attribute(e, kept, "value");
  e->SetAttribute("dynamicsDimension", kept);
}

void Osc09Rewriter::speed_action(Element* e) {
  rename(e, "SpeedAction");
  // esmini's 0.9 SpeedAction read rate, then time, then distance, each replacing the last.
  for (Element* d : osc09_children(e, "Dynamics")) {
    dynamics(d, "SpeedActionDynamics", {"distance", "time", "rate"});
  }
  for (Element* target :
       targets(e, "SpeedActionTarget", "AbsoluteTargetSpeed", "RelativeTargetSpeed")) {
    for (Element* r : osc09_children(target, "RelativeTargetSpeed")) {
      move_attribute(r, "valueType", "speedTargetValueType");
      default_attribute(r, "speedTargetValueType", "delta");
      default_attribute(r, "continuous", "false");
    }
  }
}

void Osc09Rewriter::lane_change_action(Element* e) {
  rename(e, "LaneChangeAction");
  // esmini's 0.9 LaneChange read time, else distance (a rate it did not read).
  for (Element* d : osc09_children(e, "Dynamics")) {
    dynamics(d, "LaneChangeActionDynamics", {"time", "distance", "rate"});
  }
  targets(e, "LaneChangeTarget", "AbsoluteTargetLane", "RelativeTargetLane");
}

std::vector<Element*> Osc09Rewriter::targets(Element* e, const char* name, const char* absolute,
                                             const char* relative) {
  std::vector<Element*> out = osc09_children(e, "Target");
  for (Element* target : out) {
    rename(target, name);
    for (Element* a : osc09_children(target, "Absolute")) rename(a, absolute);
    for (Element* r : osc09_children(target, "Relative")) {
      rename(r, relative);
      move_attribute(r, "object", "entityRef");
    }
  }
  return out;
}

// 0.9 Meeting (own Position, Relative master with its Position) is 1.0's SynchronizeAction.
// A time offset has no 1.0 form: such a Meeting is left for the reader to refuse. An offset
// given by a parameter is judged by the parameter's value. The 0.9.1 schema's Meeting (mode,
// timingOffset and a Position, no entity to meet) has no 1.0 form either (ASAM's migration
// removes it): refused at its line.
void Osc09Rewriter::meeting(Element* e) {
  Element* relative = e->FirstChildElement("Relative");
  Element* own = e->FirstChildElement("Position");
  if (relative == nullptr) {
    ctx_.error(e,
               "0.9 Meeting without a Relative entity to meet (the 0.9.1 schema's Meeting of "
               "mode, timingOffset and a Position) has no 1.0 form (ASAM's 0.9.1-to-1.0 "
               "migration removes it); a Meeting with a Relative object and offsetTime=\"0\" is "
               "read as a SynchronizeAction");
    return;
  }
  if (own == nullptr) return;
  if (relative->Attribute("offsetTime") != nullptr &&
      double_value(relative, "offsetTime") != std::optional<double>(0.0)) {
    return;
  }
  rename(e, "SynchronizeAction");
  e->DeleteAttribute("mode");
  move_attribute(relative, "object", "masterEntityRef");
  if (const char* master = relative->Attribute("masterEntityRef")) {
    e->SetAttribute("masterEntityRef", master);
  }
  if (Element* master = relative->FirstChildElement("Position")) {
    rename(master, "TargetPositionMaster");
    e->InsertFirstChild(master);
    position(master);
  }
  e->DeleteChild(relative);
  rename(own, "TargetPosition");
  position(own);
}

void Osc09Rewriter::synchronize(Element* e) {
  rename(e, "SynchronizeAction");
  move_attribute(e, "masterObject", "masterEntityRef");
  for (Element* p : osc09_children(e, "TargetPositionMaster")) position(p);
  for (Element* p : osc09_children(e, "TargetPosition")) position(p);
  for (Element* speed : osc09_children(e, "TargetSpeed")) {
    rename(speed, "FinalSpeed");
    for (Element* a : osc09_children(speed, "Absolute")) rename(a, "AbsoluteSpeed");
    for (Element* r : osc09_children(speed, "RelativeMaster")) {
      rename(r, "RelativeSpeedToMaster");
      move_attribute(r, "valueType", "speedTargetValueType");
    }
  }
}

// `e` holds one 0.9 position kind.
void Osc09Rewriter::position(Element* e) {
  Element* kind = e->FirstChildElement();
  if (kind == nullptr) return;
  static const std::map<std::string, std::string, std::less<>> kinds = {
      {"World", "WorldPosition"},
      {"RelativeWorld", "RelativeWorldPosition"},
      {"RelativeObject", "RelativeObjectPosition"},
      {"Road", "RoadPosition"},
      {"RelativeRoad", "RelativeRoadPosition"},
      {"Lane", "LanePosition"},
      {"RelativeLane", "RelativeLanePosition"}};
  const std::string name = kind->Name();
  if (const auto it = kinds.find(name); it != kinds.end()) {
    rename(kind, it->second.c_str());
    move_attribute(kind, "object", "entityRef");
  } else if (name == "Route") {
    rename(kind, "RoutePosition");
    for (Element* ref : osc09_children(kind, "RouteRef")) inline_definitions(ref);
    for (Element* in_route : osc09_children(kind, "Position")) {
      rename(in_route, "InRoutePosition");
      for (Element* c : osc09_children(in_route, "LaneCoord")) rename(c, "FromLaneCoordinates");
      for (Element* c : osc09_children(in_route, "RoadCoord")) rename(c, "FromRoadCoordinates");
      for (Element* c : osc09_children(in_route, "Current")) {
        rename(c, "FromCurrentEntity");
        move_attribute(c, "object", "entityRef");
      }
    }
  }
}

}  // namespace corsa::xosc
