#include "actions/action.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {

Entity& ActionContext::entity() const { return state.world.entities[*actor]; }

}  // namespace corsa::engine::detail
