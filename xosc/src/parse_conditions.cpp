// Conditions and triggers (§8.3-8.5): 16 ByEntity and 8 ByValue conditions.

#include <algorithm>

#include "parsers.h"

namespace corsa::xosc {
namespace {

std::string entity_attribute(ParseContext& ctx, const Element* e, const char* name) {
  std::string value = ctx.req_str(e, name);
  ctx.use_entity(e, value, name);
  return value;
}

// Attributes shared by the distance-like conditions (TimeHeadway, TimeToCollision, Distance).
template <class T>
void read_distance_options(ParseContext& ctx, const Element* e, T& condition) {
  condition.value = ctx.req_double(e, "value");
  condition.freespace = ctx.req_bool(e, "freespace");
  condition.rule = ctx.req_enum<Rule>(e, "rule");
  condition.along_route = ctx.opt_bool(e, "alongRoute");
  deprecated_attribute(ctx, e, "alongRoute", {"coordinateSystem", "relativeDistanceType"});
  condition.coordinate_system = ctx.opt_enum<CoordinateSystem>(e, "coordinateSystem");
  condition.relative_distance_type = ctx.opt_enum<RelativeDistanceType>(e, "relativeDistanceType");
  condition.routing_algorithm = ctx.opt_enum<RoutingAlgorithm>(e, "routingAlgorithm");
  condition.source = ctx.source(e);
}

EntityCondition parse_simple_entity_condition(ParseContext& ctx, const Element* c,
                                              std::string_view name) {
  if (name == "EndOfRoadCondition") {
    Children(ctx, c, "EndOfRoadCondition");
    return EndOfRoadCondition{ctx.req_double(c, "duration"), ctx.source(c)};
  }
  if (name == "OffroadCondition") {
    Children(ctx, c, "OffroadCondition");
    return OffroadCondition{ctx.req_double(c, "duration"), ctx.source(c)};
  }
  if (name == "StandStillCondition") {
    Children(ctx, c, "StandStillCondition");
    return StandStillCondition{ctx.req_double(c, "duration"), ctx.source(c)};
  }
  if (name == "TraveledDistanceCondition") {
    Children(ctx, c, "TraveledDistanceCondition");
    return TraveledDistanceCondition{ctx.req_double(c, "value"), ctx.source(c)};
  }
  if (name == "AccelerationCondition") {
    Children(ctx, c, "AccelerationCondition");
    return AccelerationCondition{ctx.req_double(c, "value"), ctx.req_enum<Rule>(c, "rule"),
                                 ctx.opt_enum<DirectionalDimension>(c, "direction"), ctx.source(c)};
  }
  if (name == "SpeedCondition") {
    Children(ctx, c, "SpeedCondition");
    return SpeedCondition{ctx.req_double(c, "value"), ctx.req_enum<Rule>(c, "rule"),
                          ctx.opt_enum<DirectionalDimension>(c, "direction"), ctx.source(c)};
  }
  if (name == "RelativeSpeedCondition") {
    Children(ctx, c, "RelativeSpeedCondition");
    return RelativeSpeedCondition{entity_attribute(ctx, c, "entityRef"), ctx.req_double(c, "value"),
                                  ctx.req_enum<Rule>(c, "rule"),
                                  ctx.opt_enum<DirectionalDimension>(c, "direction"),
                                  ctx.source(c)};
  }
  if (name == "AngleCondition") {
    Children(ctx, c, "AngleCondition");
    return AngleCondition{ctx.req_enum<AngleType>(c, "angleType"), ctx.req_double(c, "angle"),
                          ctx.req_double(c, "angleTolerance"),
                          ctx.opt_enum<CoordinateSystem>(c, "coordinateSystem"), ctx.source(c)};
  }
  Children(ctx, c, "RelativeAngleCondition");
  return RelativeAngleCondition{entity_attribute(ctx, c, "entityRef"),
                                ctx.req_enum<AngleType>(c, "angleType"),
                                ctx.req_double(c, "angle"),
                                ctx.req_double(c, "angleTolerance"),
                                ctx.opt_enum<CoordinateSystem>(c, "coordinateSystem"),
                                ctx.source(c)};
}

CollisionCondition parse_collision_condition(ParseContext& ctx, const Element* c) {
  Children collision_kids(ctx, c, "CollisionCondition");
  CollisionCondition condition;
  const Element* target = collision_kids.choice();
  if (std::string_view(target->Name()) == "EntityRef") {
    Children(ctx, target, "EntityRef");
    condition.entity_ref = entity_attribute(ctx, target, "entityRef");
  } else {
    Children(ctx, target, "ByObjectType");
    condition.by_type = ctx.req_enum<ObjectType>(target, "type");
  }
  condition.source = ctx.source(c);
  return condition;
}

TimeToCollisionCondition parse_time_to_collision_condition(ParseContext& ctx, const Element* c) {
  Children ttc_kids(ctx, c, "TimeToCollisionCondition");
  TimeToCollisionCondition condition;
  read_distance_options(ctx, c, condition);
  const Element* target = ttc_kids.one("TimeToCollisionConditionTarget");
  Children target_kids(ctx, target, "TimeToCollisionConditionTarget");
  const Element* t = target_kids.choice();
  if (std::string_view(t->Name()) == "EntityRef") {
    Children(ctx, t, "EntityRef");
    condition.target_entity_ref = entity_attribute(ctx, t, "entityRef");
  } else {
    condition.target_position = parse_position(ctx, t);
  }
  return condition;
}

RelativeClearanceCondition parse_relative_clearance_condition(ParseContext& ctx, const Element* c) {
  Children clearance_kids(ctx, c, "RelativeClearanceCondition");
  RelativeClearanceCondition condition;
  condition.opposite_lanes = ctx.req_bool(c, "oppositeLanes");
  condition.free_space = ctx.req_bool(c, "freeSpace");
  condition.distance_forward = ctx.opt_double(c, "distanceForward");
  condition.distance_backward = ctx.opt_double(c, "distanceBackward");
  for (const Element* range : clearance_kids.all("RelativeLaneRange")) {
    Children(ctx, range, "RelativeLaneRange");
    RelativeLaneRange lanes;
    if (const auto from = ctx.opt_int(range, "from")) lanes.from = static_cast<int>(*from);
    if (const auto to = ctx.opt_int(range, "to")) lanes.to = static_cast<int>(*to);
    condition.lane_ranges.push_back(lanes);
  }
  for (const Element* ref : clearance_kids.all("EntityRef")) {
    Children(ctx, ref, "EntityRef");
    condition.entity_refs.push_back(entity_attribute(ctx, ref, "entityRef"));
  }
  condition.source = ctx.source(c);
  return condition;
}

EntityCondition parse_entity_condition(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "EntityCondition");
  const Element* c = kids.choice();
  const std::string_view name = c->Name();
  if (name == "CollisionCondition") {
    return parse_collision_condition(ctx, c);
  }
  if (name == "TimeHeadwayCondition") {
    Children(ctx, c, "TimeHeadwayCondition");
    TimeHeadwayCondition condition;
    condition.entity_ref = entity_attribute(ctx, c, "entityRef");
    read_distance_options(ctx, c, condition);
    return condition;
  }
  if (name == "TimeToCollisionCondition") {
    return parse_time_to_collision_condition(ctx, c);
  }
  if (name == "ReachPositionCondition") {
    Children reach_kids(ctx, c, "ReachPositionCondition");
    ctx.deprecated(c, "<ReachPositionCondition>", "<DistanceCondition>");
    return ReachPositionCondition{parse_position(ctx, reach_kids.one("Position")),
                                  ctx.req_double(c, "tolerance"), ctx.source(c)};
  }
  if (name == "DistanceCondition") {
    Children distance_kids(ctx, c, "DistanceCondition");
    DistanceCondition condition;
    read_distance_options(ctx, c, condition);
    condition.position = parse_position(ctx, distance_kids.one("Position"));
    return condition;
  }
  if (name == "RelativeDistanceCondition") {
    Children(ctx, c, "RelativeDistanceCondition");
    return RelativeDistanceCondition{entity_attribute(ctx, c, "entityRef"),
                                     ctx.req_double(c, "value"),
                                     ctx.req_bool(c, "freespace"),
                                     ctx.req_enum<RelativeDistanceType>(c, "relativeDistanceType"),
                                     ctx.req_enum<Rule>(c, "rule"),
                                     ctx.opt_enum<CoordinateSystem>(c, "coordinateSystem"),
                                     ctx.opt_enum<RoutingAlgorithm>(c, "routingAlgorithm"),
                                     ctx.source(c)};
  }
  if (name == "RelativeClearanceCondition") {
    return parse_relative_clearance_condition(ctx, c);
  }
  return parse_simple_entity_condition(ctx, c, name);
}

ByEntityCondition parse_by_entity(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "ByEntityCondition");
  ByEntityCondition condition;
  const Element* triggering = kids.one("TriggeringEntities");
  Children triggering_kids(ctx, triggering, "TriggeringEntities");
  condition.triggering_entities.rule =
      ctx.req_enum<TriggeringEntitiesRule>(triggering, "triggeringEntitiesRule");
  for (const Element* ref : triggering_kids.at_least("EntityRef", 1)) {
    Children(ctx, ref, "EntityRef");
    condition.triggering_entities.entity_refs.push_back(entity_attribute(ctx, ref, "entityRef"));
  }
  condition.triggering_entities.source = ctx.source(triggering);
  condition.condition = parse_entity_condition(ctx, kids.one("EntityCondition"));
  condition.source = ctx.source(e);
  return condition;
}

