// SetMonitorAction (OpenSCENARIO 1.3 §7.5.7): sets a monitor declared in MonitorDeclarations to
// true or false, at once. Monitors are the scenario's own verdicts: their values at the end of
// the run are in the run summary and `corsa test` fails a test whose monitor ended false.

#include "actions/action_makers.h"
#include "positions/position_common.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class SetMonitorInstance final : public InstantAction {
 public:
  explicit SetMonitorInstance(const xosc::SetMonitorAction& action) : action_(action) {}
  void start(ActionContext& context) override {
    const auto found = context.state.monitors.find(action_.monitor_ref);
    if (found == context.state.monitors.end()) {
      fail(action_.source, "monitor '" + action_.monitor_ref + "' is not declared");
    }
    found->second = action_.value;
  }

 private:
  const xosc::SetMonitorAction& action_;
};

}  // namespace

std::unique_ptr<ActionInstance> make_set_monitor_action(const xosc::SetMonitorAction& action) {
  return std::make_unique<SetMonitorInstance>(action);
}

}  // namespace corsa::engine::detail
