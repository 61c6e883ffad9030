#pragma once

// The storyboard (§8): Init, Story, Act, ManeuverGroup, Maneuver, Event, Action. Catalog
// maneuvers are expanded into their ManeuverGroup. Each storyboard element knows its full
// `::`-separated path, the name StoryboardElementStateCondition::resolved_path uses.

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "corsa/xosc/common.h"
#include "corsa/xosc/conditions.h"
#include "corsa/xosc/global_actions.h"
#include "corsa/xosc/parameters.h"
#include "corsa/xosc/private_actions.h"
#include "corsa/xosc/trajectories.h"

namespace corsa::xosc {

struct Action {
  std::string name;
  std::string path;  ///< "Story::Act::ManeuverGroup::Maneuver::Event::Action"
  std::variant<GlobalAction, UserDefinedAction, PrivateAction> action;
  Source source;
};

struct Event {
  std::string name;
  std::string path;
  Priority priority = Priority::kOverride;
  uint32_t maximum_execution_count = 1;  ///< 1 when not given (§8.4.3)
  std::vector<Action> actions;
  std::optional<Trigger> start_trigger;  ///< unset: starts at once when its maneuver runs
  Source source;
};

struct Maneuver {
  std::string name;
  std::string path;
  std::vector<ParameterDeclaration> parameters;
  std::vector<Event> events;
  std::optional<CatalogOrigin> catalog;
  Source source;
};

struct Actors {
  bool select_triggering_entities = false;
  std::vector<std::string> entity_refs;
  Source source;
};

struct ManeuverGroup {
  std::string name;
  std::string path;
  uint32_t maximum_execution_count = 1;
  Actors actors;
  std::vector<Maneuver> maneuvers;  ///< inline ones and catalog ones, in document order
  Source source;
};

struct Act {
  std::string name;
  std::string path;
  std::vector<ManeuverGroup> maneuver_groups;
  std::optional<Trigger> start_trigger;
  std::optional<Trigger> stop_trigger;
  Source source;
};

struct Story {
  std::string name;
  std::string path;
  std::vector<ParameterDeclaration> parameters;
  std::vector<Act> acts;
  Source source;
};

/// Init/Actions/Private: the initial private actions of one entity.
struct InitPrivate {
  std::string entity_ref;
  std::vector<PrivateAction> actions;
  Source source;
};

struct Init {
  std::vector<GlobalAction> global_actions;
  std::vector<UserDefinedAction> user_defined_actions;
  std::vector<InitPrivate> privates;
  Source source;
};

struct Storyboard {
  Init init;
  std::vector<Story> stories;
  std::optional<Trigger> stop_trigger;
  Source source;
};

/// The Actions of every Event of `board` (not the Init's), in document order: Story, Act,
/// ManeuverGroup, Maneuver, Event. The pointers live as long as `board`.
std::vector<const Action*> event_actions(const Storyboard& board);

}  // namespace corsa::xosc
