#pragma once

// Conditions (OpenSCENARIO 1.3 §8.3 / XSD ByEntityCondition, ByValueCondition): each kind is a
// small class in its own file, built by one factory function. Entity conditions are evaluated
// once per triggering entity; value conditions once. Both read the state at the current tick.

#include <cstdint>
#include <memory>

#include "corsa/xosc/conditions.h"

namespace corsa::engine::detail {

struct SimState;

class EntityCondition {
 public:
  virtual ~EntityCondition() = default;
  /// Whether the condition holds for triggering entity `entity` now.
  virtual bool holds(const SimState& state, uint32_t entity) = 0;
};

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
