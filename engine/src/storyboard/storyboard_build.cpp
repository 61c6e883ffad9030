// Building the run-time storyboard tree from the document.

#include <algorithm>
#include <memory>
#include <optional>
#include <variant>
#include <vector>

#include "controllers/follow_ghost.h"
#include "corsa/xosc/scenario.h"
#include "positions/position_resolver.h"
#include "state/sim_state.h"
#include "storyboard/entity_refs.h"
#include "storyboard/storyboard_nodes.h"

namespace corsa::engine::detail {
namespace {

using StoryNode = Storyboard::StoryNode;
using ActNode = Storyboard::ActNode;
using GroupNode = Storyboard::GroupNode;
using ManeuverNode = Storyboard::ManeuverNode;
using EventNode = Storyboard::EventNode;
using ActionNode = Storyboard::ActionNode;

// Absolute road and lane positions of teleports are checked before the run: an entity sent to
// a missing road or lane is a located error now rather than in the middle of the run.
void check_teleport(const xosc::Action& action, const SimState& state) {
  const auto* private_action = std::get_if<xosc::PrivateAction>(&action.action);
  const auto* teleport =
      private_action ? std::get_if<xosc::TeleportAction>(private_action) : nullptr;
  if (teleport == nullptr) {
    return;
  }
  const auto& kind = teleport->position.kind;
  if (std::holds_alternative<xosc::RoadPosition>(kind) ||
      std::holds_alternative<xosc::LanePosition>(kind)) {
    resolve_position(teleport->position, state, std::nullopt);
  }
}

// The nodes of one event and its actions. Elements are added depth first, in document order
// (their indexes are their identity in the element table).
void build_event(EventNode& node, const xosc::Event& event, ManeuverNode& maneuver,
                 SimState& state) {
  node.def = &event;
  node.maneuver = &maneuver;
  node.element = state.elements.add(ElementType::kEvent, event.path);
  node.actions.resize(event.actions.size());
  for (size_t i = 0; i < event.actions.size(); ++i) {
    ActionNode& action_node = node.actions[i];
    action_node.def = &event.actions[i];
    action_node.event = &node;
    action_node.element = state.elements.add(ElementType::kAction, event.actions[i].path);
    check_teleport(event.actions[i], state);
  }
}

void build_group(GroupNode& node, const xosc::ManeuverGroup& group, ActNode& act, SimState& state) {
  node.def = &group;
  node.act = &act;
  node.element = state.elements.add(ElementType::kManeuverGroup, group.path);
  node.actors = expand_entity_refs(group.actors.entity_refs, state, group.actors.source);
  node.maneuvers.resize(group.maneuvers.size());
  for (size_t m = 0; m < group.maneuvers.size(); ++m) {
    const xosc::Maneuver& maneuver = group.maneuvers[m];
    ManeuverNode& maneuver_node = node.maneuvers[m];
    maneuver_node.group = &node;
    maneuver_node.element = state.elements.add(ElementType::kManeuver, maneuver.path);
    maneuver_node.events.resize(maneuver.events.size());
    for (size_t e = 0; e < maneuver.events.size(); ++e) {
      build_event(maneuver_node.events[e], maneuver.events[e], maneuver_node, state);
    }
  }
}

std::unique_ptr<StoryNode> build_story(const xosc::Story& story, SimState& state) {
  auto node = std::make_unique<StoryNode>();
  node->element = state.elements.add(ElementType::kStory, story.path);
  node->acts.resize(story.acts.size());
  for (size_t a = 0; a < story.acts.size(); ++a) {
    const xosc::Act& act = story.acts[a];
    ActNode& act_node = node->acts[a];
    act_node.def = &act;
    act_node.story = node.get();
    act_node.element = state.elements.add(ElementType::kAct, act.path);
    act_node.groups.resize(act.maneuver_groups.size());
    for (size_t g = 0; g < act.maneuver_groups.size(); ++g) {
      build_group(act_node.groups[g], act.maneuver_groups[g], act_node, state);
    }
  }
  return node;
}

// Whether esmini's ghost takes over this event: one of its actions is a motion action of the
// ghost's entity (controllers/follow_ghost.h).
bool ghost_event(const EventNode& event, const GroupNode& group, const SimState& state) {
  if (!state.ghost) return false;
  const bool actor = std::find(group.actors.begin(), group.actors.end(), state.ghost->entity) !=
                     group.actors.end();
  if (!actor) return false;
  for (const xosc::Action& action : event.def->actions) {
    const auto* private_action = std::get_if<xosc::PrivateAction>(&action.action);
    if (private_action != nullptr && ghost_performs(*private_action)) return true;
  }
  return false;
}

// The start and stop triggers of an act and its events. esmini's ghost takes over every Act's
// start trigger and those of the events it performs (controllers/follow_ghost.h).
// `writes`: the storyboard's count of element state writes.
void compile_triggers(ActNode& act, const SimState& state, const uint64_t& writes) {
  if (act.def->start_trigger) {
    act.start_trigger.emplace(*act.def->start_trigger, state, writes, state.ghost.has_value());
  }
  if (act.def->stop_trigger) {
    act.stop_trigger.emplace(*act.def->stop_trigger, state, writes);
  }
  for (GroupNode& group : act.groups) {
    for (ManeuverNode& maneuver : group.maneuvers) {
      for (EventNode& event : maneuver.events) {
        event.ghost = ghost_event(event, group, state);
        if (event.def->start_trigger) {
          event.start_trigger.emplace(*event.def->start_trigger, state, writes, event.ghost);
          event.ghost_restart = event.ghost && ghost_restarts_on(*event.def->start_trigger, state);
        }
      }
    }
  }
}

// Whether `trigger` has a ByEntityCondition of one of the kinds `Kinds`.
template <class... Kinds>
bool has_entity_condition(const std::optional<xosc::Trigger>& trigger) {
  if (!trigger) return false;
  for (const xosc::ConditionGroup& group : trigger->groups) {
    for (const xosc::Condition& condition : group.conditions) {
      const auto* by_entity = std::get_if<xosc::ByEntityCondition>(&condition.kind);
      if (by_entity != nullptr && (std::holds_alternative<Kinds>(by_entity->condition) || ...)) {
        return true;
      }
    }
  }
  return false;
}

// Whether any trigger of the storyboard (the stop trigger, the acts' start and stop triggers,
// the events' start triggers: every condition a run evaluates) has a ByEntityCondition of one
// of the kinds `Kinds`.
template <class... Kinds>
bool storyboard_has_entity_condition(const xosc::Storyboard& board) {
  if (has_entity_condition<Kinds...>(board.stop_trigger)) return true;
  for (const xosc::Story& story : board.stories) {
    for (const xosc::Act& act : story.acts) {
      if (has_entity_condition<Kinds...>(act.start_trigger) ||
          has_entity_condition<Kinds...>(act.stop_trigger)) {
        return true;
      }
      for (const xosc::ManeuverGroup& group : act.maneuver_groups) {
        for (const xosc::Maneuver& maneuver : group.maneuvers) {
          for (const xosc::Event& event : maneuver.events) {
            if (has_entity_condition<Kinds...>(event.start_trigger)) return true;
          }
        }
      }
    }
  }
  return false;
}

// Every trigger's entity conditions of one definition share one memo of its values
// (share_equal_conditions, conditions/condition.h).
void share_condition_values(std::vector<std::unique_ptr<StoryNode>>& stories,
                            std::optional<Trigger>& stop_trigger) {
  std::vector<EntityCondition*> conditions;
  const auto collect = [&](std::optional<Trigger>& trigger) {
    if (trigger) trigger->collect_entity_conditions(conditions);
  };
  for (auto& story : stories) {
    for (ActNode& act : story->acts) {
      collect(act.start_trigger);
      collect(act.stop_trigger);
      for (GroupNode& group : act.groups) {
        for (ManeuverNode& maneuver : group.maneuvers) {
          for (EventNode& event : maneuver.events) collect(event.start_trigger);
        }
      }
    }
  }
  collect(stop_trigger);
  share_equal_conditions(conditions);
}

}  // namespace

Storyboard::Storyboard(SimState& state) {
  const xosc::Storyboard& board = state.scenario.storyboard;
  root_ = state.elements.add(ElementType::kStoryboard, "");
  state.straight_travel_wanted =
      storyboard_has_entity_condition<xosc::TraveledDistanceCondition>(board);
  state.timers_wanted =
      storyboard_has_entity_condition<xosc::StandStillCondition, xosc::OffroadCondition,
                                      xosc::EndOfRoadCondition>(board);
  for (const xosc::Story& story : board.stories) {
    stories_.push_back(build_story(story, state));
  }
  // Triggers last: StoryboardElementStateConditions refer to elements anywhere in the tree.
  for (auto& story : stories_) {
    for (ActNode& act : story->acts) {
      compile_triggers(act, state, state_writes_);
    }
  }
  if (board.stop_trigger) {
    stop_trigger_.emplace(*board.stop_trigger, state, state_writes_);
  }
  share_condition_values(stories_, stop_trigger_);
}

Storyboard::~Storyboard() = default;

}  // namespace corsa::engine::detail
