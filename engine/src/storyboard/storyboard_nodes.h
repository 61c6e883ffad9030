#pragma once

// The nodes of the run-time storyboard tree (storyboard.h). Built once; the vectors never grow
// afterwards, so parent pointers stay valid.

#include <cstdint>
#include <optional>
#include <vector>

#include "storyboard/storyboard.h"

namespace corsa::engine::detail {

struct Storyboard::ActionNode {
  uint32_t element = 0;
  const xosc::Action* def = nullptr;
  EventNode* event = nullptr;
  std::vector<RunningInstance> instances;  ///< while running: one per actor
  bool running = false;
};

struct Storyboard::EventNode {
  uint32_t element = 0;
  const xosc::Event* def = nullptr;
  ManeuverNode* maneuver = nullptr;
  std::optional<Trigger> start_trigger;
  std::vector<ActionNode> actions;
  /// esmini's ghost performs this event's motion actions (controllers/follow_ghost.h) ...
  bool ghost = false;
  /// ... and its start restarts the ghost (a condition the ghost cannot meet ahead).
  bool ghost_restart = false;
};

struct Storyboard::ManeuverNode {
  uint32_t element = 0;
  GroupNode* group = nullptr;
  std::vector<EventNode> events;
};

struct Storyboard::GroupNode {
  uint32_t element = 0;
  const xosc::ManeuverGroup* def = nullptr;
  ActNode* act = nullptr;
  std::vector<uint32_t> actors;  ///< Actors/EntityRef, selections expanded
  std::vector<ManeuverNode> maneuvers;
};

/// One stop of an Act's walk over its groups (Storyboard::update_groups): the start of a group in
/// standby (`maneuver` and `event` null), or the trigger of an event in standby whose maneuver
/// runs (the nodes' vectors never grow: the pointers stay valid).
struct Storyboard::WalkStop {
  uint32_t group = 0;
  ManeuverNode* maneuver = nullptr;
  EventNode* event = nullptr;
};

struct Storyboard::ActNode {
  uint32_t element = 0;
  const xosc::Act* def = nullptr;
  StoryNode* story = nullptr;
  std::optional<Trigger> start_trigger;
  std::optional<Trigger> stop_trigger;
  std::vector<uint32_t> triggering;  ///< entities that fired the start trigger
  std::vector<GroupNode> groups;
  /// Where the walk over the groups does anything, in document order, as the element states
  /// were when the storyboard's count of state writes was walk_writes (storyboard_walk.cpp).
  std::vector<WalkStop> walk;
  uint64_t walk_writes = UINT64_MAX;
};

struct Storyboard::StoryNode {
  uint32_t element = 0;
  std::vector<ActNode> acts;
};

}  // namespace corsa::engine::detail
