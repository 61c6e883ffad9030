#pragma once

// Triggers (OpenSCENARIO 1.3 §8.3): a Trigger holds when any of its ConditionGroups holds; a
// group when all of its Conditions hold. Each Condition has an edge (rising, falling,
// risingOrFalling, none) and a delay; the value a condition returns at tick k is its edge-
// qualified value at tick k - delay (delays rounded to whole ticks).
//
// Conditions with an edge return false the first time they are checked, since there is no
// earlier value to compare with (OpenSCENARIO user guide, "Condition edges"). Every condition of
// every group is evaluated on each check, so that edge memory never skips a step; a condition
// whose inputs stand since its previous check (ConditionInputs) takes the value they give
// without reading them again.

#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

#include "conditions/condition.h"
#include "corsa/xosc/conditions.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {

class CompiledCondition {
 public:
  /// `element_writes`: the storyboard's count of element state writes (Storyboard, which
  /// outlives its triggers). `ghost`: the condition belongs to a trigger esmini's ghost takes
  /// over (an Act's start trigger, or an event whose motion actions the ghost performs;
  /// controllers/follow_ghost.h).
  CompiledCondition(const xosc::Condition& condition, const SimState& state,
                    const uint64_t& element_writes, bool ghost = false);

  /// The condition's value now. When it holds, the entities that made it hold are appended to
  /// `triggering` (by-entity conditions); when it does not, nothing is.
  bool evaluate(const SimState& state, std::vector<uint32_t>& triggering) {
    bool now = false;
    if (inputs_ == ConditionInputs::kAnything) {
      now = holds(state);
    } else if (const uint64_t stamp = inputs_stamp(state); evaluated_ && stamp == stamp_) {
      // The inputs stand: the value is the one they gave (holders_ too, kept from then).
      now = stands_ && last_;
    } else {
      stamp_ = stamp;
      now = holds(state);
    }
    bool edged = now;
    if (edge_ != xosc::ConditionEdge::kNone) {
      // The first value has no earlier one to make an edge with.
      edged = evaluated_ && (edge_ == xosc::ConditionEdge::kRising    ? now && !last_
                             : edge_ == xosc::ConditionEdge::kFalling ? !now && last_
                                                                      : now != last_);
    }
    evaluated_ = true;
    last_ = now;
    if (delay_ticks_ != 0) {
      // Nothing new and nothing waiting: nothing due.
      return (edged || !pending_.empty()) && delayed(state, edged, triggering);
    }
    if (edged) {
      triggering.insert(triggering.end(), holders_.begin(), holders_.end());
    }
    return edged;
  }

  /// Forgets the values seen so far (the edge's previous value, values waiting for their delay):
  /// the condition starts over as if never evaluated.
  void forget_history();

  /// The entity condition evaluated, or null (a value condition).
  EntityCondition* entity_condition() { return entity_.get(); }

 private:
  /// The condition's value now, read from its inputs.
  bool holds(const SimState& state) {
    return value_                    ? value_->holds(state)
           : candidates_.size() == 1 ? one_holds(state)
                                     : entities_hold(state);
  }
  /// The count of writes of the inputs (inputs_ kOwnState or kElementStates).
  uint64_t inputs_stamp(const SimState& state) const {
    return inputs_ == ConditionInputs::kOwnState
               ? state.world.entities[candidates_.front()].state_changes()
               : *element_writes_;
  }
  /// The entity condition's value now; holders_ receives the entities that make it hold.
  bool entities_hold(const SimState& state);
  /// The same for one triggering entity, whichever the rule (any and all agree on one).
  bool one_holds(const SimState& state) {
    holders_.clear();
    const uint32_t entity = candidates_.front();
    // An absent entity (not added yet, deleted) fulfils no condition.
    if (!state.world.entities[entity].state().placed || !entity_->holds(state, entity)) {
      return false;
    }
    holders_.push_back(entity);
    return true;
  }
  /// The edge-qualified value `edged` of now, seen `delay_ticks_` later: the value of tick - delay.
  bool delayed(const SimState& state, bool edged, std::vector<uint32_t>& triggering);

  xosc::ConditionEdge edge_ = xosc::ConditionEdge::kNone;
  std::unique_ptr<EntityCondition> entity_;
  std::unique_ptr<ValueCondition> value_;
  std::vector<uint32_t> candidates_;  ///< triggering entities (selections expanded)
  bool all_ = false;                  ///< triggeringEntitiesRule "all"
  int64_t delay_ticks_ = 0;
  /// What the value reads (kOwnState only with one triggering entity, whose count is the stamp).
  ConditionInputs inputs_ = ConditionInputs::kAnything;
  bool stands_ = true;  ///< ValueCondition::value_stands
  uint64_t stamp_ = 0;  ///< inputs_stamp at the last evaluation that read the inputs
  const uint64_t* element_writes_ = nullptr;
  bool evaluated_ = false;
  bool last_ = false;
  /// The entities that made the entity condition hold at its last evaluation (kept: reusing the
  /// vector allocates nothing at each step; empty for value conditions).
  std::vector<uint32_t> holders_;
  struct Pending {
    int64_t tick = 0;
    std::vector<uint32_t> entities;
  };
  std::deque<Pending> pending_;  ///< true values waiting for their delay
};

class Trigger {
 public:
  /// `element_writes` and `ghost`: see CompiledCondition.
  Trigger(const xosc::Trigger& trigger, const SimState& state, const uint64_t& element_writes,
          bool ghost = false);

  /// Whether the trigger fires now; `triggering` receives the triggering entities of the groups
  /// that hold (sorted, unique).
  bool evaluate(const SimState& state, std::vector<uint32_t>& triggering) {
    if (single_ && triggering.empty()) {
      // One condition: it appends its entities (sorted, unique: a subset of its candidates)
      // only when it holds, which is when the trigger fires.
      return groups_.front().front().evaluate(state, triggering);
    }
    return evaluate_groups(state, triggering);
  }

  /// Starts over for a new execution of the element it starts: values seen by its conditions in
  /// an earlier execution (edges, values waiting for their delay) no longer count.
  void forget_history();

  /// Appends the entity conditions of every group (share_equal_conditions).
  void collect_entity_conditions(std::vector<EntityCondition*>& out);

 private:
  bool evaluate_groups(const SimState& state, std::vector<uint32_t>& triggering);

  std::vector<std::vector<CompiledCondition>> groups_;
  bool single_ = false;                   ///< one group of one condition
  std::vector<uint32_t> group_entities_;  ///< evaluate_groups' scratch (kept: no allocation)
};

}  // namespace corsa::engine::detail
