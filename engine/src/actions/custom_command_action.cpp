// CustomCommandAction (OpenSCENARIO 1.3 §7.6 UserDefinedAction): a command for the simulator.
// The engine hands it to the handler registered for its type (Simulation::
// set_custom_command_handler; e.g. the capture timeline's "corsa:capture"); a type nobody
// handles is reported once and otherwise ignored.

#include "actions/action_makers.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class CustomCommandInstance final : public InstantAction {
 public:
  explicit CustomCommandInstance(const xosc::UserDefinedAction& action) : action_(action) {}
  void start(ActionContext& context) override {
    SimState& state = context.state;
    if (action_.type.empty()) {
      return;  // an empty <Action/>, read at load as an action that does nothing
    }
    const auto handler = state.custom_handlers.find(action_.type);
    if (handler == state.custom_handlers.end()) {
      state.diagnostics.add_once(
          "custom-command:" + action_.type,
          action_.source.warning("CustomCommandAction type '" + action_.type +
                                 "' has no handler in this run; ignored"));
      return;
    }
    handler->second(action_, *state.simulation);
  }

 private:
  const xosc::UserDefinedAction& action_;
};

class UnsupportedInstance final : public InstantAction {
 public:
  UnsupportedInstance(std::string_view kind, const xosc::Source& source)
      : kind_(kind), source_(source) {}
  void start(ActionContext& context) override {
    context.state.diagnostics.add_once(
        "unsupported-action:" + kind_,
        source_.warning(kind_ + " is not performed by this engine yet; it completes at once"));
  }

 private:
  std::string kind_;
  const xosc::Source& source_;
};

}  // namespace

std::unique_ptr<ActionInstance> make_custom_command_action(const xosc::UserDefinedAction& action) {
  return std::make_unique<CustomCommandInstance>(action);
}

std::unique_ptr<ActionInstance> make_unsupported_action(std::string_view kind,
                                                        const xosc::Source& source) {
  return std::make_unique<UnsupportedInstance>(kind, source);
}

}  // namespace corsa::engine::detail
