#pragma once

// The run-time status of every storyboard element (OpenSCENARIO 1.3 §8.4), indexed in document
// order, and the log of their transitions. The storyboard runtime drives it; conditions
// (StoryboardElementStateCondition) read it.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "corsa/engine/storyboard_state.h"
#include "state/time_base.h"

namespace corsa::engine::detail {

struct ElementStatus {
  ElementType type = ElementType::kStory;
  std::string path;
  ElementState state = ElementState::kStandby;
  std::optional<TransitionKind> last_transition;
  int64_t last_tick = -1;   ///< tick of the last transition
  uint32_t executions = 0;  ///< startTransitions + skipTransitions (§8.4.2.1)
  /// Position in the transition log of the last transition of each kind (TransitionKind order),
  /// -1 for none: lets a StoryboardElementStateCondition see every transition exactly once.
  std::array<int64_t, 4> last_sequence{-1, -1, -1, -1};
};

class ElementTable {
 public:
  uint32_t add(ElementType type, std::string path);
  std::optional<uint32_t> find(std::string_view path) const;
  const ElementStatus& operator[](uint32_t index) const { return items_[index]; }
  size_t size() const { return items_.size(); }

  /// Moves element `index` into `state` through `transition` at `tick`, and logs it.
  void transition(uint32_t index, TransitionKind transition, ElementState state, int64_t tick,
                  const TimeBase& time);
  /// Counts one execution (a start or a skip) of an event or maneuver group.
  void count_execution(uint32_t index) { ++items_[index].executions; }
  /// Resets the execution count (a parent started again, §8.4: the reset starts a new count).
  void reset_executions(uint32_t index) { items_[index].executions = 0; }
  /// Puts an element back into standby without a logged transition: the state it enters when
  /// its parent starts (again).
  void enter_standby(uint32_t index) { items_[index].state = ElementState::kStandby; }

  const std::vector<TransitionRecord>& log() const { return log_; }

 private:
  std::vector<ElementStatus> items_;
  std::unordered_map<std::string, uint32_t> by_path_;
  std::vector<TransitionRecord> log_;
};

}  // namespace corsa::engine::detail