ByValueCondition parse_by_value(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "ByValueCondition");
  const Element* c = kids.choice();
  const std::string_view name = c->Name();
  if (name == "ParameterCondition") {
    Children(ctx, c, "ParameterCondition");
    ParameterCondition condition{ctx.parameter_name(c, "parameterRef"),
                                 ctx.req_enum<Rule>(c, "rule"), ctx.req_str(c, "value"),
                                 ctx.source(c)};
    ctx.check_parameter_ref(c, condition.parameter_ref);
    return condition;
  }
  if (name == "TimeOfDayCondition") {
    Children(ctx, c, "TimeOfDayCondition");
    TimeOfDayCondition condition{ctx.req_str(c, "dateTime"), ctx.req_enum<Rule>(c, "rule"),
                                 ctx.source(c)};
    if (!parse_value(ParameterType::kDateTime, condition.date_time)) {
      ctx.fail(c, "attribute dateTime: '" + condition.date_time + "' is not a valid dateTime");
    }
    return condition;
  }
  if (name == "SimulationTimeCondition") {
    Children(ctx, c, "SimulationTimeCondition");
    return SimulationTimeCondition{ctx.req_double(c, "value"), ctx.req_enum<Rule>(c, "rule"),
                                   ctx.source(c)};
  }
  if (name == "StoryboardElementStateCondition") {
    Children(ctx, c, "StoryboardElementStateCondition");
    StoryboardElementStateCondition condition;
    condition.type = ctx.req_enum<StoryboardElementType>(c, "storyboardElementType");
    condition.storyboard_element_ref = ctx.req_str(c, "storyboardElementRef");
    condition.state = ctx.req_enum<StoryboardElementState>(c, "state");
    condition.source = ctx.source(c);
    ctx.storyboard_refs.emplace(std::tuple(condition.source.file.get(), condition.source.line,
                                           condition.storyboard_element_ref),
                                ctx.defer_attribute_line(c, "storyboardElementRef"));
    return condition;
  }
  if (name == "UserDefinedValueCondition") {
    Children(ctx, c, "UserDefinedValueCondition");
    return UserDefinedValueCondition{ctx.req_str(c, "name"), ctx.req_enum<Rule>(c, "rule"),
                                     ctx.req_str(c, "value"), ctx.source(c)};
  }
  if (name == "TrafficSignalCondition") {
    Children(ctx, c, "TrafficSignalCondition");
    return TrafficSignalCondition{ctx.req_str(c, "name"), ctx.req_str(c, "state"), ctx.source(c)};
  }
  if (name == "TrafficSignalControllerCondition") {
    Children(ctx, c, "TrafficSignalControllerCondition");
    TrafficSignalControllerCondition condition{ctx.req_str(c, "trafficSignalControllerRef"),
                                               ctx.req_str(c, "phase"), ctx.source(c)};
    ctx.check_signal_controller(c, condition.traffic_signal_controller_ref, condition.phase);
    return condition;
  }
  Children(ctx, c, "VariableCondition");
  VariableCondition condition{ctx.parameter_name(c, "variableRef"), ctx.req_enum<Rule>(c, "rule"),
                              ctx.req_str(c, "value"), ctx.source(c)};
  ctx.check_variable_ref(c, condition.variable_ref);
  return condition;
}

