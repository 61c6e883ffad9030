#include "storyboard/entity_refs.h"

#include <algorithm>

#include "corsa/xosc/scenario.h"
#include "state/entity_builder.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

void expand(const std::string& name, const SimState& state, const xosc::Source& source,
            std::vector<uint32_t>& out, int depth) {
  if (const auto index = state.world.find(name)) {
    out.push_back(*index);
    return;
  }
  const xosc::EntitySelection* selection = state.scenario.entities.find_selection(name);
  if (selection == nullptr) {
    throw InputError(source.error("unknown entity or entity selection '" + name + "'"));
  }
  if (depth > 32) {
    throw InputError(selection->source.error("entity selection '" + name + "' contains itself"));
  }
  for (const std::string& member : selection->entity_refs) {
    expand(member, state, selection->source, out, depth + 1);
  }
  for (const xosc::ByType& by_type : selection->by_type) {
    for (uint32_t i = 0; i < state.world.entities.size(); ++i) {
      if (state.world.entities[i].info.kind == object_kind(by_type.object_type) &&
          !state.world.entities[i].ghost) {
        out.push_back(i);
      }
    }
  }
}

}  // namespace

std::vector<uint32_t> expand_entity_refs(const std::vector<std::string>& names,
                                         const SimState& state, const xosc::Source& source) {
  std::vector<uint32_t> out;
  for (const std::string& name : names) {
    expand(name, state, source, out, 0);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace corsa::engine::detail
