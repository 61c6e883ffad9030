#pragma once

// The storyboard at run time (OpenSCENARIO 1.3 §8.4, "Storyboard element execution"): a tree
// that mirrors the document (Story > Act > ManeuverGroup > Maneuver > Event > Action), each node
// in standbyState, runningState or completeState, moved by start, end, stop and skip
// transitions:
//   - Stories start with the storyboard; an Act starts when its start trigger fires (at once
//     without one) and is stopped by its stop trigger; ManeuverGroups and Maneuvers start with
//     their parent; Events wait in standby for their start trigger (none: at once).
//   - Event priorities (§8.4.2.2): override stops the running events of the same maneuver,
//     parallel starts regardless, skip does not start while another event of the maneuver runs
//     (a skipTransition that counts as an execution).
//   - maximumExecutionCount (§8.4.2.1): an Event or ManeuverGroup that ends with executions left
//     goes back to standby and may run again (a ManeuverGroup restarts at the next step).
//   - Elements end when all their children are complete; a stop ends the whole subtree.
//   - The Storyboard's stop trigger stops everything and ends the run.

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "corsa/xosc/storyboard.h"
#include "storyboard/action_runner.h"
#include "storyboard/trigger.h"

namespace corsa::engine::detail {

struct SimState;

class Storyboard {
 public:
  /// Registers every element in state.elements (document order, the Storyboard itself first)
  /// and compiles the triggers. Throws InputError for unresolvable references.
  explicit Storyboard(SimState& state);
  ~Storyboard();
  Storyboard(const Storyboard&) = delete;
  Storyboard& operator=(const Storyboard&) = delete;

  /// Evaluates the triggers at the current tick and makes the transitions they cause.
  void update(SimState& state);
  /// Steps every running action (before the controllers move the entities).
  void step_actions(SimState& state);
  /// Completes the actions that reached their goal during the last step (step_actions found
  /// them done), and what ends with them (called after the tick advanced).
  void settle(SimState& state);

  /// The stop trigger fired.
  bool stopped() const { return stopped_; }
  /// Every story is complete and the storyboard has no stop trigger to wait for.
  bool finished(const SimState& state) const;
  bool has_stop_trigger() const { return stop_trigger_.has_value(); }

  struct StoryNode;
  struct ActNode;
  struct GroupNode;
  struct ManeuverNode;
  struct EventNode;
  struct ActionNode;
  struct WalkStop;

 private:
  void start(SimState& state);
  void update_act(SimState& state, ActNode& act);
  /// update_group for each of the act's groups, as if walked through, at the stops alone while no
  /// element state changes (storyboard_walk.cpp).
  void update_groups(SimState& state, ActNode& act);
  void update_group(SimState& state, GroupNode& group);
  /// The walk over the act's groups on from the event after `stop` (as update_groups would
  /// have gone on from there).
  void walk_on(SimState& state, ActNode& act, const WalkStop& stop);
  void update_event(SimState& state, ManeuverNode& maneuver, EventNode& event);
  /// The start of an event in standby whose trigger fired (or that has none), by its priority.
  void fire_event(SimState& state, ManeuverNode& maneuver, EventNode& event,
                  const std::vector<uint32_t>& triggering);
  void start_act(SimState& state, ActNode& act);
  void start_group(SimState& state, GroupNode& group);
  void start_event(SimState& state, EventNode& event, const std::vector<uint32_t>& triggering);
  void stop_event(SimState& state, EventNode& event);
  /// esmini's ghost restart: the ghost's completed events that teleport it go back to standby.
  void reset_ghost_events(SimState& state);
  /// `propagate`: let the story end when this was its last act (not while stopping all).
  void stop_act(SimState& state, ActNode& act, bool propagate);
  void stop_all(SimState& state);
  /// Completes `action` when all its instances are done, then checks its ancestors.
  void settle_action(SimState& state, ActionNode& action);
  void check_event(SimState& state, EventNode& event);
  void check_maneuver(SimState& state, ManeuverNode& maneuver);
  void check_group(SimState& state, GroupNode& group);
  void check_act(SimState& state, ActNode& act);
  void check_story(SimState& state, StoryNode& story);
  void move(SimState& state, uint32_t element, TransitionKind transition, ElementState to);
  /// ElementTable::enter_standby, counted in state_writes_.
  void enter_standby(SimState& state, uint32_t element);

  uint32_t root_ = 0;
  std::vector<std::unique_ptr<StoryNode>> stories_;
  std::optional<Trigger> stop_trigger_;
  std::vector<ActionNode*> running_;  ///< running action elements, in start order
  /// The entities that fired an event's trigger (kept: reusing it allocates nothing; no trigger
  /// is evaluated while an event starts).
  std::vector<uint32_t> triggering_;
  /// Element states set so far (move, enter_standby; the storyboard alone sets them): while the
  /// count stays, every element is in the state it was in and the transition log has not grown
  /// (update_groups and the triggers' StoryboardElementStateConditions read it so).
  uint64_t state_writes_ = 0;
  bool started_ = false;
  bool stopped_ = false;
  bool ended_ = false;  ///< step_actions found an instance done (step_instance)
};

}  // namespace corsa::engine::detail
