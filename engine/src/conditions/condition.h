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

class EntityCondition {
 public:
  virtual ~EntityCondition() = default;
  /// Whether the condition holds for triggering entity `entity` now.
  virtual bool holds(const SimState& state, uint32_t entity) = 0;

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
