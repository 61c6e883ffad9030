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
    rename(e, "LongitudinalAction");
    for (Element* speed : osc09_children(e, "Speed")) speed_action(speed);
  } else if (name == "Lateral") {
    rename(e, "LateralAction");
    for (Element* change : osc09_children(e, "LaneChange")) lane_change_action(change);
  } else if (name == "Routing") {
    rename(e, "RoutingAction");
    for (Element* follow : osc09_children(e, "FollowRoute")) rename(follow, "AssignRouteAction");
  } else if (name == "Meeting") {
    meeting(e);
  } else if (name == "EXT_Synchronize") {
    synchronize(e);
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
  for (Element* target : osc09_children(e, "Target")) {
    rename(target, "SpeedActionTarget");
    for (Element* a : osc09_children(target, "Absolute")) rename(a, "AbsoluteTargetSpeed");
    for (Element* r : osc09_children(target, "Relative")) {
      rename(r, "RelativeTargetSpeed");
      move_attribute(r, "object", "entityRef");
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
  for (Element* target : osc09_children(e, "Target")) {
    rename(target, "LaneChangeTarget");
    for (Element* a : osc09_children(target, "Absolute")) rename(a, "AbsoluteTargetLane");
    for (Element* r : osc09_children(target, "Relative")) {
      rename(r, "RelativeTargetLane");
      move_attribute(r, "object", "entityRef");
    }
  }
}

// 0.9 Meeting (own Position, Relative master with its Position) is 1.0's SynchronizeAction.
// A time offset has no 1.0 form: such a Meeting is left for the reader to refuse. An offset
// given by a parameter is judged by the parameter's value.
void Osc09Rewriter::meeting(Element* e) {
  Element* relative = e->FirstChildElement("Relative");
  Element* own = e->FirstChildElement("Position");
  if (relative == nullptr || own == nullptr) return;
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
