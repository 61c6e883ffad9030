// TrailerAction (OpenSCENARIO 1.3 §7.4.8): ConnectTrailerAction connects the trailer entity to
// the actor's hitch; from then on the trailer follows the actor (motion/trailers.h) and the two
// do not count as colliding. DisconnectTrailerAction releases the actor's trailer, which stays
// where it is. Both complete at once.

#include "actions/action_makers.h"
#include "motion/trailers.h"
#include "positions/position_common.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class ConnectTrailerInstance final : public InstantAction {
 public:
  explicit ConnectTrailerInstance(const xosc::ConnectTrailerAction& action) : action_(action) {}
  void start(ActionContext& context) override {
    if (action_.trailer_ref.empty()) return;  // read leniently as no trailer (corsa_xosc)
    const auto trailer = context.state.world.find(action_.trailer_ref);
    if (!trailer) fail(action_.source, "unknown entity '" + action_.trailer_ref + "'");
    if (*trailer == *context.actor) {
      fail(action_.source, "'" + action_.trailer_ref + "' cannot tow itself");
    }
    if (!context.state.world.entities[*trailer].state().placed) {
      fail(action_.source, "the trailer '" + action_.trailer_ref + "' has no position");
    }
    connect_trailer(context.state, *context.actor, *trailer, false);
  }

 private:
  const xosc::ConnectTrailerAction& action_;
};

class DisconnectTrailerInstance final : public InstantAction {
 public:
  void start(ActionContext& context) override { disconnect_trailer(context.state, *context.actor); }
};

}  // namespace

std::unique_ptr<ActionInstance> make_connect_trailer_action(
    const xosc::ConnectTrailerAction& action) {
  return std::make_unique<ConnectTrailerInstance>(action);
}

std::unique_ptr<ActionInstance> make_disconnect_trailer_action(
    const xosc::DisconnectTrailerAction&) {
  return std::make_unique<DisconnectTrailerInstance>();
}

}  // namespace corsa::engine::detail
