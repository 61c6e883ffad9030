// Global actions (§7.5) and user-defined actions. Traffic actions are in parse_traffic.cpp.

#include "parsers.h"

namespace corsa::xosc {

GlobalAction parse_traffic_action(ParseContext& ctx, const Element* e);

namespace {

ModifyRule parse_modify_rule(ParseContext& ctx, const Element* rule, double& value) {
  Children kids(ctx, rule, "ModifyRule");
  const Element* r = kids.choice();
  Children(ctx, r, "ValueRule");
  value = ctx.req_double(r, "value");
  return std::string_view(r->Name()) == "AddValue" ? ModifyRule::kAddValue
                                                   : ModifyRule::kMultiplyByValue;
}

bool is_numeric(ParameterType type) {
  return type == ParameterType::kDouble || type == ParameterType::kInt ||
         type == ParameterType::kUnsignedInt || type == ParameterType::kUnsignedShort;
}

// §9.1.4, §9.3: a SetAction's value must be one of the declared type, and only numbers can be
// modified. Checked at load, so that a bad value does not wait for its trigger to be found.
void check_set_value(ParseContext& ctx, const Element* set, std::optional<ParameterType> type,
                     const std::string& what, const std::string& value) {
  if (type && !ctx.typed_value(set, *type, value, "value of " + what)) {
    ctx.error(set, "value '" + clip(value) + "' cannot be set on " + what + " of type " +
                       type_name(*type));
  }
}

void check_modify(ParseContext& ctx, const Element* modify, std::optional<ParameterType> type,
                  const std::string& what) {
  if (type && !is_numeric(*type)) {
    ctx.error(modify, what + " is of type " + type_name(*type) +
                          "; a ModifyAction needs a numeric type (int, unsignedInt, "
                          "unsignedShort or double)");
  }
}

GlobalAction parse_entity_action(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "EntityAction");
  const std::string entity = ctx.req_str(e, "entityRef");
  ctx.use_entity(e, entity, "entityRef");
  const Element* a = kids.choice();
  if (std::string_view(a->Name()) == "AddEntityAction") {
    Children add_kids(ctx, a, "AddEntityAction");
    return AddEntityAction{entity, parse_position(ctx, add_kids.one("Position")), ctx.source(a)};
  }
  Children(ctx, a, "DeleteEntityAction");
  return DeleteEntityAction{entity, ctx.source(a)};
}

/// What tells the SetAction / ModifyAction of a ParameterAction from those of a VariableAction:
/// the XSD types of the two and the noun messages use.
struct ValueActionKind {
  std::string_view noun;         // "parameter"
  std::string_view set_type;     // "ParameterSetAction"
  std::string_view modify_type;  // "ParameterModifyAction"
};

/// The SetAction or ModifyAction `a` on the parameter or variable `name`, checked against its
/// declared type when that is known (§9.1.4, §9.3).
template <typename SetAction, typename ModifyAction>
GlobalAction parse_set_or_modify(ParseContext& ctx, const Element* a, const std::string& name,
                                 std::optional<ParameterType> type, const ValueActionKind& kind) {
  const std::string what = std::string(kind.noun) + " '" + clip(name) + "'";
  if (std::string_view(a->Name()) == "SetAction") {
    Children(ctx, a, kind.set_type);
    SetAction action{name, ctx.req_str(a, "value"), ctx.source(a)};
    check_set_value(ctx, a, type, what, action.value);
    return action;
  }
  check_modify(ctx, a, type, what);
  Children modify_kids(ctx, a, kind.modify_type);
  double value = 0.0;
  const ModifyRule rule = parse_modify_rule(ctx, modify_kids.one("Rule"), value);
  return ModifyAction{name, rule, value, ctx.source(a)};
}

GlobalAction parse_parameter_action(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "ParameterAction");
  ctx.deprecated(e, "<ParameterAction>", "<VariableAction>");
  const std::string parameter = ctx.parameter_name(e, "parameterRef");
  ctx.check_parameter_ref(e, parameter);
  const Element* a = kids.choice();
  const std::optional<ParameterType> type =
      ctx.record_entities ? ctx.parameter_type(parameter) : std::nullopt;
  return parse_set_or_modify<ParameterSetAction, ParameterModifyAction>(
      ctx, a, parameter, type, {"parameter", "ParameterSetAction", "ParameterModifyAction"});
}

GlobalAction parse_variable_action(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "VariableAction");
  const std::string variable = ctx.parameter_name(e, "variableRef");
  ctx.check_variable_ref(e, variable);
  const Element* a = kids.choice();
  const std::optional<ParameterType> type =
      ctx.record_entities ? ctx.variable_type(variable) : std::nullopt;
  return parse_set_or_modify<VariableSetAction, VariableModifyAction>(
      ctx, a, variable, type, {"variable", "VariableSetAction", "VariableModifyAction"});
}

GlobalAction parse_infrastructure_action(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "InfrastructureAction");
  const Element* signal = kids.one("TrafficSignalAction");
  Children signal_kids(ctx, signal, "TrafficSignalAction");
  const Element* a = signal_kids.choice();
  if (std::string_view(a->Name()) == "TrafficSignalControllerAction") {
    Children(ctx, a, "TrafficSignalControllerAction");
    TrafficSignalControllerAction action{ctx.req_str(a, "trafficSignalControllerRef"),
                                         ctx.req_str(a, "phase"), ctx.source(a)};
    ctx.check_signal_controller(a, action.traffic_signal_controller_ref, action.phase);
    return action;
  }
  Children(ctx, a, "TrafficSignalStateAction");
  return TrafficSignalStateAction{ctx.req_str(a, "name"), ctx.req_str(a, "state"), ctx.source(a)};
}

GlobalAction parse_environment_action(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "EnvironmentAction");
  const Element* which = kids.choice();
  EnvironmentAction action;
  action.source = ctx.source(e);
  if (std::string_view(which->Name()) == "Environment") {
    action.environment = parse_environment(ctx, which);
    return action;
  }
  action.environment = expand_catalog_reference<Environment>(
      ctx, which, {"Environment"}, [&](const Element* entry, CatalogOrigin& origin) {
        Environment environment =
            parse_environment(ctx, entry, {&origin.assignments, true, "environment"});
        environment.catalog = origin;
        return environment;
      });
  return action;
}

}  // namespace

GlobalAction parse_global_action(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "GlobalAction");
  const Element* a = kids.choice();
  const std::string_view name = a->Name();
  if (name == "EnvironmentAction") return parse_environment_action(ctx, a);
  if (name == "EntityAction") return parse_entity_action(ctx, a);
  if (name == "InfrastructureAction") return parse_infrastructure_action(ctx, a);
  if (name == "SetMonitorAction") {
    Children(ctx, a, "SetMonitorAction");
    SetMonitorAction action{ctx.parameter_name(a, "monitorRef"), ctx.req_bool(a, "value"),
                            ctx.source(a)};
    ctx.check_monitor_ref(a, action.monitor_ref);
    return action;
  }
  if (name == "ParameterAction") return parse_parameter_action(ctx, a);
  if (name == "TrafficAction") return parse_traffic_action(ctx, a);
  return parse_variable_action(ctx, a);
}

UserDefinedAction parse_user_defined_action(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "UserDefinedAction");
  const Element* command = kids.one("CustomCommandAction");
  Children(ctx, command, "CustomCommandAction");
  return UserDefinedAction{ctx.req_str(command, "type"), element_text(command), ctx.source(e)};
}

}  // namespace corsa::xosc
