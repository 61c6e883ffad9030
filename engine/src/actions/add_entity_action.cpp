// AddEntityAction and DeleteEntityAction (OpenSCENARIO 1.3 §7.5.4 EntityAction). The entities
// are those of the scenario's Entities; a deleted entity is absent: no controller moves it, it
// has no trajectory rows, no contacts, and conditions about it do not hold. Adding places it
// (as a TeleportAction would) and makes it present again under its controller, at the speed it
// was deleted at (standing if it never ran); adding an entity that is present does nothing (with
// a lenient-reading warning).

#include "actions/action_makers.h"
#include "controllers/controllers.h"
#include "motion/placement.h"
#include "positions/position_resolver.h"
#include "state/lenient.h"
#include "state/sim_state.h"
#include "traffic/traffic_update.h"

namespace corsa::engine::detail {
namespace {

uint32_t entity_index(const SimState& state, const std::string& name, const xosc::Source& source) {
  const auto index = state.world.find(name);
  if (!index) {
    throw InputError(source.error("unknown entity '" + name + "'"));
  }
  return *index;
}

class AddEntityInstance final : public InstantAction {
 public:
  explicit AddEntityInstance(const xosc::AddEntityAction& action) : action_(action) {}
  void start(ActionContext& context) override {
    SimState& state = context.state;
    const uint32_t index = entity_index(state, action_.entity_ref, action_.source);
    Entity& entity = state.world.entities[index];
    if (entity.state().placed) {
      // §7.5.4: an AddEntityAction adds an entity that is not in the simulation; esmini's
      // add_delete_entity adds one that is ("ExpectedToFail") and esmini leaves it as it is.
      lenient(state, action_.source,
              "AddEntityAction on '" + action_.entity_ref + "', which is already present",
              "no action: the entity stays where it is");
      return;
    }
    const ResolvedPosition at = resolve_position(action_.position, state, index);
    // 1.3 AddEntityAction: "Adds an entity to the scenario, at a predefined position": a position
    // only, the speed is left open. An entity added again drives on at the speed it was deleted
    // at, as esmini's object of a deleted entity does; one never present before stands.
    const double speed = entity.removed ? entity.removed_speed : 0.0;
    entity.write_state().speed = speed;
    entity.speed_command = speed;
    entity.lateral_command = 0.0;
    place_entity(state, entity, at, action_.position.source, false);
    control_of(state, index).dynamics.reset();
  }

 private:
  const xosc::AddEntityAction& action_;
};

class DeleteEntityInstance final : public InstantAction {
 public:
  explicit DeleteEntityInstance(const xosc::DeleteEntityAction& action) : action_(action) {}
  void start(ActionContext& context) override {
    SimState& state = context.state;
    const uint32_t index = entity_index(state, action_.entity_ref, action_.source);
    remove_entity(state, index);
    // esmini's ghost (controllers/follow_ghost.h) goes with its entity. (A scenario cannot name
    // the ghost: it is made after the file's references are resolved.)
    if (state.ghost && index == state.ghost->entity) {
      remove_entity(state, state.ghost->ghost);
    }
  }

 private:
  const xosc::DeleteEntityAction& action_;
};

}  // namespace

std::unique_ptr<ActionInstance> make_add_entity_action(const xosc::AddEntityAction& action) {
  return std::make_unique<AddEntityInstance>(action);
}

std::unique_ptr<ActionInstance> make_delete_entity_action(const xosc::DeleteEntityAction& action) {
  return std::make_unique<DeleteEntityInstance>(action);
}

}  // namespace corsa::engine::detail
