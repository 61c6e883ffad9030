#pragma once

// Triggers (OpenSCENARIO 1.3 §8.3): a Trigger holds when any of its ConditionGroups holds; a
// group when all of its Conditions hold. Each Condition has an edge (rising, falling,
// risingOrFalling, none) and a delay; the value a condition returns at tick k is its edge-
// qualified value at tick k - delay (delays rounded to whole ticks).
//
// Conditions with an edge return false the first time they are checked, since there is no
// earlier value to compare with (OpenSCENARIO user guide, "Condition edges"). Every condition of
// every group is evaluated on each check, so that edge memory never skips a step.

#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

#include "conditions/condition.h"
#include "corsa/xosc/conditions.h"

namespace corsa::engine::detail {

struct SimState;

class CompiledCondition {
 public:
  /// `ghost`: the condition belongs to a trigger esmini's ghost takes over (an Act's start
  /// trigger, or an event whose motion actions the ghost performs; controllers/follow_ghost.h).
  CompiledCondition(const xosc::Condition& condition, const SimState& state, bool ghost = false);

  /// The condition's value now. When it holds, the entities that made it hold are appended to
  /// `triggering` (by-entity conditions); when it does not, nothing is.
  bool evaluate(const SimState& state, std::vector<uint32_t>& triggering);

  /// Forgets the values seen so far (the edge's previous value, values waiting for their delay):
  /// the condition starts over as if never evaluated.
  void forget_history();

 private:
  bool raw(const SimState& state, std::vector<uint32_t>& holders);

  const xosc::Condition& condition_;
  std::unique_ptr<EntityCondition> entity_;
  std::unique_ptr<ValueCondition> value_;
  std::vector<uint32_t> candidates_;  ///< triggering entities (selections expanded)
  bool all_ = false;                  ///< triggeringEntitiesRule "all"
  int64_t delay_ticks_ = 0;
  bool evaluated_ = false;
  bool last_ = false;
  struct Pending {
    int64_t tick = 0;
    std::vector<uint32_t> entities;
  };
  std::deque<Pending> pending_;  ///< true values waiting for their delay
};

class Trigger {
 public:
  Trigger(const xosc::Trigger& trigger, const SimState& state, bool ghost = false);

  /// Whether the trigger fires now; `triggering` receives the triggering entities of the groups
  /// that hold (sorted, unique).
  bool evaluate(const SimState& state, std::vector<uint32_t>& triggering);

  /// Starts over for a new execution of the element it starts: values seen by its conditions in
  /// an earlier execution (edges, values waiting for their delay) no longer count.
  void forget_history();

 private:
  std::vector<std::vector<CompiledCondition>> groups_;
};

}  // namespace corsa::engine::detail