Condition parse_condition(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "Condition");
  Condition condition;
  condition.name = ctx.req_str(e, "name");
  condition.delay = ctx.req_double(e, "delay");
  if (condition.delay < 0.0) {
    ctx.fail(e, "condition delay must not be negative");
  }
  std::optional<ConditionEdge> edge = ctx.opt_enum<ConditionEdge>(e, "conditionEdge");
  if (edge && e->Attribute("edge") != nullptr) {
    ctx.error(e, "attributes 'edge' and 'conditionEdge' together (the file says it twice)");
  } else if (!edge && e->Attribute("edge") != nullptr) {
    // `edge` is the attribute's name in pre-1.0 drafts; esmini's examples still write it.
    edge = ctx.opt_enum<ConditionEdge>(e, "edge");
    ctx.lenient(e, "attribute 'edge' of <Condition>",
                "conditionEdge " + std::string(to_string(*edge)));
  } else if (!edge) {
    // §7.6.2: `none` evaluates the condition as it is; an edge needs saying (esmini's 1.0
    // examples leave the attribute out for the plain condition).
    ctx.lenient(e, "<Condition> without conditionEdge", "conditionEdge none");
  }
  condition.edge = edge.value_or(ConditionEdge::kNone);
  const Element* kind = kids.choice();
  if (std::string_view(kind->Name()) == "ByEntityCondition") {
    condition.kind = parse_by_entity(ctx, kind);
  } else {
    condition.kind = parse_by_value(ctx, kind);
  }
  condition.source = ctx.source(e);
  return condition;
}

