// StoryboardElementStateCondition (OpenSCENARIO 1.3 §8.3.2, §8.4): a storyboard element is in a
// state (standbyState, runningState, completeState), or took a transition (startTransition,
// endTransition, stopTransition, skipTransition). A transition is seen by the condition at its
// first evaluation after it happened, whatever the order of evaluation within a step.

#include "conditions/condition_makers.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class ElementStateCheck final : public ValueCondition {
 public:
  ElementStateCheck(uint32_t element, std::optional<ElementState> state,
                    std::optional<TransitionKind> transition)
      : element_(element), state_(state), transition_(transition) {}

  [[gnu::hot]] bool holds(const SimState& state) override {
    const ElementStatus& status = state.elements[element_];
    if (state_) {
      return status.state == *state_;
    }
    const int64_t sequence = status.last_sequence[static_cast<size_t>(*transition_)];
    const auto log_size = static_cast<int64_t>(state.elements.log().size());
    // First evaluation: only a transition of this very tick counts.
    const bool result = seen_ < 0 ? sequence >= 0 && status.last_tick == state.tick &&
                                        status.last_transition == transition_
                                  : sequence >= seen_;
    seen_ = log_size;
    return result;
  }
  ConditionInputs inputs() const override { return ConditionInputs::kElementStates; }
  // A transition seen at one evaluation is not seen again: with no write since, the next
  // evaluation finds none (seen_ is the log's size then).
  bool value_stands() const override { return state_.has_value(); }

 private:
  uint32_t element_;
  std::optional<ElementState> state_;
  std::optional<TransitionKind> transition_;
  int64_t seen_ = -1;  ///< log size at the previous evaluation
};

ElementType element_type(xosc::StoryboardElementType type) {
  switch (type) {
    case xosc::StoryboardElementType::kStory:
      return ElementType::kStory;
    case xosc::StoryboardElementType::kAct:
      return ElementType::kAct;
    case xosc::StoryboardElementType::kManeuverGroup:
      return ElementType::kManeuverGroup;
    case xosc::StoryboardElementType::kManeuver:
      return ElementType::kManeuver;
    case xosc::StoryboardElementType::kEvent:
      return ElementType::kEvent;
    case xosc::StoryboardElementType::kAction:
      return ElementType::kAction;
  }
  return ElementType::kEvent;
}

}  // namespace

std::unique_ptr<ValueCondition> make_storyboard_element_state(
    const xosc::StoryboardElementStateCondition& c, const SimState& state) {
  const std::string& path = c.resolved_path.empty() ? c.storyboard_element_ref : c.resolved_path;
  const auto element = state.elements.find(path);
  if (!element) {
    throw InputError(c.source.error("no storyboard element '" + c.storyboard_element_ref + "'"));
  }
  if (state.elements[*element].type != element_type(c.type)) {
    throw InputError(c.source.error("storyboard element '" + c.storyboard_element_ref +
                                    "' is not a " + std::string(xosc::to_string(c.type))));
  }
  std::optional<ElementState> wanted_state;
  std::optional<TransitionKind> wanted_transition;
  switch (c.state) {
    case xosc::StoryboardElementState::kStandbyState:
      wanted_state = ElementState::kStandby;
      break;
    case xosc::StoryboardElementState::kRunningState:
      wanted_state = ElementState::kRunning;
      break;
    case xosc::StoryboardElementState::kCompleteState:
      wanted_state = ElementState::kComplete;
      break;
    case xosc::StoryboardElementState::kStartTransition:
      wanted_transition = TransitionKind::kStart;
      break;
    case xosc::StoryboardElementState::kEndTransition:
      wanted_transition = TransitionKind::kEnd;
      break;
    case xosc::StoryboardElementState::kStopTransition:
      wanted_transition = TransitionKind::kStop;
      break;
    case xosc::StoryboardElementState::kSkipTransition:
      wanted_transition = TransitionKind::kSkip;
      break;
  }
  return std::make_unique<ElementStateCheck>(*element, wanted_state, wanted_transition);
}

}  // namespace corsa::engine::detail
