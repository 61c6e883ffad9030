// ParameterAction Set/Modify (OpenSCENARIO 1.3 §7.5.3, deprecated in favour of VariableAction)
// and VariableAction Set/Modify (§7.5.4): instantaneous changes of a run-time value, checked
// against the declared type.

#include <cmath>

#include "actions/action_makers.h"
#include "corsa/core/strings.h"
#include "positions/position_common.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

enum class Store { kParameter, kVariable };

xosc::Value& need_value(SimState& state, Store store, const std::string& name,
                        const xosc::Source& source) {
  ValueStore& values = store == Store::kParameter ? state.parameters : state.variables;
  xosc::Value* value = values.find(name);
  if (value == nullptr) {
    fail(source, std::string(store == Store::kParameter ? "parameter" : "variable") + " '" + name +
                     "' is not declared");
  }
  return *value;
}

class SetInstance final : public InstantAction {
 public:
  SetInstance(Store store, const std::string& name, const std::string& text,
              const xosc::Source& source)
      : store_(store), name_(name), text_(text), source_(source) {}
  void start(ActionContext& context) override {
    xosc::Value& value = need_value(context.state, store_, name_, source_);
    const auto parsed = xosc::parse_value(value.type, text_);
    if (!parsed) {
      fail(source_, "'" + text_ + "' is not a valid " + std::string(xosc::to_string(value.type)) +
                        " for '" + name_ + "'");
    }
    value = *parsed;
  }

 private:
  Store store_;
  const std::string& name_;
  const std::string& text_;
  const xosc::Source& source_;
};

class ModifyInstance final : public InstantAction {
 public:
  ModifyInstance(Store store, const std::string& name, xosc::ModifyRule rule, double operand,
                 const xosc::Source& source)
      : store_(store), name_(name), rule_(rule), operand_(operand), source_(source) {}
  void start(ActionContext& context) override {
    xosc::Value& value = need_value(context.state, store_, name_, source_);
    const auto current = value.number();
    if (!current || value.type == xosc::ParameterType::kBoolean) {
      fail(source_, "'" + name_ + "' is not numeric and cannot be modified");
    }
    const double result =
        rule_ == xosc::ModifyRule::kAddValue ? *current + operand_ : *current * operand_;
    const std::string text = value.type == xosc::ParameterType::kDouble
                                 ? format_double(result)
                                 : std::to_string(std::llround(result));
    const auto parsed = xosc::parse_value(value.type, text);
    if (!parsed) {
      fail(source_, "modifying '" + name_ + "' gives " + format_double(result) +
                        ", outside its type " + std::string(xosc::to_string(value.type)));
    }
    value = *parsed;
  }

 private:
  Store store_;
  const std::string& name_;
  xosc::ModifyRule rule_;
  double operand_;
  const xosc::Source& source_;
};

}  // namespace

std::unique_ptr<ActionInstance> make_parameter_set_action(const xosc::ParameterSetAction& action) {
  return std::make_unique<SetInstance>(Store::kParameter, action.parameter_ref, action.value,
                                       action.source);
}

std::unique_ptr<ActionInstance> make_parameter_modify_action(
    const xosc::ParameterModifyAction& action) {
  return std::make_unique<ModifyInstance>(Store::kParameter, action.parameter_ref, action.rule,
                                          action.value, action.source);
}

std::unique_ptr<ActionInstance> make_variable_set_action(const xosc::VariableSetAction& action) {
  return std::make_unique<SetInstance>(Store::kVariable, action.variable_ref, action.value,
                                       action.source);
}

std::unique_ptr<ActionInstance> make_variable_modify_action(
    const xosc::VariableModifyAction& action) {
  return std::make_unique<ModifyInstance>(Store::kVariable, action.variable_ref, action.rule,
                                          action.value, action.source);
}

}  // namespace corsa::engine::detail
