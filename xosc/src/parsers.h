#pragma once

// Internal: one parse function per OpenSCENARIO element kind. Each takes the element and returns
// the model value; bad input throws InputError through ParseContext::fail.

#include <vector>

#include "corsa/xosc/catalogs.h"
#include "corsa/xosc/conditions.h"
#include "corsa/xosc/distributions.h"
#include "corsa/xosc/entities.h"
#include "corsa/xosc/environment.h"
#include "corsa/xosc/global_actions.h"
#include "corsa/xosc/positions.h"
#include "corsa/xosc/private_actions.h"
#include "corsa/xosc/scenario.h"
#include "corsa/xosc/storyboard.h"
#include "corsa/xosc/trajectories.h"
#include "parse_context.h"

namespace corsa::xosc {

/// How a catalogable element's ParameterDeclarations open their scope: inline elements see the
/// enclosing parameters; catalog entries see only their own, with the reference's assignments.
struct EntryScope {
  const std::vector<ParameterAssignment>* assignments = nullptr;
  bool isolated = false;
  std::string_view owner = "element";
};

// common
FileHeader parse_file_header(ParseContext& ctx, const Element* element);
Properties parse_properties(ParseContext& ctx, const Element* element);
File parse_file(ParseContext& ctx, const Element* element);
Range parse_range(ParseContext& ctx, const Element* element);
std::vector<ParameterAssignment> parse_parameter_assignments(ParseContext& ctx,
                                                             const Element* element);
/// ParameterDeclarations child of `kids` (if any) as a new scope; pops with ScopeGuard.
std::vector<ParameterDeclaration> open_scope(ParseContext& ctx, Children& kids,
                                             const EntryScope& scope);

// positions and paths
Orientation parse_orientation(ParseContext& ctx, const Element* element);
Position parse_position(ParseContext& ctx, const Element* element);
Route parse_route(ParseContext& ctx, const Element* element, const EntryScope& scope = {});
Trajectory parse_trajectory(ParseContext& ctx, const Element* element,
                            const EntryScope& scope = {});
/// RouteRef / AssignRouteAction: an inline Route or a CatalogReference.
Route parse_route_choice(ParseContext& ctx, const Element* route_or_reference);
Trajectory parse_trajectory_choice(ParseContext& ctx, const Element* trajectory_or_reference);
TimeReference parse_time_reference(ParseContext& ctx, const Element* element);

// entities
BoundingBox parse_bounding_box(ParseContext& ctx, const Element* element);
Vehicle parse_vehicle(ParseContext& ctx, const Element* element, const EntryScope& scope = {});
Pedestrian parse_pedestrian(ParseContext& ctx, const Element* element,
                            const EntryScope& scope = {});
MiscObject parse_misc_object(ParseContext& ctx, const Element* element,
                             const EntryScope& scope = {});
Controller parse_controller(ParseContext& ctx, const Element* element,
                            const EntryScope& scope = {});
/// A Controller element or a CatalogReference to one.
Controller parse_controller_choice(ParseContext& ctx, const Element* element);
ObjectController parse_object_controller(ParseContext& ctx, const Element* element);
/// The EntityObject choice (CatalogReference, Vehicle, Pedestrian, MiscObject,
/// ExternalObjectReference) among the children of a ScenarioObject / ScenarioObjectTemplate.
EntityObject parse_entity_object(ParseContext& ctx, const Element* element);
ScenarioObject parse_scenario_object(ParseContext& ctx, const Element* element);
/// A Vehicle's <Trailer>; nothing when it names no trailer (an empty reference).
std::optional<Trailer> parse_trailer(ParseContext& ctx, const Element* element);
Entities parse_entities(ParseContext& ctx, const Element* element);

// environment
Environment parse_environment(ParseContext& ctx, const Element* element,
                              const EntryScope& scope = {});

// actions
/// `in_init`: an Init Private's action, where a 1.0 ControllerAction pair is two actions (the
/// caller adds the override: controller_override_pair, parse_controller_override).
PrivateAction parse_private_action(ParseContext& ctx, const Element* element, bool in_init = false);
/// The OverrideControllerValueAction of a 1.0 ControllerAction holding it beside an
/// AssignControllerAction, in this PrivateAction; null otherwise.
const Element* controller_override_pair(const Element* private_action);
PrivateAction parse_controller_override(ParseContext& ctx, const Element* e);
GlobalAction parse_global_action(ParseContext& ctx, const Element* element);
UserDefinedAction parse_user_defined_action(ParseContext& ctx, const Element* element);
TrafficDistribution parse_traffic_distribution(ParseContext& ctx, const Element* element);
TrafficDefinition parse_traffic_definition(ParseContext& ctx, const Element* element);

// conditions
Trigger parse_trigger(ParseContext& ctx, const Element* element);
/// One warning per file for the CARLA evaluation criteria parse_trigger left out (their count and
/// the first's place; an error under --strict), and a note at each.
void report_carla_criteria(ParseContext& ctx);
/// A StartTrigger; an empty one (1.0 style) is read as none, with a lenient-reading warning.
std::optional<Trigger> parse_start_trigger(ParseContext& ctx, const Element* element);

// storyboard
Maneuver parse_maneuver(ParseContext& ctx, const Element* element, const EntryScope& scope = {});
Storyboard parse_storyboard(ParseContext& ctx, const Element* element);

// catalogs
/// Expands a CatalogReference whose entry must be one of `kinds` (element names, e.g.
/// "Vehicle"). `parse` is called with the entry element and its isolated scope.
template <class T, class Parse>
T expand_catalog_reference(ParseContext& ctx, const Element* reference,
                           std::initializer_list<std::string_view> kinds, Parse parse);
Catalog parse_catalog(ParseContext& ctx, const Element* element);

// distributions
ParameterValueDistribution parse_parameter_value_distribution(ParseContext& ctx,
                                                              const Element* element);

/// A deprecated 1.0/1.1 attribute: when present, a warning naming its replacements (attributes,
/// or child elements when capitalised); written together with one of them, an error. Returns
/// whether the attribute is present.
bool deprecated_attribute(ParseContext& ctx, const Element* element, const char* name,
                          std::initializer_list<const char*> replacements);

}  // namespace corsa::xosc

#include "catalog_resolver.h"
