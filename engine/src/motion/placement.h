#pragma once

// Putting an entity at a resolved position (TeleportAction, OpenSCENARIO 1.3 §7.4.3): on a lane
// when the position is on one (the default controller then follows that lane), otherwise free.

#include "corsa/xosc/common.h"
#include "positions/position_resolver.h"
#include "state/entity.h"

namespace corsa::engine::detail {

struct SimState;

/// Distance (m) from every lane beyond which a position is "off the map".
inline constexpr double kOffMapDistance = 20.0;

/// Places `entity`. With `require_on_map` (the Init placement) a position farther than
/// kOffMapDistance from every lane of the road network is an InputError located at `source`.
void place_entity(SimState& state, Entity& entity, const ResolvedPosition& position,
                  const xosc::Source& source, bool require_on_map);

/// The entity has jumped to where it now is (placed, connected as a trailer): that is no travel
/// for Entity::straight_travel.
void mark_jump(Entity& entity);

/// Adds each placed entity's straight distance from its last place (the end of the previous
/// step, or where it jumped to) to Entity::straight_travel: once per step, after every move.
void sum_straight_travel(SimState& state);

}  // namespace corsa::engine::detail
