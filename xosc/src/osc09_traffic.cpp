// The 0.9-to-1.0 mapping (osc09_rewriter.h) of traffic, signals and entity selections, as ASAM's
// 0.9.1-to-1.0 migration maps them: Entities/Selection (1.0's EntitySelection),
// RoadNetwork/Signals (1.0's TrafficSignals), Global/Infrastructure (an
// InfrastructureAction's TrafficSignalAction) and Global/Traffic (a TrafficAction's source, sink
// and swarm, their TrafficDefinition). A Jam has no 1.0 form: refused at its line.

#include <array>

#include "osc09_rewriter.h"

namespace corsa::xosc {
namespace {

// 1.0's vehicle categories; 0.9's VehicleDistribution typed its category as any text.
bool is_vehicle_category(std::string_view word) {
  static constexpr std::array<std::string_view, 10> kCategories = {
      "car", "van",       "truck",   "trailer", "semitrailer",
      "bus", "motorbike", "bicycle", "train",   "tram"};
  for (const std::string_view category : kCategories) {
    if (category == word) return true;
  }
  return false;
}

}  // namespace

// 0.9 Selection name of Members with ByEntity name or ByType type elements: 1.0's
// EntitySelection of Members with EntityRef entityRef, ByType objectType (the same words).
void Osc09Rewriter::selection(Element* e) {
  rename(e, "EntitySelection");
  for (Element* members : osc09_children(e, "Members")) {
    for (Element* by : osc09_children(members, "ByEntity")) {
      rename(by, "EntityRef");
      move_attribute(by, "name", "entityRef");
    }
    for (Element* by : osc09_children(members, "ByType")) move_attribute(by, "type", "objectType");
  }
}

// 0.9 RoadNetwork/Signals name of Controller name delay reference, each of Phase type duration
// of Signal name state: 1.0's TrafficSignals of TrafficSignalController (the same attributes),
// Phase name duration of TrafficSignalState trafficSignalId state. The set's own name has no
// 1.0 place and names nothing a scenario refers to: dropped.
void Osc09Rewriter::signals(Element* e) {
  rename(e, "TrafficSignals");
  e->DeleteAttribute("name");
  for (Element* controller : osc09_children(e, "Controller")) {
    rename(controller, "TrafficSignalController");
    for (Element* phase : osc09_children(controller, "Phase")) {
      move_attribute(phase, "type", "name");
      for (Element* signal : osc09_children(phase, "Signal")) {
        rename(signal, "TrafficSignalState");
        move_attribute(signal, "name", "trafficSignalId");
      }
    }
  }
}

// 0.9 Infrastructure/Signal of SetController name state or SetState name state: 1.0's
// InfrastructureAction/TrafficSignalAction of TrafficSignalControllerAction
// trafficSignalControllerRef phase, TrafficSignalStateAction name state.
void Osc09Rewriter::infrastructure_action(Element* e) {
  rename(e, "InfrastructureAction");
  for (Element* signal : osc09_children(e, "Signal")) {
    rename(signal, "TrafficSignalAction");
    for (Element* set : osc09_children(signal, "SetController")) {
      rename(set, "TrafficSignalControllerAction");
      move_attribute(set, "name", "trafficSignalControllerRef");
      move_attribute(set, "state", "phase");
    }
    for (Element* set : osc09_children(signal, "SetState")) rename(set, "TrafficSignalStateAction");
  }
}

// 0.9 Traffic of Source or Sink (rate, radius, Position, TrafficDefinition) or Swarm
// (CentralObject name, semiMajorAxis, semiMinorAxis, innerRadius, offset, TrafficDefinition):
// 1.0's TrafficAction of TrafficSourceAction, TrafficSinkAction, TrafficSwarmAction. 0.9's Swarm
// has no numberOfVehicles, which 1.0 requires: one written anyway (ASAM's migration copies it)
// is read, a Swarm without it is refused. A Jam has no 1.0 form (the migration removes it).
void Osc09Rewriter::traffic_action(Element* e) {
  rename(e, "TrafficAction");
  for (Element* a : osc09_children(e)) {
    const std::string_view kind = a->Name();
    if (kind == "Jam") {
      ctx_.error(a,
                 "0.9 Traffic Jam has no 1.0 form (ASAM's 0.9.1-to-1.0 migration removes it): "
                 "no traffic jam to read it as");
      continue;
    }
    if (kind == "Source" || kind == "Sink") {
      rename(a, kind == "Source" ? "TrafficSourceAction" : "TrafficSinkAction");
      for (Element* p : osc09_children(a, "Position")) position(p);
    } else if (kind == "Swarm") {
      rename(a, "TrafficSwarmAction");
      if (a->Attribute("numberOfVehicles") == nullptr) {
        ctx_.error(a,
                   "0.9 Swarm gives no numberOfVehicles, which 1.0's TrafficSwarmAction requires "
                   "(the 0.9.1 schema has none; write numberOfVehicles=\"N\" on the Swarm)");
      }
      for (Element* central : osc09_children(a, "CentralObject")) {
        move_attribute(central, "name", "entityRef");
      }
    } else {
      continue;  // not 0.9: left for the reader
    }
    for (Element* definition : osc09_children(a, "TrafficDefinition")) {
      traffic_definition(definition);
    }
  }
}

// 0.9 TrafficDefinition name of VehicleDistribution/Vehicle category percentage and
// DriverDistribution/Driver name percentage: 1.0's VehicleCategoryDistribution of
// VehicleCategoryDistributionEntry category weight and ControllerDistribution of
// ControllerDistributionEntry weight. A category that is no 1.0 vehicle category is read as a
// car, as ASAM's migration reads it. A 0.9 Driver is a name where 1.0 wants a Controller (the
// migration leaves an empty one to fill in): read as a Controller of that name without
// properties, generated traffic's own driver, with a warning.
void Osc09Rewriter::traffic_definition(Element* e) {
  for (Element* vehicles : osc09_children(e, "VehicleDistribution")) {
    rename(vehicles, "VehicleCategoryDistribution");
    for (Element* v : osc09_children(vehicles, "Vehicle")) {
      rename(v, "VehicleCategoryDistributionEntry");
      move_attribute(v, "percentage", "weight");
      const char* category = v->Attribute("category");
      if (category != nullptr && category[0] != '$' && !is_vehicle_category(category)) {
        ctx_.lenient(attribute_source(v, "category"),
                     "0.9 VehicleDistribution category=\"" + clip(category) +
                         "\" is no 1.0 vehicle category",
                     "car, as ASAM's 0.9.1-to-1.0 migration");
        v->SetAttribute("category", "car");
      }
    }
  }
  for (Element* drivers : osc09_children(e, "DriverDistribution")) {
    rename(drivers, "ControllerDistribution");
    std::string names;
    for (Element* d : osc09_children(drivers, "Driver")) {
      rename(d, "ControllerDistributionEntry");
      move_attribute(d, "percentage", "weight");
      const char* name = d->Attribute("name");
      Element* controller = new_element("Controller", d);
      controller->SetAttribute("name", name != nullptr ? name : "");
      controller->InsertEndChild(new_element("Properties", d));
      d->InsertEndChild(controller);
      d->DeleteAttribute("name");
      names += (names.empty() ? "" : ", ") + clip(name != nullptr ? name : "");
    }
    if (!names.empty()) {
      ctx_.lenient(drivers,
                   "0.9 DriverDistribution names drivers (" + names +
                       ") where 1.0's ControllerDistributionEntry holds a Controller",
                   "a Controller of each name without properties: generated traffic's own "
                   "driver");
    }
  }
}

}  // namespace corsa::xosc