// CARLA's scenario_runner writes its evaluation criteria (collision, driven distance, ...) as
// conditions named "criteria_..." of a ParameterCondition on a parameter nobody declares
// (`parameterRef=""`, `"distance_success"`); it takes them out of the trigger and evaluates them
// as pass/fail tests. Such a condition never holds here, and neither does its group.
bool carla_criterion(ParseContext& ctx, const Element* condition) {
  const char* name = condition->Attribute("name");
  if (name == nullptr || !std::string_view(name).starts_with("criteria_")) return false;
  const Element* by_value = condition->FirstChildElement("ByValueCondition");
  const Element* c = by_value == nullptr ? nullptr : by_value->FirstChildElement();
  if (c == nullptr || std::string_view(c->Name()) != "ParameterCondition" ||
      c->Attribute("parameterRef") == nullptr || !ctx.record_entities) {
    return false;
  }
  const std::string ref = ctx.parameter_name(c, "parameterRef");
  return !ctx.global_parameters.contains(ref) && !ctx.parameter_visible(ref);
}

}  // namespace

Trigger parse_trigger(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "Trigger");
  Trigger trigger;
  trigger.source = ctx.source(e);
  for (const Element* group : kids.all("ConditionGroup")) {
    Children group_kids(ctx, group, "ConditionGroup");
    ConditionGroup value;
    value.source = ctx.source(group);
    bool criterion = false;
    for (const Element* condition : group_kids.at_least("Condition", 1)) {
      if (carla_criterion(ctx, condition)) {
        criterion = true;
        ctx.carla_criteria.emplace_back(ctx.source(condition), condition->Attribute("name"));
        continue;
      }
      ctx.recover([&] { value.conditions.push_back(parse_condition(ctx, condition)); });
    }
    if (!criterion) trigger.groups.push_back(std::move(value));
  }
  return trigger;
}

// A CARLA scenario gives its criteria together (7 in scenario_runner's LaneChangeSimple): one
// warning per file says how many and where the first is, and a note at each says which it is.
void report_carla_criteria(ParseContext& ctx) {
  const auto criteria = std::move(ctx.carla_criteria);
  ctx.carla_criteria.clear();
  std::vector<std::string> files;  // in the order first met
  for (const auto& [where, name] : criteria) {
    if (std::find(files.begin(), files.end(), where.file_name()) == files.end()) {
      files.push_back(where.file_name());
    }
  }
  for (const std::string& file : files) {
    std::vector<const std::pair<Source, std::string>*> in_file;
    for (const auto& criterion : criteria) {
      if (criterion.first.file_name() == file) in_file.push_back(&criterion);
    }
    const size_t count = in_file.size();
    ctx.lenient(in_file.front()->first,
                std::to_string(count) +
                    (count == 1 ? " condition is a CARLA evaluation criterion"
                                : " conditions are CARLA evaluation criteria") +
                    " (ParameterConditions on undeclared parameters; the first '" +
                    clip(in_file.front()->second) + "', each in a note)",
                count == 1 ? "a condition that never holds: its ConditionGroup is left out"
                           : "conditions that never hold: their ConditionGroups are left out");
    for (const auto* criterion : in_file) {
      Diagnostic note =
          criterion->first.warning("CARLA evaluation criterion '" + clip(criterion->second) +
                                   "': its ConditionGroup is left out");
      note.severity = Severity::kNote;
      ctx.diagnostics().add(std::move(note));
    }
  }
}

std::optional<Trigger> parse_start_trigger(ParseContext& ctx, const Element* e) {
  Trigger trigger = parse_trigger(ctx, e);
  if (!trigger.groups.empty()) return trigger;
  // §7.6.1: a trigger is the OR of its condition groups, so an empty one would never fire; the
  // standard keeps empty triggers only for compatibility with 1.0, where an Act and an Event
  // had to have a StartTrigger and `<StartTrigger/>` was how "no condition" was written.
  ctx.lenient(e, "empty <StartTrigger/>", "no StartTrigger: the element starts with its parent");
  return std::nullopt;
}

}  // namespace corsa::xosc
