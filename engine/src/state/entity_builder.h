#pragma once

// Entities from the scenario's Entities (OpenSCENARIO 1.3 §6.2): one per ScenarioObject, in
// document order; their category, bounding box and performance.

#include "corsa/core/diagnostic.h"
#include "corsa/engine/entity_state.h"
#include "corsa/xosc/enums.h"

namespace corsa::xosc {
struct ScenarioObject;
}

namespace corsa::engine::detail {

struct SimState;

/// Kind, category, box and performance of a scenario object (also of the objects traffic
/// generators spawn).
EntityInfo describe_object(const xosc::ScenarioObject& object, Diagnostics& diagnostics);

/// The entity kind an OpenSCENARIO ObjectType names (ByType in CollisionCondition and entity
/// selections).
ObjectKind object_kind(xosc::ObjectType type);

/// Fills state.world. ExternalObjectReferences (objects only the simulator would know) get an
/// empty box and a warning.
void build_entities(SimState& state);

}  // namespace corsa::engine::detail
