#pragma once

// The Storyboard's Init (OpenSCENARIO 1.3 §8.2): actions performed at tick 0, before time
// starts: global actions, then the entities' placements (TeleportActions, in an order where an
// entity placed relative to another comes after it), then the other private actions, then the
// user-defined ones, each group in document order. Actions that take time (e.g. a SpeedAction
// with a linear shape) keep running and step with the storyboard's actions.

#include <vector>

#include "storyboard/action_runner.h"

namespace corsa::engine::detail {

struct SimState;

class InitActions {
 public:
  /// Performs the Init at the current tick (0). Throws InputError for placements that cannot
  /// be made (missing roads or lanes, off the map, circular relative positions).
  void run(SimState& state);
  /// Performs Init's user-defined actions (CustomCommandActions). Called when the run starts
  /// (the first step), so that command handlers registered after construction see them.
  void run_user_defined(SimState& state);
  void step_actions(SimState& state);
  /// Drops the actions that are done (step_actions found them).
  void settle(SimState& state);

 private:
  void place_entities(SimState& state);
  void launch(SimState& state, RunningInstance instance);
  std::vector<RunningInstance> running_;
  bool ended_ = false;  ///< step_actions found an instance done (step_instance)
};

}  // namespace corsa::engine::detail
