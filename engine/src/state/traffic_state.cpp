#include "state/traffic_state.h"

#include "corsa/xosc/scenario.h"

namespace corsa::engine::detail {

std::optional<size_t> TrafficState::find_controller(std::string_view name) const {
  for (size_t i = 0; i < controllers.size(); ++i) {
    if (controllers[i].definition->name == name) {
      return i;
    }
  }
  return std::nullopt;
}

}  // namespace corsa::engine::detail
