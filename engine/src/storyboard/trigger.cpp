#include "storyboard/trigger.h"

#include <algorithm>

#include "conditions/condition_makers.h"
#include "controllers/follow_ghost.h"
#include "state/sim_state.h"
#include "storyboard/entity_refs.h"

namespace corsa::engine::detail {

CompiledCondition::CompiledCondition(const xosc::Condition& condition, const SimState& state,
                                     bool ghost)
    : condition_(condition), delay_ticks_(state.time.ticks(condition.delay)) {
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
  } else {
    const auto& by_value = std::get<xosc::ByValueCondition>(condition.kind);
    const auto* time = std::get_if<xosc::SimulationTimeCondition>(&by_value);
    if (ghost && state.ghost && time != nullptr) {
      value_ = make_shifted_simulation_time(*time, -state.ghost->headstart);
    } else {
      value_ = make_value_condition(by_value, state);
    }
  }
}

[[gnu::hot]] bool CompiledCondition::raw(const SimState& state, std::vector<uint32_t>& holders) {
  if (value_) {
    return value_->holds(state);
  }
  for (const uint32_t entity : candidates_) {
    // An absent entity (not added yet, deleted) fulfils no condition.
    if (state.world.entities[entity].state().placed && entity_->holds(state, entity)) {
      holders.push_back(entity);
    } else if (all_) {
      holders.clear();
      return false;
    }
  }
  return all_ ? !candidates_.empty() : !holders.empty();
}

[[gnu::hot]] bool CompiledCondition::evaluate(const SimState& state,
                                              std::vector<uint32_t>& triggering) {
  std::vector<uint32_t> holders;
  const bool now = raw(state, holders);
  bool edged = false;
  switch (condition_.edge) {
    case xosc::ConditionEdge::kNone:
      edged = now;
      break;
    case xosc::ConditionEdge::kRising:
      edged = evaluated_ && now && !last_;
      break;
    case xosc::ConditionEdge::kFalling:
      edged = evaluated_ && !now && last_;
      break;
    case xosc::ConditionEdge::kRisingOrFalling:
      edged = evaluated_ && now != last_;
      break;
  }
  evaluated_ = true;
  last_ = now;
  if (delay_ticks_ == 0) {
    if (edged) {
      triggering.insert(triggering.end(), holders.begin(), holders.end());
    }
    return edged;
  }
  if (edged) {
    pending_.push_back({state.tick, std::move(holders)});
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

Trigger::Trigger(const xosc::Trigger& trigger, const SimState& state, bool ghost) {
  for (const xosc::ConditionGroup& group : trigger.groups) {
    std::vector<CompiledCondition> conditions;
    conditions.reserve(group.conditions.size());
    for (const xosc::Condition& condition : group.conditions) {
      conditions.emplace_back(condition, state, ghost);
    }
    groups_.push_back(std::move(conditions));
  }
}

[[gnu::hot]] bool Trigger::evaluate(const SimState& state, std::vector<uint32_t>& triggering) {
  bool fires = false;
  if (groups_.size() == 1 && groups_.front().size() == 1) {
    // One condition: it appends its entities only when it holds, which is when the group does.
    fires = groups_.front().front().evaluate(state, triggering);
  } else {
    for (auto& group : groups_) {
      std::vector<uint32_t> group_entities;
      bool all = !group.empty();
      for (auto& condition : group) {
        all = condition.evaluate(state, group_entities) && all;
      }
      if (all) {
        fires = true;
        triggering.insert(triggering.end(), group_entities.begin(), group_entities.end());
      }
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

}  // namespace corsa::engine::detail
