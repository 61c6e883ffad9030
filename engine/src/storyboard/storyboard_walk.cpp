// An Act's walk over its groups at each update (storyboard.h, Storyboard::update_groups).
//
// update_group on each group in turn starts the groups in standby and, in each running maneuver
// of a running group, evaluates the start trigger of each event in standby (update_event). Most
// steps change no element's state: the walk then reaches the same events as at the last step.
// Those stops are remembered with the storyboard's count of element state writes; while it
// stays, only the stops are visited (a trigger's evaluation writes no element state). The first
// stop that changes a state hands the rest of the walk to the full one, from where it stands.

#include "state/sim_state.h"
#include "storyboard/storyboard_nodes.h"

namespace corsa::engine::detail {
namespace {

bool running(const SimState& state, uint32_t element) {
  return state.elements[element].state == ElementState::kRunning;
}

// The stops of the walk over act's groups with the element states as they are: up to the first
// group in standby (its start changes states, and the walk goes on in full from there).
void find_stops(const SimState& state, Storyboard::ActNode& act,
                std::vector<Storyboard::WalkStop>& stops) {
  stops.clear();
  for (uint32_t g = 0; g < act.groups.size(); ++g) {
    Storyboard::GroupNode& group = act.groups[g];
    if (state.elements[group.element].state == ElementState::kStandby) {
      stops.push_back({g, nullptr, nullptr});
      return;
    }
    if (!running(state, group.element)) {
      continue;
    }
    for (Storyboard::ManeuverNode& maneuver : group.maneuvers) {
      if (!running(state, maneuver.element)) {
        continue;
      }
      for (Storyboard::EventNode& event : maneuver.events) {
        if (state.elements[event.element].state == ElementState::kStandby) {
          stops.push_back({g, &maneuver, &event});
        }
      }
    }
  }
}

}  // namespace

[[gnu::hot]] void Storyboard::update_groups(SimState& state, ActNode& act) {
  if (act.walk_writes != state_writes_) {
    find_stops(state, act, act.walk);
    act.walk_writes = state_writes_;
  }
  for (const WalkStop& stop : act.walk) {
    if (stop.maneuver == nullptr) {
      for (size_t g = stop.group; g < act.groups.size(); ++g) {
        update_group(state, act.groups[g]);
      }
      return;
    }
    EventNode& event = *stop.event;
    // update_event without its check: the stop's event is in standby.
    triggering_.clear();
    if (!event.start_trigger || event.start_trigger->evaluate(state, triggering_)) {
      fire_event(state, *stop.maneuver, event, triggering_);
    }
    if (act.walk_writes != state_writes_) {
      walk_on(state, act, stop);
      return;
    }
  }
}

[[gnu::hot]] void Storyboard::walk_on(SimState& state, ActNode& act, const WalkStop& stop) {
  // As update_group's loops go on: the rest of this maneuver's events (its state read before
  // them), the group's later maneuvers, the later groups.
  GroupNode& group = act.groups[stop.group];
  ManeuverNode& here = *stop.maneuver;
  for (auto e = static_cast<size_t>(stop.event - here.events.data()) + 1; e < here.events.size();
       ++e) {
    update_event(state, here, here.events[e]);
  }
  for (auto m = static_cast<size_t>(stop.maneuver - group.maneuvers.data()) + 1;
       m < group.maneuvers.size(); ++m) {
    ManeuverNode& maneuver = group.maneuvers[m];
    if (!running(state, maneuver.element)) {
      continue;
    }
    for (EventNode& event : maneuver.events) {
      update_event(state, maneuver, event);
    }
  }
  for (size_t g = stop.group + 1; g < act.groups.size(); ++g) {
    update_group(state, act.groups[g]);
  }
}

}  // namespace corsa::engine::detail
