#pragma once

// What generated traffic is made of and how it is put on the road (OpenSCENARIO 1.3 §7.5.6):
// the mix of objects a traffic action spawns (TrafficDistribution, else the deprecated
// TrafficDefinition's vehicle categories, else cars) and the base of every generator (swarm,
// source, area, NPCs): new entities appended after the scenario's own, reused when a generator
// respawns an object of the same kind, each draw from a stream of the run seed.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "corsa/core/random.h"
#include "corsa/xosc/global_actions.h"
#include "positions/position_resolver.h"
#include "state/point_grid.h"
#include "state/traffic_state.h"

namespace corsa::engine::detail {

/// The kinds of object a traffic action spawns, with their probabilities.
class TrafficMix {
 public:
  /// From a TrafficDistribution when given (each EntityDistributionEntry's weight within its
  /// TrafficDistributionEntry, times that entry's weight), else from the TrafficDefinition's
  /// vehicle categories, else one car.
  TrafficMix(const std::optional<xosc::TrafficDefinition>& definition,
             const xosc::TrafficDistribution* distribution);
  /// A single prototype (the NPCs: a car, or a pedestrian).
  explicit TrafficMix(xosc::ScenarioObject prototype);

  /// Index of a prototype, drawn by weight.
  size_t draw(RandomStream& random) const;
  const xosc::ScenarioObject& prototype(size_t index) const { return prototypes_[index]; }
  bool walks(size_t index) const;  ///< a pedestrian: spawned on sidewalks
  /// The Properties of the TrafficDistributionEntry prototype `index` belongs to (nullptr
  /// without a TrafficDistribution).
  const xosc::Properties* entry_properties(size_t index) const {
    return index < entry_properties_.size() ? entry_properties_[index] : nullptr;
  }

 private:
  std::vector<xosc::ScenarioObject> prototypes_;
  std::vector<double> weights_;
  std::vector<const xosc::Properties*> entry_properties_;  ///< by prototype; the scenario's
};

/// A car, truck or bus, or two-wheeler of `category`: box, mass and Performance by category.
xosc::Vehicle vehicle_model(xosc::VehicleCategory category);
/// An adult pedestrian: 0.5 x 0.6 x 1.8 m, 75 kg.
xosc::Pedestrian pedestrian_model();

/// The centre of the nearest lane to (x, y) within `reach` metres that the object may use
/// (drivable lanes; sidewalks for pedestrians), facing its direction of travel (right-hand
/// traffic: lanes right of the reference line toward +s; pedestrians either way, by `flip`).
std::optional<ResolvedPosition> lane_spot(const xodr::Map& map, double x, double y, bool walks,
                                          bool flip = false, double reach = 4.0);

/// No placed entity's reference point closer than `clearance` metres to (x, y). With `grid`
/// (every placed entity's reference point, by index) only the entities near (x, y) are looked
/// at; the answer is the same.
bool clear_of_others(const SimState& state, double x, double y, double clearance,
                     const PointGrid* grid = nullptr);

/// A PointGrid of every placed entity's reference point (cells of `cell` metres).
PointGrid placed_entities_grid(const SimState& state, double cell);

/// The base of the traffic generators: spawning (a new entity, or one of ours that left
/// reused for an object of the same prototype), and keeping track of which are present.
class GeneratorBase : public TrafficGenerator {
 public:
  GeneratorBase(std::optional<std::string> name, std::string stem, uint64_t seed)
      : name_(std::move(name)), stem_(std::move(stem)), random_(seed) {}
  const std::optional<std::string>& name() const override { return name_; }

 protected:
  /// Puts an object of `mix` prototype `kind` at `at`, driving (walking) at `speed` m/s. A new
  /// entity is called `name`, by default `<trafficName or stem>_<n>`.
  uint32_t spawn(SimState& state, const TrafficMix& mix, size_t kind, const ResolvedPosition& at,
                 double speed, const std::string& name = {});
  /// Ours removed by others (a sink, a DeleteEntityAction) are free again.
  void prune(const SimState& state);
  /// Removes one of ours.
  void despawn(SimState& state, uint32_t index);

  std::optional<std::string> name_;
  std::string stem_;
  RandomStream random_;
  std::vector<uint32_t> mine_;  ///< present entities of this generator

 private:
  struct FreeSlot {
    uint32_t index = 0;
    const TrafficMix* mix = nullptr;
    size_t kind = 0;
  };
  std::vector<FreeSlot> free_;   ///< ours that left, reusable for the same prototype
  std::vector<FreeSlot> kinds_;  ///< the prototype of each of ours (present ones)
};

}  // namespace corsa::engine::detail
