#include "storyboard/init_actions.h"

#include <algorithm>

#include "actions/action_factory.h"
#include "controllers/follow_ghost.h"
#include "corsa/xosc/scenario.h"
#include "motion/placement.h"
#include "motion/refpoint_trail.h"
#include "motion/trailers.h"
#include "positions/position_resolver.h"
#include "positions/trajectory_path.h"
#include "state/lenient.h"
#include "state/sim_state.h"
#include "storyboard/entity_refs.h"

namespace corsa::engine::detail {
namespace {

struct Placement {
  uint32_t entity = 0;
  const xosc::PrivateAction* action = nullptr;
  const xosc::TeleportAction* teleport = nullptr;
};

// An entity no TeleportAction places but whose Init has it follow a trajectory: it clearly starts
// where the trajectory starts (at its initialDistanceOffset), and is recorded from tick 0. The
// standard places entities by TeleportAction only (§7.4.3), so this is a lenient reading.
void place_on_trajectories(SimState& state) {
  for (const xosc::InitPrivate& init : state.scenario.storyboard.init.privates) {
    for (const uint32_t entity : expand_entity_refs({init.entity_ref}, state, init.source)) {
      for (const xosc::PrivateAction& action : init.actions) {
        const auto* follow = std::get_if<xosc::FollowTrajectoryAction>(&action);
        if (follow == nullptr || state.world.entities[entity].state().placed) continue;
        const TrajectoryPath path = build_trajectory_path(follow->trajectory, state, entity);
        const PathPoint start =
            path.at(std::clamp(follow->initial_distance_offset.value_or(0.0), 0.0, path.length()));
        lenient(state, follow->source,
                "entity '" + state.world.entities[entity].info.name +
                    "' has no initial position (no TeleportAction in Init)",
                "the start of the trajectory it follows");
        ResolvedPosition position;
        position.pose.x = start.x;
        position.pose.y = start.y;
        position.pose.z = start.z;
        position.pose.h = start.h;
        if (state.map != nullptr) {
          position.road = locate_point(*state.map, start.x, start.y, 0.0);
        }
        place_entity(state, state.world.entities[entity], position, follow->source, true);
        // esmini moves it there from the origin: a body trailing its reference point turns
        // from where it waited (motion/refpoint_trail.h).
        mark_refpoint_moved(state, state.world.entities[entity]);
      }
    }
  }
}

// A Vehicle's <Trailer> (§6.2.4): connected from the start, in line behind it.
void connect_initial_trailers(SimState& state) {
  for (uint32_t i = 0; i < state.world.entities.size(); ++i) {
    const Entity& tower = state.world.entities[i];
    const auto* vehicle =
        tower.object ? std::get_if<xosc::Vehicle>(&tower.object->object) : nullptr;
    if (vehicle == nullptr || !vehicle->trailer || !tower.state().placed) continue;
    std::optional<uint32_t> trailer = tower.initial_trailer;
    if (vehicle->trailer->trailer_ref) {
      trailer = state.world.find(*vehicle->trailer->trailer_ref);
      if (!trailer || *trailer == i) {
        throw InputError(vehicle->trailer->source.error(
            "trailer '" + *vehicle->trailer->trailer_ref + "' is not another entity"));
      }
    }
    if (trailer) connect_trailer(state, i, *trailer, true);
  }
}

// The entities an Init action of `init` acts on: those it names, and esmini's ghost with its
// entity for all but the controller actions (controllers/follow_ghost.h).
std::vector<uint32_t> init_actors(const xosc::InitPrivate& init, const xosc::PrivateAction& action,
                                  const SimState& state) {
  std::vector<uint32_t> actors = expand_entity_refs({init.entity_ref}, state, init.source);
  if (state.ghost && ghost_copies_init(action) &&
      std::find(actors.begin(), actors.end(), state.ghost->entity) != actors.end()) {
    actors.push_back(state.ghost->ghost);
  }
  return actors;
}

}  // namespace

void InitActions::place_entities(SimState& state) {
  std::vector<Placement> pending;
  for (const xosc::InitPrivate& init : state.scenario.storyboard.init.privates) {
    for (const xosc::PrivateAction& action : init.actions) {
      const auto* teleport = std::get_if<xosc::TeleportAction>(&action);
      if (teleport == nullptr) continue;
      for (const uint32_t entity : init_actors(init, action, state)) {
        pending.push_back({entity, &action, teleport});
      }
    }
  }
  // Relative placements wait for their reference; each pass places what it can.
  while (!pending.empty()) {
    std::vector<Placement> waiting;
    for (const Placement& placement : pending) {
      const std::string* reference = referenced_entity(placement.teleport->position);
      const auto index = reference ? state.world.find(*reference) : std::nullopt;
      if (index && *index != placement.entity && !state.world.entities[*index].state().placed) {
        waiting.push_back(placement);
        continue;
      }
      RunningInstance instance{make_private_action(*placement.action), placement.entity};
      start_instance(state, instance, true);
    }
    if (waiting.size() == pending.size()) {
      const Placement& first = waiting.front();
      const std::string& reference = *referenced_entity(first.teleport->position);
      throw InputError(first.teleport->position.source.error(
          "entity '" + state.world.entities[first.entity].info.name + "' is placed relative to '" +
          reference +
          "', which has no initial position (or the placements refer to each "
          "other)"));
    }
    pending = std::move(waiting);
  }
  place_on_trajectories(state);
  connect_initial_trailers(state);
}

void InitActions::launch(SimState& state, RunningInstance instance) {
  start_instance(state, instance, true);
  if (!instance.action->done()) {
    running_.push_back(std::move(instance));
  } else {
    release_instance(state, instance);
  }
}

void InitActions::run(SimState& state) {
  const xosc::Init& init = state.scenario.storyboard.init;
  for (const xosc::GlobalAction& action : init.global_actions) {
    launch(state, {make_global_action(action), std::nullopt});
  }
  place_entities(state);
  for (const xosc::InitPrivate& private_init : init.privates) {
    for (const uint32_t entity :
         expand_entity_refs({private_init.entity_ref}, state, private_init.source)) {
      for (const xosc::PrivateAction& action : private_init.actions) {
        if (!std::holds_alternative<xosc::TeleportAction>(action)) {
          launch(state, {make_private_action(action), entity});
        }
      }
    }
  }
  if (state.ghost) {
    // The ghost's copies of its entity's Init actions, after all the entities' own.
    for (const xosc::InitPrivate& private_init : init.privates) {
      for (const xosc::PrivateAction& action : private_init.actions) {
        const auto actors = init_actors(private_init, action, state);
        if (!std::holds_alternative<xosc::TeleportAction>(action) &&
            std::find(actors.begin(), actors.end(), state.ghost->ghost) != actors.end()) {
          launch(state, {make_private_action(action), state.ghost->ghost});
        }
      }
    }
  }
}

void InitActions::run_user_defined(SimState& state) {
  for (const xosc::UserDefinedAction& action :
       state.scenario.storyboard.init.user_defined_actions) {
    launch(state, {make_user_defined_action(action), std::nullopt});
  }
}

[[gnu::hot]] void InitActions::step_actions(SimState& state) {
  for (RunningInstance& instance : running_) {
    ended_ = step_instance(state, instance) || ended_;
  }
}

[[gnu::hot]] void InitActions::settle(SimState& state) {
  // Mostly none has ended (a continuous action runs for the whole run): nothing to rebuild.
  if (!ended_) {
    return;
  }
  ended_ = false;
  std::vector<RunningInstance> still;
  for (RunningInstance& instance : running_) {
    if (instance.action->done()) {
      release_instance(state, instance);
    } else {
      still.push_back(std::move(instance));
    }
  }
  running_ = std::move(still);
}

}  // namespace corsa::engine::detail
