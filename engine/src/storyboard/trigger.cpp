#include "storyboard/trigger.h"

#include <algorithm>

#include "conditions/condition_makers.h"
#include "controllers/follow_ghost.h"
#include "state/sim_state.h"
#include "storyboard/entity_refs.h"

namespace corsa::engine::detail {

CompiledCondition::CompiledCondition(const xosc::Condition& condition, const SimState& state,
                                     const uint64_t& element_writes, bool ghost)
    : edge_(condition.edge),
      delay_ticks_(state.time.ticks(condition.delay)),
      element_writes_(&element_writes) {
  if (condition.delay < 0.0) {
    throw InputError(
        condition.source.error("condition '" + condition.name + "' has a negative delay"));
  }
  if (const auto* by_entity = std::get_if<xosc::ByEntityCondition>(&condition.kind)) {
    candidates_ = expand_entity_refs(by_entity->triggering_entities.entity_refs, state,
                                     by_entity->triggering_entities.source);
    all_ = by_entity->triggering_entities.rule == xosc::TriggeringEntitiesRule::kAll;
    entity_ = make_entity_condition(by_entity->condition, state);
    if (ghost && state.ghost && ghost_meets(by_entity->condition)) {
      std::replace(candidates_.begin(), candidates_.end(), state.ghost->entity, state.ghost->ghost);
      std::sort(candidates_.begin(), candidates_.end());
    }
    if (candidates_.size() == 1 && entity_->inputs() == ConditionInputs::kOwnState) {
      inputs_ = ConditionInputs::kOwnState;
    }
  } else {
    const auto& by_value = std::get<xosc::ByValueCondition>(condition.kind);
    const auto* time = std::get_if<xosc::SimulationTimeCondition>(&by_value);
    if (ghost && state.ghost && time != nullptr) {
      value_ = make_shifted_simulation_time(*time, -state.ghost->headstart);
    } else {
      value_ = make_value_condition(by_value, state);
    }
    if (value_->inputs() == ConditionInputs::kElementStates) {
      inputs_ = ConditionInputs::kElementStates;
      stands_ = value_->value_stands();
    }
  }
}

bool CompiledCondition::entities_hold(const SimState& state) {
  holders_.clear();
  for (const uint32_t entity : candidates_) {
    // An absent entity (not added yet, deleted) fulfils no condition.
    if (state.world.entities[entity].state().placed && entity_->holds(state, entity)) {
      holders_.push_back(entity);
    } else if (all_) {
      holders_.clear();
      return false;
    }
  }
  return all_ ? !candidates_.empty() : !holders_.empty();
}

bool CompiledCondition::delayed(const SimState& state, bool edged,
                                std::vector<uint32_t>& triggering) {
  if (edged) {
    pending_.push_back({state.tick, holders_});
  }
  // The value of tick - delay: values older than that are dropped (they were due while the
  // trigger was not being checked).
  const int64_t due = state.tick - delay_ticks_;
  while (!pending_.empty() && pending_.front().tick < due) {
    pending_.pop_front();
  }
  if (!pending_.empty() && pending_.front().tick == due) {
    triggering.insert(triggering.end(), pending_.front().entities.begin(),
                      pending_.front().entities.end());
    pending_.pop_front();
    return true;
  }
  return false;
}

void CompiledCondition::forget_history() {
  evaluated_ = false;
  last_ = false;
  pending_.clear();
}

Trigger::Trigger(const xosc::Trigger& trigger, const SimState& state,
                 const uint64_t& element_writes, bool ghost) {
  for (const xosc::ConditionGroup& group : trigger.groups) {
    std::vector<CompiledCondition> conditions;
    conditions.reserve(group.conditions.size());
    for (const xosc::Condition& condition : group.conditions) {
      conditions.emplace_back(condition, state, element_writes, ghost);
    }
    groups_.push_back(std::move(conditions));
  }
  single_ = groups_.size() == 1 && groups_.front().size() == 1;
}

bool Trigger::evaluate_groups(const SimState& state, std::vector<uint32_t>& triggering) {
  bool fires = false;
  for (auto& group : groups_) {
    group_entities_.clear();
    bool all = !group.empty();
    for (auto& condition : group) {
      all = condition.evaluate(state, group_entities_) && all;
    }
    if (all) {
      fires = true;
      triggering.insert(triggering.end(), group_entities_.begin(), group_entities_.end());
    }
  }
  if (triggering.size() > 1) {
    std::sort(triggering.begin(), triggering.end());
    triggering.erase(std::unique(triggering.begin(), triggering.end()), triggering.end());
  }
  return fires;
}

void Trigger::forget_history() {
  for (auto& group : groups_) {
    for (auto& condition : group) {
      condition.forget_history();
    }
  }
}

void Trigger::collect_entity_conditions(std::vector<EntityCondition*>& out) {
  for (auto& group : groups_) {
    for (auto& condition : group) {
      if (EntityCondition* entity = condition.entity_condition()) out.push_back(entity);
    }
  }
}

}  // namespace corsa::engine::detail
