// UserDefinedValueCondition (OpenSCENARIO 1.3 §8.3.2): a named value that the simulator or the
// user provides (Simulation::set_user_value_provider, external_control.h), compared with the
// condition's value by its rule. The condition's text is read as a value of the provided value's
// type (numerically for numbers and booleans); text that is not one compares as a string
// (equalTo / notEqualTo only, as for string parameters). Without a value (no provider, or the
// provider has none for the name) the condition does not hold, with a located warning once per
// name.

#include "conditions/condition_makers.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class UserDefinedValueCheck final : public ValueCondition {
 public:
  explicit UserDefinedValueCheck(const xosc::UserDefinedValueCondition& condition)
      : condition_(condition) {}

  bool holds(const SimState& state) override {
    std::optional<xosc::Value> value;
    if (state.user_values) {
      value = state.user_values(condition_.name);
    }
    if (!value) {
      state.diagnostics.add_once(
          "user-defined-value:" + condition_.name,
          condition_.source.warning("UserDefinedValueCondition '" + condition_.name +
                                    "' has no value in this run (nothing provides it); it does "
                                    "not hold"));
      return false;
    }
    if (auto reference = xosc::parse_value(value->type, condition_.value)) {
      return xosc::compare_values(*value, condition_.rule, *reference);
    }
    const xosc::Value text{xosc::ParameterType::kString, value->text()};
    return xosc::compare_values(text, condition_.rule,
                                xosc::Value{xosc::ParameterType::kString, condition_.value});
  }

 private:
  const xosc::UserDefinedValueCondition& condition_;
};

}  // namespace

std::unique_ptr<ValueCondition> make_user_defined_value(const xosc::UserDefinedValueCondition& c,
                                                        const SimState&) {
  return std::make_unique<UserDefinedValueCheck>(c);
}

}  // namespace corsa::engine::detail
