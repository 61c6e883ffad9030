#include "signal_controllers.h"

#include <map>
#include <unordered_map>
#include <utility>
#include <vector>

namespace corsa::ngii::detail {

size_t add_signal_controllers(xodr::MapData& map) {
  std::unordered_map<std::string, size_t> junction_index;
  for (size_t j = 0; j < map.junctions.size(); ++j) {
    junction_index.emplace(map.junctions[j].id, j);
  }
  // (junction, approach road index) -> signal ids, both in document order.
  std::map<std::pair<size_t, size_t>, std::vector<std::string>> groups;
  for (size_t r = 0; r < map.roads.size(); ++r) {
    const xodr::Road& road = map.roads[r];
    if (road.signals.empty()) {
      continue;
    }
    std::string junction = road.in_junction() ? road.junction : "";
    if (junction.empty() && road.successor.element_type == xodr::LinkElement::kJunction) {
      junction = road.successor.element_id;
    }
    const auto found = junction_index.find(junction);
    if (found == junction_index.end() ||
        map.junctions[found->second].type != xodr::JunctionType::kDefault) {
      continue;  // a light away from any intersection: no controller
    }
    auto& ids = groups[{found->second, r}];
    for (const xodr::Signal& signal : road.signals) {
      if (signal.dynamic) {
        ids.push_back(signal.id);
      }
    }
  }
  std::map<size_t, uint32_t> next_sequence;
  for (const auto& [key, ids] : groups) {
    if (ids.empty()) {
      continue;
    }
    xodr::Junction& junction = map.junctions[key.first];
    const uint32_t sequence = next_sequence[key.first]++;
    xodr::Controller controller;
    controller.id = "junction" + junction.id + "_" + std::to_string(sequence);
    controller.name = "junction " + junction.id + ", approach road " + map.roads[key.second].id;
    controller.sequence = sequence;
    for (const std::string& id : ids) {
      controller.controls.push_back(xodr::Control{id, "0"});
    }
    junction.controllers.push_back(xodr::JunctionController{controller.id, "0", sequence});
    map.controllers.push_back(std::move(controller));
  }
  return map.controllers.size();
}

}  // namespace corsa::ngii::detail
