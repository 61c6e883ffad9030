// The storyboard's transitions at run time (OpenSCENARIO 1.3 §8.4).

#include <algorithm>

#include "actions/action.h"
#include "actions/action_factory.h"
#include "controllers/follow_ghost.h"
#include "state/sim_state.h"
#include "storyboard/storyboard_nodes.h"

namespace corsa::engine::detail {

void Storyboard::move(SimState& state, uint32_t element, TransitionKind transition,
                      ElementState to) {
  state.elements.transition(element, transition, to, state.tick, state.time);
  ++state_writes_;
}

void Storyboard::enter_standby(SimState& state, uint32_t element) {
  state.elements.enter_standby(element);
  ++state_writes_;
}

[[gnu::hot]] bool Storyboard::finished(const SimState& state) const {
  return state.elements[root_].state == ElementState::kComplete;
}

void Storyboard::start(SimState& state) {
  started_ = true;
  move(state, root_, TransitionKind::kStart, ElementState::kRunning);
  for (auto& story : stories_) {
    move(state, story->element, TransitionKind::kStart, ElementState::kRunning);
    check_story(state, *story);
  }
  if (stories_.empty() && !stop_trigger_) {
    // Nothing to wait for: every (zero) story is complete.
    move(state, root_, TransitionKind::kEnd, ElementState::kComplete);
  }
}

[[gnu::hot]] void Storyboard::update(SimState& state) {
  if (stopped_ || (started_ && finished(state))) {
    return;
  }
  if (!started_) {
    start(state);
  }
  if (stop_trigger_) {
    std::vector<uint32_t> triggering;
    if (stop_trigger_->evaluate(state, triggering)) {
      stop_all(state);
      return;
    }
  }
  for (auto& story : stories_) {
    if (state.elements[story->element].state != ElementState::kRunning) {
      continue;
    }
    for (ActNode& act : story->acts) {
      update_act(state, act);
    }
  }
}

[[gnu::hot]] void Storyboard::update_act(SimState& state, ActNode& act) {
  const ElementState current = state.elements[act.element].state;
  if (current == ElementState::kStandby) {
    act.triggering.clear();
    // §8.4.5: without a start trigger an Act starts together with its Story.
    if (!act.start_trigger || act.start_trigger->evaluate(state, act.triggering)) {
      start_act(state, act);
    }
  } else if (current == ElementState::kRunning && act.stop_trigger) {
    std::vector<uint32_t> triggering;
    if (act.stop_trigger->evaluate(state, triggering)) {
      stop_act(state, act, true);
      return;
    }
  }
  if (state.elements[act.element].state != ElementState::kRunning) {
    return;
  }
  update_groups(state, act);
}

void Storyboard::update_group(SimState& state, GroupNode& group) {
  if (state.elements[group.element].state == ElementState::kStandby) {
    start_group(state, group);  // a re-execution (§8.4.4): it has no trigger of its own
  }
  if (state.elements[group.element].state != ElementState::kRunning) {
    return;
  }
  for (ManeuverNode& maneuver : group.maneuvers) {
    if (state.elements[maneuver.element].state != ElementState::kRunning) {
      continue;
    }
    for (EventNode& event : maneuver.events) {
      update_event(state, maneuver, event);
    }
  }
}

[[gnu::hot]] void Storyboard::update_event(SimState& state, ManeuverNode& maneuver,
                                           EventNode& event) {
  if (state.elements[event.element].state != ElementState::kStandby) {
    return;
  }
  triggering_.clear();
  // §8.4.2: an Event without a start trigger inherits its Act's, which has fired already.
  if (event.start_trigger && !event.start_trigger->evaluate(state, triggering_)) {
    return;
  }
  fire_event(state, maneuver, event, triggering_);
}

void Storyboard::fire_event(SimState& state, ManeuverNode& maneuver, EventNode& event,
                            const std::vector<uint32_t>& triggering) {
  const auto is_running = [&](const EventNode& other) {
    return &other != &event && state.elements[other.element].state == ElementState::kRunning;
  };
  switch (event.def->priority) {
    case xosc::Priority::kSkip:
      // §8.4.2.2: not started while another event of the maneuver runs; counts as an execution.
      if (std::any_of(maneuver.events.begin(), maneuver.events.end(), is_running)) {
        state.elements.count_execution(event.element);
        const bool done =
            state.elements[event.element].executions >= event.def->maximum_execution_count;
        move(state, event.element, TransitionKind::kSkip,
             done ? ElementState::kComplete : ElementState::kStandby);
        if (done) {
          check_maneuver(state, maneuver);
        }
        return;
      }
      break;
    case xosc::Priority::kOverride:
      // §8.4.2.2: the running events of the same maneuver are stopped.
      for (EventNode& other : maneuver.events) {
        if (is_running(other)) {
          stop_event(state, other);
        }
      }
      break;
    case xosc::Priority::kParallel:
      break;
  }
  start_event(state, event, triggering);
}

void Storyboard::start_act(SimState& state, ActNode& act) {
  move(state, act.element, TransitionKind::kStart, ElementState::kRunning);
  for (GroupNode& group : act.groups) {
    state.elements.reset_executions(group.element);
    start_group(state, group);
  }
  check_act(state, act);
}

void Storyboard::start_group(SimState& state, GroupNode& group) {
  state.elements.count_execution(group.element);
  move(state, group.element, TransitionKind::kStart, ElementState::kRunning);
  for (ManeuverNode& maneuver : group.maneuvers) {
    move(state, maneuver.element, TransitionKind::kStart, ElementState::kRunning);
    for (EventNode& event : maneuver.events) {
      // §8.4.2: events enter standby when their maneuver starts, with a fresh count. A group's
      // re-execution (§8.4.4) starts its events afresh: a condition value of the previous
      // execution still waiting for its delay does not start them again at once.
      enter_standby(state, event.element);
      state.elements.reset_executions(event.element);
      if (event.start_trigger) {
        event.start_trigger->forget_history();
      }
      for (ActionNode& action : event.actions) {
        enter_standby(state, action.element);
      }
    }
  }
  for (ManeuverNode& maneuver : group.maneuvers) {
    check_maneuver(state, maneuver);
  }
  if (group.maneuvers.empty()) {
    check_group(state, group);
  }
}

void Storyboard::start_event(SimState& state, EventNode& event,
                             const std::vector<uint32_t>& triggering) {
  state.elements.count_execution(event.element);
  move(state, event.element, TransitionKind::kStart, ElementState::kRunning);
  if (event.ghost_restart && state.ghost) {
    // esmini's ghost restart (controllers/follow_ghost.h): a teleport of the ghost onto its
    // entity, which stops what ran on it; when the run's time went back, the ghost's completed
    // events may start again on the way.
    stop_domain_owners(state.world.entities[state.ghost->ghost],
                       kDomainLongitudinal | kDomainLateral);
    if (restart_ghost(state)) {
      reset_ghost_events(state);
    }
  }
  const GroupNode& group = *event.maneuver->group;
  std::vector<uint32_t> actors = group.actors;
  if (group.def->actors.select_triggering_entities) {
    // Actors chosen at run time: the entities that fired this event's trigger, else its Act's.
    const auto& chosen = triggering.empty() ? group.act->triggering : triggering;
    actors.insert(actors.end(), chosen.begin(), chosen.end());
    std::sort(actors.begin(), actors.end());
    actors.erase(std::unique(actors.begin(), actors.end()), actors.end());
  }
  for (ActionNode& action : event.actions) {
    move(state, action.element, TransitionKind::kStart, ElementState::kRunning);
    action.running = true;
    running_.push_back(&action);
    if (is_private(*action.def)) {
      if (actors.empty()) {
        state.diagnostics.add_once(
            "no-actors:" + action.def->path,
            action.def->source.warning("private action '" + action.def->name +
                                       "' has no actors; it completes at once"));
      }
      for (uint32_t actor : actors) {
        // esmini's ghost performs its entity's motion actions (controllers/follow_ghost.h).
        if (state.ghost && actor == state.ghost->entity &&
            ghost_performs(std::get<xosc::PrivateAction>(action.def->action))) {
          actor = state.ghost->ghost;
        }
        action.instances.push_back({make_action(*action.def), actor});
      }
    } else {
      action.instances.push_back({make_action(*action.def), std::nullopt});
    }
    for (RunningInstance& instance : action.instances) {
      start_instance(state, instance, false);
    }
  }
  for (ActionNode& action : event.actions) {
    if (action.running) {
      settle_action(state, action);
    }
  }
}

void Storyboard::reset_ghost_events(SimState& state) {
  for (auto& story : stories_) {
    for (ActNode& act : story->acts) {
      for (GroupNode& group : act.groups) {
        for (ManeuverNode& maneuver : group.maneuvers) {
          for (EventNode& event : maneuver.events) {
            if (!event.ghost || state.elements[event.element].state != ElementState::kComplete) {
              continue;
            }
            // esmini's reading: an event of the ghost's that puts the ghost somewhere (its
            // restart, or a TeleportAction of its own).
            const bool teleports =
                event.ghost_restart ||
                std::any_of(event.def->actions.begin(), event.def->actions.end(),
                            [](const xosc::Action& a) {
                              const auto* p = std::get_if<xosc::PrivateAction>(&a.action);
                              return p != nullptr &&
                                     std::holds_alternative<xosc::TeleportAction>(*p);
                            });
            if (!teleports) continue;
            enter_standby(state, event.element);
            state.elements.reset_executions(event.element);
            for (ActionNode& action : event.actions) {
              enter_standby(state, action.element);
            }
          }
        }
      }
    }
  }
}

[[gnu::hot]] void Storyboard::step_actions(SimState& state) {
  for (ActionNode* action : running_) {
    for (RunningInstance& instance : action->instances) {
      ended_ = step_instance(state, instance) || ended_;
    }
  }
}

[[gnu::hot]] void Storyboard::settle(SimState& state) {
  // Mostly no instance is done (step_instance tells), and no action has every instance done
  // (settle_action then changes nothing): no copy to make.
  if (!ended_) {
    return;
  }
  ended_ = false;
  const auto settles = [](const ActionNode* action) {
    return action->running &&
           std::all_of(action->instances.begin(), action->instances.end(),
                       [](const RunningInstance& instance) { return instance.action->done(); });
  };
  if (std::none_of(running_.begin(), running_.end(), settles)) {
    return;
  }
  // Copy: settling removes actions from running_ and may stop others.
  const std::vector<ActionNode*> running = running_;
  for (ActionNode* action : running) {
    if (action->running) {
      settle_action(state, *action);
    }
  }
}

// Out of line: settle() runs every step, an action ends rarely.
[[gnu::noinline]] void Storyboard::settle_action(SimState& state, ActionNode& action) {
  bool stopped = false;
  for (const RunningInstance& instance : action.instances) {
    if (!instance.action->done()) {
      return;
    }
    stopped = stopped || instance.action->stopped();
  }
  for (RunningInstance& instance : action.instances) {
    release_instance(state, instance);
  }
  action.instances.clear();
  action.running = false;
  running_.erase(std::find(running_.begin(), running_.end(), &action));
  // §8.4.1: an action that was stopped (overridden) completes through stopTransition.
  move(state, action.element, stopped ? TransitionKind::kStop : TransitionKind::kEnd,
       ElementState::kComplete);
  check_event(state, *action.event);
}

void Storyboard::check_event(SimState& state, EventNode& event) {
  if (state.elements[event.element].state != ElementState::kRunning) {
    return;
  }
  for (const ActionNode& action : event.actions) {
    if (state.elements[action.element].state != ElementState::kComplete) {
      return;
    }
  }
  // §8.4.2.1: back to standby while executions are left.
  const bool done = state.elements[event.element].executions >= event.def->maximum_execution_count;
  move(state, event.element, TransitionKind::kEnd,
       done ? ElementState::kComplete : ElementState::kStandby);
  if (!done) {
    for (ActionNode& action : event.actions) {
      enter_standby(state, action.element);
    }
  }
  check_maneuver(state, *event.maneuver);
}

void Storyboard::check_maneuver(SimState& state, ManeuverNode& maneuver) {
  if (state.elements[maneuver.element].state != ElementState::kRunning) {
    return;
  }
  for (const EventNode& event : maneuver.events) {
    if (state.elements[event.element].state != ElementState::kComplete) {
      return;
    }
  }
  move(state, maneuver.element, TransitionKind::kEnd, ElementState::kComplete);
  check_group(state, *maneuver.group);
}

void Storyboard::check_group(SimState& state, GroupNode& group) {
  if (state.elements[group.element].state != ElementState::kRunning) {
    return;
  }
  for (const ManeuverNode& maneuver : group.maneuvers) {
    if (state.elements[maneuver.element].state != ElementState::kComplete) {
      return;
    }
  }
  // §8.4.4: a ManeuverGroup with executions left goes back to standby and starts again.
  const bool done = state.elements[group.element].executions >= group.def->maximum_execution_count;
  move(state, group.element, TransitionKind::kEnd,
       done ? ElementState::kComplete : ElementState::kStandby);
  if (done) {
    check_act(state, *group.act);
  }
}

void Storyboard::check_act(SimState& state, ActNode& act) {
  if (state.elements[act.element].state != ElementState::kRunning) {
    return;
  }
  for (const GroupNode& group : act.groups) {
    if (state.elements[group.element].state != ElementState::kComplete) {
      return;
    }
  }
  move(state, act.element, TransitionKind::kEnd, ElementState::kComplete);
  check_story(state, *act.story);
}

void Storyboard::check_story(SimState& state, StoryNode& story) {
  if (state.elements[story.element].state != ElementState::kRunning) {
    return;
  }
  for (const ActNode& act : story.acts) {
    if (state.elements[act.element].state != ElementState::kComplete) {
      return;
    }
  }
  move(state, story.element, TransitionKind::kEnd, ElementState::kComplete);
  // Without a stop trigger the storyboard ends with its last story; with one, the run waits
  // for it (the ASAM examples stop some seconds after their acts complete).
  if (stop_trigger_ || state.elements[root_].state != ElementState::kRunning) {
    return;
  }
  for (const auto& other : stories_) {
    if (state.elements[other->element].state != ElementState::kComplete) {
      return;
    }
  }
  move(state, root_, TransitionKind::kEnd, ElementState::kComplete);
}

void Storyboard::stop_event(SimState& state, EventNode& event) {
  for (ActionNode& action : event.actions) {
    if (!action.running) {
      continue;
    }
    for (RunningInstance& instance : action.instances) {
      stop_instance(state, instance);
    }
    action.instances.clear();
    action.running = false;
    running_.erase(std::find(running_.begin(), running_.end(), &action));
    move(state, action.element, TransitionKind::kStop, ElementState::kComplete);
  }
  // §8.4.2.2: a stopped event completes regardless of the executions left.
  move(state, event.element, TransitionKind::kStop, ElementState::kComplete);
}

void Storyboard::stop_act(SimState& state, ActNode& act, bool propagate) {
  for (GroupNode& group : act.groups) {
    for (ManeuverNode& maneuver : group.maneuvers) {
      for (EventNode& event : maneuver.events) {
        const ElementState s = state.elements[event.element].state;
        if (s == ElementState::kRunning) {
          stop_event(state, event);
        } else if (s == ElementState::kStandby &&
                   state.elements[maneuver.element].state == ElementState::kRunning) {
          move(state, event.element, TransitionKind::kStop, ElementState::kComplete);
        }
      }
      if (state.elements[maneuver.element].state == ElementState::kRunning) {
        move(state, maneuver.element, TransitionKind::kStop, ElementState::kComplete);
      }
    }
    if (state.elements[group.element].state != ElementState::kComplete) {
      move(state, group.element, TransitionKind::kStop, ElementState::kComplete);
    }
  }
  // §8.4: an Act its own StopTrigger stops takes the stopTransition; esmini reports it as the
  // Act's endTransition, which its examples' StoryboardElementStateConditions wait for.
  const bool esmini_end = propagate && state.options.semantics == Semantics::kEsmini;
  move(state, act.element, esmini_end ? TransitionKind::kEnd : TransitionKind::kStop,
       ElementState::kComplete);
  if (propagate) {
    check_story(state, *act.story);
  }
}

void Storyboard::stop_all(SimState& state) {
  stopped_ = true;
  for (auto& story : stories_) {
    if (state.elements[story->element].state != ElementState::kRunning) {
      continue;
    }
    for (ActNode& act : story->acts) {
      const ElementState s = state.elements[act.element].state;
      if (s == ElementState::kRunning) {
        stop_act(state, act, false);
      } else if (s == ElementState::kStandby) {
        move(state, act.element, TransitionKind::kStop, ElementState::kComplete);
      }
    }
    if (state.elements[story->element].state == ElementState::kRunning) {
      move(state, story->element, TransitionKind::kStop, ElementState::kComplete);
    }
  }
  move(state, root_, TransitionKind::kStop, ElementState::kComplete);
}

}  // namespace corsa::engine::detail
