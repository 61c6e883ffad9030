// Condition kinds the engine does not evaluate (UserDefinedValueCondition, whose value only the
// user's simulator would know): a located warning once per kind, and the condition never holds.

#include "conditions/condition_makers.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class NeverHolds final : public ValueCondition {
 public:
  bool holds(const SimState&) override { return false; }
};

}  // namespace

std::unique_ptr<ValueCondition> make_unsupported_value(const char* kind, const xosc::Source& source,
                                                       const SimState& state) {
  state.diagnostics.add_once(
      std::string("unsupported-condition:") + kind,
      source.warning(std::string(kind) + " is not evaluated by this engine yet; it never holds"));
  return std::make_unique<NeverHolds>();
}

}  // namespace corsa::engine::detail
