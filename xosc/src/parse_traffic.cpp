// Traffic actions (§7.5.5): source, sink, swarm, area, stop; TrafficDefinition and
// TrafficDistribution.

#include "parsers.h"

namespace corsa::xosc {
namespace {

double weight_of(ParseContext& ctx, const Element* e) {
  const double weight = ctx.req_double(e, "weight");
  if (weight < 0.0) {
    ctx.fail(e, "weight must not be negative");
  }
  return weight;
}

ScenarioObjectTemplate parse_template(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "ScenarioObjectTemplate");
  ScenarioObjectTemplate object;
  kids.consume_all();
  const Element* definition = nullptr;
  for (const Element* child = e->FirstChildElement(); child != nullptr;
       child = child->NextSiblingElement()) {
    if (std::string_view(child->Name()) == "ObjectController") continue;
    if (definition != nullptr) {
      ctx.fail(child, "<ScenarioObjectTemplate> takes one object definition");
    }
    definition = child;
  }
  if (definition == nullptr) {
    ctx.fail(e, "<ScenarioObjectTemplate> needs an object definition");
  }
  object.object = parse_entity_object(ctx, definition);
  for (const Element* controller : kids.all("ObjectController")) {
    object.controllers.push_back(parse_object_controller(ctx, controller));
  }
  object.source = ctx.source(e);
  return object;
}

std::optional<TrafficDefinition> optional_definition(ParseContext& ctx, Children& kids) {
  const Element* e = kids.opt("TrafficDefinition");
  if (e == nullptr) return std::nullopt;
  return parse_traffic_definition(ctx, e);
}

std::optional<TrafficDistribution> optional_distribution(ParseContext& ctx, Children& kids) {
  const Element* e = kids.opt("TrafficDistribution");
  if (e == nullptr) return std::nullopt;
  return parse_traffic_distribution(ctx, e);
}

RoadRange parse_road_range(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "RoadRange");
  RoadRange range;
  range.length = ctx.opt_double(e, "length");
  for (const Element* c : kids.at_least("RoadCursor", 2)) {
    Children cursor_kids(ctx, c, "RoadCursor");
    RoadCursor cursor{ctx.req_str(c, "roadId"), ctx.opt_double(c, "s"), {}, ctx.source(c)};
    for (const Element* lane : cursor_kids.all("Lane")) {
      Children(ctx, lane, "Lane");
      cursor.lanes.push_back(static_cast<int>(ctx.req_int(lane, "id")));
    }
    range.cursors.push_back(std::move(cursor));
  }
  range.source = ctx.source(e);
  return range;
}

TrafficSwarmAction parse_swarm(ParseContext& ctx, const Element* e,
                               std::optional<std::string> name) {
  Children kids(ctx, e, "TrafficSwarmAction");
  TrafficSwarmAction action;
  action.traffic_name = std::move(name);
  // Every revision's XSD names the element CentralObject (its type is CentralSwarmObject); esmini's
  // swarm example writes the type name, whose meaning is plain.
  const Element* central = kids.opt("CentralObject");
  if (central == nullptr) {
    central = kids.opt("CentralSwarmObject");
    if (central != nullptr) {
      ctx.lenient(central, "<CentralSwarmObject> in <TrafficSwarmAction> is the type's name",
                  "<CentralObject>");
    } else {
      central = kids.one("CentralObject");
    }
  }
  Children(ctx, central, "CentralSwarmObject");
  action.central_object = ctx.req_str(central, "entityRef");
  ctx.use_entity(central, action.central_object, "entityRef");
  action.inner_radius = ctx.req_double(e, "innerRadius");
  action.number_of_vehicles =
      static_cast<uint32_t>(ctx.req_int(e, "numberOfVehicles", ParameterType::kUnsignedInt));
  // offset is required in every revision (1.0-1.3 XSD); esmini's swarm example leaves it out.
  // Read as 0: the ellipse centred on the central object.
  if (e->Attribute("offset") == nullptr) {
    ctx.lenient(e, "<TrafficSwarmAction> without offset",
                "offset 0: centred on the central object");
    action.offset = 0.0;
  } else {
    action.offset = ctx.req_double(e, "offset");
  }
  action.semi_major_axis = ctx.req_double(e, "semiMajorAxis");
  action.semi_minor_axis = ctx.req_double(e, "semiMinorAxis");
  action.velocity = ctx.opt_double(e, "velocity");
  deprecated_attribute(ctx, e, "velocity", {"InitialSpeedRange"});
  action.traffic_definition = optional_definition(ctx, kids);
  action.traffic_distribution = optional_distribution(ctx, kids);
  if (const Element* range = kids.opt("InitialSpeedRange")) {
    action.initial_speed_range = parse_range(ctx, range);
  }
  if (const Element* direction = kids.opt("DirectionOfTravelDistribution")) {
    Children(ctx, direction, "DirectionOfTravelDistribution");
    action.direction_same = ctx.req_double(direction, "same");
    action.direction_opposite = ctx.req_double(direction, "opposite");
  }
  action.source = ctx.source(e);
  return action;
}

