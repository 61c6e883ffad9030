#pragma once

// Conditions (OpenSCENARIO 1.3 §8.3 / XSD ByEntityCondition, ByValueCondition): each kind is a
// small class in its own file, built by one factory function. Entity conditions are evaluated
// once per triggering entity; value conditions once. Both read the state at the current tick.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "corsa/xosc/conditions.h"

namespace corsa::engine::detail {

struct SimState;

/// What a condition's value reads besides its definition, the map and the options (fixed for the
/// run): a trigger skips the evaluations whose inputs stand (CompiledCondition,
/// storyboard/trigger.h).
enum class ConditionInputs : uint8_t {
  kAnything,       ///< more than the below (the time, other entities, ...): evaluated at each check
  kOwnState,       ///< the triggering entity's EntityState alone, counted by its state_changes
  kElementStates,  ///< the storyboard's element states and transitions, counted by their writes
};

class EntityCondition {
 public:
  virtual ~EntityCondition() = default;
  /// Whether the condition holds for triggering entity `entity` now.
  virtual bool holds(const SimState& state, uint32_t entity) = 0;
  /// kOwnState when the value for one entity is a function of that entity's state alone (so it
  /// is the same while the state's count of writes stands); kAnything (the default) otherwise.
  virtual ConditionInputs inputs() const { return ConditionInputs::kAnything; }

  /// Names the condition's definition when its value is a function of that definition and of
  /// the triggering entity's state alone (the map and the options fixed for the run): conditions
  /// with one key then give one value for one entity in one state, and may share a memo of it
  /// (share_values). Empty (the default): the value reads more, and is not shared.
  virtual std::string value_key() const { return {}; }
  /// Makes this condition keep its values in `other`'s memo; `other` has the same value_key, so
  /// it is of this condition's class. Only called for a non-empty key.
  virtual void share_values(EntityCondition& /*other*/) {}
};

/// Lets the conditions of one definition (OpenSCENARIO allows many: a maneuver of a catalog
/// instantiated for several actors repeats its triggers) share one memo of their values, so that
/// a step evaluates the definition once per entity. Each keeps its own edge, delay and rule
/// (CompiledCondition, storyboard/trigger.h): only the value of the definition is shared.
void share_equal_conditions(const std::vector<EntityCondition*>& conditions);

class ValueCondition {
 public:
  virtual ~ValueCondition() = default;
  virtual bool holds(const SimState& state) = 0;
  /// kElementStates when the value reads the element table alone; kAnything (the default)
  /// otherwise.
  virtual ConditionInputs inputs() const { return ConditionInputs::kAnything; }
  /// With inputs() kElementStates, the value at an evaluation when no element state was written
  /// since the previous one: the previous value (true, a state) or false (a transition, which
  /// is seen once).
  virtual bool value_stands() const { return true; }
};

/// Builds the evaluator of an entity condition; references (entities, positions) are checked
/// here and reported as InputError located at the condition.
std::unique_ptr<EntityCondition> make_entity_condition(const xosc::EntityCondition& condition,
                                                       const SimState& state);
std::unique_ptr<ValueCondition> make_value_condition(const xosc::ByValueCondition& condition,
                                                     const SimState& state);

/// OpenSCENARIO Rule applied to numbers (equalTo within a relative 1e-9, since values that
/// reach a target exactly are compared with it).
bool compare(double value, xosc::Rule rule, double reference);

}  // namespace corsa::engine::detail
