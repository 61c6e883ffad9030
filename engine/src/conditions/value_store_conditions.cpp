// ParameterCondition and VariableCondition (OpenSCENARIO 1.3 §8.3.2): a run-time parameter or
// variable compared with a value, by the rules of its declared type (numerically for numbers
// and booleans, equalTo / notEqualTo only for strings and dates).

#include "conditions/condition_makers.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class StoreCheck final : public ValueCondition {
 public:
  StoreCheck(const ValueStore& (*store)(const SimState&), std::string name, xosc::Rule rule,
             xosc::Value reference)
      : store_(store), name_(std::move(name)), rule_(rule), reference_(std::move(reference)) {}
  bool holds(const SimState& state) override {
    const xosc::Value* value = store_(state).find(name_);
    return value != nullptr && xosc::compare_values(*value, rule_, reference_);
  }

 private:
  const ValueStore& (*store_)(const SimState&);
  std::string name_;
  xosc::Rule rule_;
  xosc::Value reference_;
};

const ValueStore& parameters(const SimState& state) { return state.parameters; }
const ValueStore& variables(const SimState& state) { return state.variables; }

std::unique_ptr<ValueCondition> make_store_check(const ValueStore& (*store)(const SimState&),
                                                 const char* what, const std::string& name,
                                                 xosc::Rule rule, const std::string& text,
                                                 const xosc::Source& source,
                                                 const SimState& state) {
  const xosc::Value* declared = store(state).find(name);
  if (declared == nullptr) {
    throw InputError(source.error(std::string(what) + " '" + name + "' is not declared"));
  }
  auto reference = xosc::parse_value(declared->type, text);
  if (!reference) {
    throw InputError(source.error("'" + text + "' is not a valid " +
                                  std::string(xosc::to_string(declared->type)) + " to compare " +
                                  what + " '" + name + "' with"));
  }
  return std::make_unique<StoreCheck>(store, name, rule, std::move(*reference));
}

}  // namespace

std::unique_ptr<ValueCondition> make_parameter(const xosc::ParameterCondition& c,
                                               const SimState& state) {
  return make_store_check(parameters, "parameter", c.parameter_ref, c.rule, c.value, c.source,
                          state);
}

std::unique_ptr<ValueCondition> make_variable(const xosc::VariableCondition& c,
                                              const SimState& state) {
  return make_store_check(variables, "variable", c.variable_ref, c.rule, c.value, c.source, state);
}

}  // namespace corsa::engine::detail
