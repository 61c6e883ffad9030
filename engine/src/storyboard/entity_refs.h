#pragma once

// Entity references in actors and triggering entities: a ScenarioObject's name, or an
// EntitySelection's (OpenSCENARIO 1.3 §6.2.3), expanded to entity indices in document order.

#include <cstdint>
#include <string>
#include <vector>

#include "corsa/xosc/common.h"

namespace corsa::engine::detail {

struct SimState;

/// Indices of the entities named (selections expanded, duplicates removed, sorted). Throws
/// InputError located at `source` for a name that is neither an entity nor a selection.
std::vector<uint32_t> expand_entity_refs(const std::vector<std::string>& names,
                                         const SimState& state, const xosc::Source& source);

}  // namespace corsa::engine::detail
