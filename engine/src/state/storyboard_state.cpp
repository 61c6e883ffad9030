#include "corsa/engine/storyboard_state.h"

namespace corsa::engine {

std::string_view to_string(ElementType type) {
  switch (type) {
    case ElementType::kStoryboard:
      return "storyboard";
    case ElementType::kStory:
      return "story";
    case ElementType::kAct:
      return "act";
    case ElementType::kManeuverGroup:
      return "maneuverGroup";
    case ElementType::kManeuver:
      return "maneuver";
    case ElementType::kEvent:
      return "event";
    case ElementType::kAction:
      return "action";
  }
  return "story";
}

std::string_view to_string(ElementState state) {
  switch (state) {
    case ElementState::kStandby:
      return "standbyState";
    case ElementState::kRunning:
      return "runningState";
    case ElementState::kComplete:
      return "completeState";
  }
  return "standbyState";
}

std::string_view to_string(TransitionKind transition) {
  switch (transition) {
    case TransitionKind::kStart:
      return "startTransition";
    case TransitionKind::kEnd:
      return "endTransition";
    case TransitionKind::kStop:
      return "stopTransition";
    case TransitionKind::kSkip:
      return "skipTransition";
  }
  return "startTransition";
}

}  // namespace corsa::engine
