#pragma once

// Entities from the scenario's Entities (OpenSCENARIO 1.3 §6.2): one per ScenarioObject, in
// document order; their category, bounding box and performance.

namespace corsa::engine::detail {

struct SimState;

/// Fills state.world. ExternalObjectReferences (objects only the simulator would know) get an
/// empty box and a warning.
void build_entities(SimState& state);

}  // namespace corsa::engine::detail
