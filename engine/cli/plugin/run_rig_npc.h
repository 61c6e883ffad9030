#pragma once

// `--npc vehicles=N,pedestrians=M`: seeded random NPCs for data collection. The engine cannot
// add entities to a running simulation yet (AddEntityAction and TrafficSwarm are issue #6), so
// the NPCs are simply moving objects added to the world the sensors see: vehicles drive along
// their driving lane (in the lane's travel direction under the road's traffic rule) at a speed
// fixed per lane, pedestrians walk along sidewalks at 1.0-1.6 m/s; each stops at its road's
// end. They are seen and labelled like scenario entities but take no part in the scenario's
// conditions or collisions.

#include <cstdint>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/engine/simulation.h"
#include "corsa/engine/world_snapshot.h"

namespace corsa::xodr {
class Map;
}

namespace corsa::cli {

/// One NPC's path: along s of one lane of one road, at a constant speed.
struct NpcTrack {
  uint32_t road = 0;
  int lane = 0;
  double s0 = 0.0;
  double direction = 1.0;  ///< +1 along s, -1 against
  double speed = 0.0;      ///< m/s
};

struct NpcSet {
  const xodr::Map* map = nullptr;
  std::vector<engine::EntitySnapshot> entities;  ///< at tick 0
  std::vector<NpcTrack> tracks;                  ///< one per entity

  bool empty() const { return entities.empty(); }
};

/// Places the NPCs at tick 0 (seeded by the run seed): random road, s and lane of the right
/// type, at least 10 m (vehicles) or 2 m (pedestrians) from every entity and other NPC.
/// Instance ids follow the scenario's entities. Warns when fewer fit than asked.
NpcSet place_npcs(const engine::Simulation& simulation, int vehicles, int pedestrians,
                  Diagnostics& diagnostics);

/// Moves the NPCs to the snapshot's time and appends them to its entities.
void move_npcs(const NpcSet& npcs, engine::WorldSnapshot& world);

}  // namespace corsa::cli
