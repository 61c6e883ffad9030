#include "traffic/signal_groups.h"

#include <algorithm>

#include "corsa/xodr/map.h"
#include "corsa/xosc/scenario.h"

namespace corsa::engine::detail {

std::vector<std::string> map_controller_signals(const xodr::Map* map, std::string_view id) {
  std::vector<std::string> signals;
  if (map == nullptr) {
    return signals;
  }
  for (const xodr::Controller& controller : map->data().controllers) {
    if (controller.id == id) {
      for (const xodr::Control& control : controller.controls) {
        signals.push_back(control.signal_id);
      }
    }
  }
  return signals;
}

std::vector<std::string> signal_group(const xodr::Map* map,
                                      const xosc::TrafficSignalController& controller) {
  std::vector<std::string> group = map_controller_signals(map, controller.name);
  for (const xosc::Phase& phase : controller.phases) {
    for (const xosc::TrafficSignalState& signal : phase.states) {
      group.push_back(signal.traffic_signal_id);
    }
  }
  // Each once, keeping the first place (a group has a handful of signals).
  std::vector<std::string> unique;
  for (std::string& id : group) {
    if (std::find(unique.begin(), unique.end(), id) == unique.end()) {
      unique.push_back(std::move(id));
    }
  }
  return unique;
}

bool map_has_signal(const xodr::Map* map, std::string_view id) {
  if (map == nullptr) {
    return false;
  }
  for (const xodr::Road& road : map->data().roads) {
    for (const xodr::Signal& signal : road.signals) {
      if (signal.id == id) {
        return true;
      }
    }
  }
  return false;
}

}  // namespace corsa::engine::detail
