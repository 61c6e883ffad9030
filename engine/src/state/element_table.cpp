#include "state/element_table.h"

namespace corsa::engine::detail {

uint32_t ElementTable::add(ElementType type, std::string path) {
  const auto index = static_cast<uint32_t>(items_.size());
  by_path_.emplace(path, index);
  ElementStatus status;
  status.type = type;
  status.path = std::move(path);
  items_.push_back(std::move(status));
  return index;
}

std::optional<uint32_t> ElementTable::find(std::string_view path) const {
  const auto it = by_path_.find(std::string(path));
  return it == by_path_.end() ? std::nullopt : std::optional<uint32_t>(it->second);
}

void ElementTable::transition(uint32_t index, TransitionKind transition, ElementState state,
                              int64_t tick, const TimeBase& time) {
  ElementStatus& status = items_[index];
  status.state = state;
  status.last_transition = transition;
  status.last_tick = tick;
  status.last_sequence[static_cast<size_t>(transition)] = static_cast<int64_t>(log_.size());
  log_.push_back({tick, time.time(tick), status.type, status.path, transition, state});
}

}  // namespace corsa::engine::detail
