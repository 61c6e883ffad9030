#pragma once

// Run-time states of storyboard elements and the transitions between them (OpenSCENARIO 1.3
// §8.4, "Storyboard element execution"): every Story, Act, ManeuverGroup, Maneuver, Event and
// Action is in standbyState, runningState or completeState and moves with startTransition,
// endTransition, stopTransition or skipTransition.

#include <cstdint>
#include <string>
#include <string_view>

namespace corsa::engine {

enum class ElementType : uint8_t {
  kStoryboard,
  kStory,
  kAct,
  kManeuverGroup,
  kManeuver,
  kEvent,
  kAction
};

enum class ElementState : uint8_t { kStandby, kRunning, kComplete };

enum class TransitionKind : uint8_t { kStart, kEnd, kStop, kSkip };

/// One transition of one storyboard element, as the event log records it.
struct TransitionRecord {
  int64_t tick = 0;   ///< step count at which it happened
  double time = 0.0;  ///< seconds, the tick on the fixed step grid
  ElementType type = ElementType::kStory;
  std::string
      path;  ///< "Story::Act::ManeuverGroup::Maneuver::Event::Action", "" for the storyboard
  TransitionKind transition = TransitionKind::kStart;
  ElementState state = ElementState::kRunning;  ///< the state entered
};

/// OpenSCENARIO spellings: "act", "runningState", "startTransition", ...
std::string_view to_string(ElementType type);
std::string_view to_string(ElementState state);
std::string_view to_string(TransitionKind transition);

}  // namespace corsa::engine
