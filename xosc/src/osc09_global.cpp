// The 0.9-to-1.0 mapping (osc09_rewriter.h) of global and user-defined actions: 0.9's
// SetEnvironment and its Environment (TimeOfDay of Time and Date, Precipitation type,
// RoadCondition frictionScale), Entity, Parameter, and UserDefined's Command. Infrastructure and
// Traffic are in osc09_traffic.cpp.

#include <charconv>
#include <cstdio>

#include "corsa/core/strings.h"
#include "osc09_rewriter.h"

namespace corsa::xosc {
namespace {

template <typename T>
bool number_of(const Element* e, const char* attribute, T* out) {
  const char* text = e == nullptr ? nullptr : e->Attribute(attribute);
  if (text == nullptr) return false;
  const std::string_view view(text);
  const auto [end, error] = std::from_chars(view.data(), view.data() + view.size(), *out);
  return error == std::errc() && end == view.data() + view.size();
}

}  // namespace

void Osc09Rewriter::global_action(Element* e) {
  rename(e, "GlobalAction");
  for (Element* set : osc09_children(e, "SetEnvironment")) {
    rename(set, "EnvironmentAction");
    for (Element* environment : osc09_children(set, "Environment")) this->environment(environment);
  }
  for (Element* entity : osc09_children(e, "Entity")) entity_action(entity);
  for (Element* parameter : osc09_children(e, "Parameter")) parameter_action(parameter);
  for (Element* i : osc09_children(e, "Infrastructure")) infrastructure_action(i);
  for (Element* traffic : osc09_children(e, "Traffic")) traffic_action(traffic);
}

// 0.9 UserDefined of a Command (its text the command) or a Script (name, file, execution). A
// Command is 1.0's UserDefinedAction/CustomCommandAction, whose required type 0.9 did not have:
// the command's text is read as its type as well as its content, with a warning (a `type`
// written on the Command, as ASAM's migration copies, is kept). A Script has no 1.0 form (the
// migration removes it): refused at its line.
void Osc09Rewriter::user_defined_action(Element* e) {
  rename(e, "UserDefinedAction");
  for (Element* script : osc09_children(e, "Script")) {
    const char* file = script->Attribute("file");
    ctx_.error(script, "0.9 UserDefined Script" +
                           (file != nullptr ? " file=\"" + clip(file) + "\"" : std::string()) +
                           " has no 1.0 form (ASAM's 0.9.1-to-1.0 migration removes it): no "
                           "script to read it as");
  }
  for (Element* command : osc09_children(e, "Command")) {
    rename(command, "CustomCommandAction");
    const std::string text(trim(element_text(command)));
    if (command->Attribute("type") != nullptr || text.empty()) continue;
    ctx_.lenient(command,
                 "0.9 UserDefined Command \"" + clip(text) +
                     "\" has no type, which 1.0's CustomCommandAction requires",
                 "type \"" + clip(text) + "\": the command's text its type and content");
    command->SetAttribute("type", text.c_str());
  }
}

// 0.9 Entity name with Add (a Position) or Delete: 1.0's EntityAction entityRef.
void Osc09Rewriter::entity_action(Element* e) {
  rename(e, "EntityAction");
  move_attribute(e, "name", "entityRef");
  for (Element* add : osc09_children(e, "Add")) {
    rename(add, "AddEntityAction");
    for (Element* p : osc09_children(add, "Position")) position(p);
  }
  for (Element* remove : osc09_children(e, "Delete")) rename(remove, "DeleteEntityAction");
}

// 0.9 Parameter name="$X" with Set value or Modify/Rule of Add or Multiply value: 1.0's
// ParameterAction parameterRef="X" with SetAction, ModifyAction/Rule of AddValue,
// MultiplyByValue.
void Osc09Rewriter::parameter_action(Element* e) {
  rename(e, "ParameterAction");
  parameter_ref(e);
  for (Element* set : osc09_children(e, "Set")) rename(set, "SetAction");
  for (Element* modify : osc09_children(e, "Modify")) {
    rename(modify, "ModifyAction");
    for (Element* rule : osc09_children(modify, "Rule")) {
      for (Element* add : osc09_children(rule, "Add")) rename(add, "AddValue");
      for (Element* multiply : osc09_children(rule, "Multiply"))
        rename(multiply, "MultiplyByValue");
    }
  }
}

bool Osc09Rewriter::date_time(Element* e) {
  Element* time = e->FirstChildElement("Time");
  Element* date = e->FirstChildElement("Date");
  int hour = 0, minute = 0, day = 0, month = 0, year = 0;
  double second = 0.0;
  if (!number_of(time, "hour", &hour) || !number_of(time, "min", &minute) ||
      !number_of(time, "sec", &second) || !number_of(date, "day", &day) ||
      !number_of(date, "month", &month) || !number_of(date, "year", &year) || second < 0.0 ||
      second >= 60.0) {
    return false;
  }
  char text[64];
  std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02d", year, month, day, hour, minute,
                static_cast<int>(second));
  note(std::string(e->Name()) + " Time/Date");
  e->SetAttribute("dateTime", text);
  e->DeleteChild(time);
  e->DeleteChild(date);
  return true;
}

// 0.9's TimeOfDay held a Time (hour, min, sec) and a Date (day, month, year), 1.0's one dateTime.
// Values that are not plain numbers (a parameter) are left for the reader to refuse at the
// element.
void Osc09Rewriter::environment(Element* e) {
  for (Element* time_of_day : osc09_children(e, "TimeOfDay")) date_time(time_of_day);
  for (Element* weather : osc09_children(e, "Weather")) {
    for (Element* p : osc09_children(weather, "Precipitation")) {
      if (p->Attribute("type") != nullptr) note("Precipitation type");
      move_attribute(p, "type", "precipitationType");
    }
  }
  for (Element* road : osc09_children(e, "RoadCondition")) {
    if (road->Attribute("frictionScale") != nullptr) note("RoadCondition frictionScale");
    move_attribute(road, "frictionScale", "frictionScaleFactor");
  }
}

}  // namespace corsa::xosc
