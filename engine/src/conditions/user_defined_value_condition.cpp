// UserDefinedValueCondition (OpenSCENARIO 1.3 §8.3.2): a named value that the user's environment
// provides, compared with the condition's value by its rule. Values come from outside the
// scenario: `corsa run --value NAME=VALUE` (SimulationOptions::values) and
// Simulation::set_user_value give text, which wins; Simulation::set_user_value_provider
// (external_control.h) gives typed values. Given text compares as a number when both sides are
// numbers, else as text (equalTo / notEqualTo only, as for string parameters). A provided value
// reads the condition's text as a value of its type (numerically for numbers and booleans); text
// that is not one compares as a string. A name with no value never holds, with a located warning
// once per name.

#include "conditions/condition_makers.h"
#include "corsa/core/strings.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class UserDefinedValueCheck final : public ValueCondition {
 public:
  explicit UserDefinedValueCheck(const xosc::UserDefinedValueCondition& condition)
      : condition_(condition) {}

  bool holds(const SimState& state) override {
    if (const auto given = state.given_values.find(condition_.name);
        given != state.given_values.end()) {
      return compare_given(given->second);
    }
    std::optional<xosc::Value> value;
    if (state.user_values) {
      value = state.user_values(condition_.name);
    }
    if (!value) {
      state.diagnostics.add_once(
          "user-defined-value:" + condition_.name,
          condition_.source.warning("UserDefinedValueCondition '" + condition_.name +
                                    "' has no value in this run: no value '" + condition_.name +
                                    "' is given (corsa run --value " + condition_.name +
                                    "=...) and no value provider has one; it does not hold"));
      return false;
    }
    if (auto reference = xosc::parse_value(value->type, condition_.value)) {
      return xosc::compare_values(*value, condition_.rule, *reference);
    }
    return compare_text(value->text());
  }

 private:
  bool compare_given(const std::string& given) const {
    const auto left = parse_double(given);
    const auto right = parse_double(condition_.value);
    if (left && right) {
      return xosc::compare_values(xosc::Value{xosc::ParameterType::kDouble, *left}, condition_.rule,
                                  xosc::Value{xosc::ParameterType::kDouble, *right});
    }
    return compare_text(given);
  }

  bool compare_text(const std::string& text) const {
    return xosc::compare_values(xosc::Value{xosc::ParameterType::kString, text}, condition_.rule,
                                xosc::Value{xosc::ParameterType::kString, condition_.value});
  }

  const xosc::UserDefinedValueCondition& condition_;
};

}  // namespace

std::unique_ptr<ValueCondition> make_user_defined_value(const xosc::UserDefinedValueCondition& c,
                                                        const SimState&) {
  return std::make_unique<UserDefinedValueCheck>(c);
}

}  // namespace corsa::engine::detail