TrafficAreaAction parse_area(ParseContext& ctx, const Element* e, std::optional<std::string> name) {
  Children kids(ctx, e, "TrafficAreaAction");
  TrafficAreaAction action;
  action.traffic_name = std::move(name);
  action.number_of_entities =
      static_cast<uint32_t>(ctx.req_int(e, "numberOfEntities", ParameterType::kUnsignedInt));
  action.continuous = ctx.req_bool(e, "continuous");
  action.traffic_distribution = parse_traffic_distribution(ctx, kids.one("TrafficDistribution"));
  const Element* area = kids.one("TrafficArea");
  Children area_kids(ctx, area, "TrafficArea");
  if (const Element* polygon = area_kids.opt("Polygon")) {
    Children polygon_kids(ctx, polygon, "Polygon");
    for (const Element* p : polygon_kids.at_least("Position", 3)) {
      action.polygon.push_back(parse_position(ctx, p));
    }
  } else {
    for (const Element* range : area_kids.at_least("RoadRange", 1)) {
      action.road_ranges.push_back(parse_road_range(ctx, range));
    }
  }
  action.source = ctx.source(e);
  return action;
}

}  // namespace

TrafficDefinition parse_traffic_definition(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "TrafficDefinition");
  ctx.deprecated(e, "<TrafficDefinition>", "<TrafficDistribution>");
  TrafficDefinition definition;
  definition.name = ctx.req_str(e, "name");
  const Element* categories = kids.one("VehicleCategoryDistribution");
  Children category_kids(ctx, categories, "VehicleCategoryDistribution");
  for (const Element* entry : category_kids.at_least("VehicleCategoryDistributionEntry", 1)) {
    Children(ctx, entry, "VehicleCategoryDistributionEntry");
    definition.vehicle_categories.push_back(
        {ctx.req_enum<VehicleCategory>(entry, "category"), weight_of(ctx, entry)});
  }
  if (const Element* roles = kids.opt("VehicleRoleDistribution")) {
    Children role_kids(ctx, roles, "VehicleRoleDistribution");
    for (const Element* entry : role_kids.at_least("VehicleRoleDistributionEntry", 1)) {
      Children(ctx, entry, "VehicleRoleDistributionEntry");
      definition.vehicle_roles.push_back(
          {ctx.req_enum<Role>(entry, "role"), weight_of(ctx, entry)});
    }
  }
  const Element* controllers = kids.one("ControllerDistribution");
  Children controller_kids(ctx, controllers, "ControllerDistribution");
  for (const Element* entry : controller_kids.at_least("ControllerDistributionEntry", 1)) {
    Children entry_kids(ctx, entry, "ControllerDistributionEntry");
    definition.controllers.push_back(
        {weight_of(ctx, entry), parse_controller_choice(ctx, entry_kids.choice())});
  }
  definition.source = ctx.source(e);
  return definition;
}

TrafficDistribution parse_traffic_distribution(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "TrafficDistribution");
  TrafficDistribution distribution;
  for (const Element* entry : kids.at_least("TrafficDistributionEntry", 1)) {
    Children entry_kids(ctx, entry, "TrafficDistributionEntry");
    TrafficDistributionEntry value;
    value.weight = weight_of(ctx, entry);
    const Element* entities = entry_kids.one("EntityDistribution");
    Children entity_kids(ctx, entities, "EntityDistribution");
    for (const Element* item : entity_kids.at_least("EntityDistributionEntry", 1)) {
      Children item_kids(ctx, item, "EntityDistributionEntry");
      value.entities.push_back(
          {weight_of(ctx, item), parse_template(ctx, item_kids.one("ScenarioObjectTemplate"))});
    }
    if (const Element* properties = entry_kids.opt("Properties")) {
      value.properties = parse_properties(ctx, properties);
    }
    value.source = ctx.source(entry);
    distribution.entries.push_back(std::move(value));
  }
  distribution.source = ctx.source(e);
  return distribution;
}

GlobalAction parse_traffic_action(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "TrafficAction");
  std::optional<std::string> name = ctx.opt_str(e, "trafficName");
  const Element* a = kids.choice();
  const std::string_view kind = a->Name();
  if (kind == "TrafficSourceAction") {
    Children source_kids(ctx, a, "TrafficSourceAction");
    TrafficSourceAction action;
    action.traffic_name = std::move(name);
    action.radius = ctx.req_double(a, "radius");
    action.rate = ctx.req_double(a, "rate");
    action.speed = ctx.opt_double(a, "speed");
    if (deprecated_attribute(ctx, a, "velocity", {"speed"})) {
      action.speed = action.speed.value_or(*ctx.opt_double(a, "velocity"));
    }
    action.position = parse_position(ctx, source_kids.one("Position"));
    action.traffic_definition = optional_definition(ctx, source_kids);
    action.traffic_distribution = optional_distribution(ctx, source_kids);
    action.source = ctx.source(a);
    return action;
  }
  if (kind == "TrafficSinkAction") {
    Children sink_kids(ctx, a, "TrafficSinkAction");
    TrafficSinkAction action;
    action.traffic_name = std::move(name);
    action.radius = ctx.req_double(a, "radius");
    action.rate = ctx.opt_double(a, "rate");
    action.position = parse_position(ctx, sink_kids.one("Position"));
    action.traffic_definition = optional_definition(ctx, sink_kids);
    action.source = ctx.source(a);
    return action;
  }
  if (kind == "TrafficSwarmAction") return parse_swarm(ctx, a, std::move(name));
  if (kind == "TrafficAreaAction") return parse_area(ctx, a, std::move(name));
  Children(ctx, a, "TrafficStopAction");
  return TrafficStopAction{std::move(name), ctx.source(a)};
}

}  // namespace corsa::xosc
