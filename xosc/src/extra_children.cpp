// The content of a child beyond what its parent allows (a second child of a choice, a second
// <Position> where one is allowed): the cardinality error is reported where the parent is read,
// and the extra child is read here for the errors inside it, then dropped.

#include <string_view>
#include <utility>

#include "parsers.h"
#include "schema_table.h"

namespace corsa::xosc {
namespace {

using ExtraChildReader = void (*)(ParseContext&, const Element*);

// Element kinds whose parse function stands on its own (no parent state): the extra child is read
// as fully as the first. Others are read by read_extra_generically.
constexpr std::pair<std::string_view, ExtraChildReader> kExtraChildReaders[] = {
    {"PrivateAction", [](ParseContext& c, const Element* e) { parse_private_action(c, e); }},
    {"GlobalAction", [](ParseContext& c, const Element* e) { parse_global_action(c, e); }},
    {"UserDefinedAction",
     [](ParseContext& c, const Element* e) { parse_user_defined_action(c, e); }},
    {"Position", [](ParseContext& c, const Element* e) { parse_position(c, e); }},
    {"Orientation", [](ParseContext& c, const Element* e) { parse_orientation(c, e); }},
    {"Route", [](ParseContext& c, const Element* e) { parse_route(c, e); }},
    {"Trajectory", [](ParseContext& c, const Element* e) { parse_trajectory(c, e); }},
    {"TimeReference", [](ParseContext& c, const Element* e) { parse_time_reference(c, e); }},
    {"BoundingBox", [](ParseContext& c, const Element* e) { parse_bounding_box(c, e); }},
    {"Vehicle", [](ParseContext& c, const Element* e) { parse_vehicle(c, e); }},
    {"Pedestrian", [](ParseContext& c, const Element* e) { parse_pedestrian(c, e); }},
    {"MiscObject", [](ParseContext& c, const Element* e) { parse_misc_object(c, e); }},
    {"Controller", [](ParseContext& c, const Element* e) { parse_controller(c, e); }},
    {"ObjectController", [](ParseContext& c, const Element* e) { parse_object_controller(c, e); }},
    {"Environment", [](ParseContext& c, const Element* e) { parse_environment(c, e); }},
    {"TrafficDefinition",
     [](ParseContext& c, const Element* e) { parse_traffic_definition(c, e); }},
    {"StartTrigger", [](ParseContext& c, const Element* e) { parse_trigger(c, e); }},
    {"StopTrigger", [](ParseContext& c, const Element* e) { parse_trigger(c, e); }},
    {"Maneuver", [](ParseContext& c, const Element* e) { parse_maneuver(c, e); }},
    {"Properties", [](ParseContext& c, const Element* e) { parse_properties(c, e); }},
    {"Range", [](ParseContext& c, const Element* e) { parse_range(c, e); }},
};

// Attributes that name a parameter or variable: taken as written, not resolved.
bool names_a_reference(std::string_view attribute) {
  return attribute == "parameterRef" || attribute == "variableRef";
}

// An element of no kind above: its children are checked against its type's rule (unknown
// elements), every attribute is resolved (undefined parameters, bad expressions, uses of
// parameters in error), and its children are read the same way.
void read_extra_generically(ParseContext& ctx, const Element* element) {
  const TypeRule* rule = find_type_rule(element->Name());
  if (rule != nullptr) {
    Children kids(ctx, element, element->Name());
    kids.consume_all();
  }
  for (const tinyxml2::XMLAttribute* a = element->FirstAttribute(); a != nullptr; a = a->Next()) {
    if (!names_a_reference(a->Name())) ctx.attr(element, a->Name());
  }
  for (const Element* child = element->FirstChildElement(); child != nullptr;
       child = child->NextSiblingElement()) {
    // An unknown element is reported by Children and not read.
    if (rule != nullptr && !rule->allows_child(child->Name())) continue;
    ctx.recover([&] { read_extra_child(ctx, child); });
  }
}

}  // namespace

void read_extra_child(ParseContext& ctx, const Element* element) {
  const std::string_view name = element->Name();
  for (const auto& [kind, reader] : kExtraChildReaders) {
    if (kind == name) {
      reader(ctx, element);
      return;
    }
  }
  read_extra_generically(ctx, element);
}

}  // namespace corsa::xosc
