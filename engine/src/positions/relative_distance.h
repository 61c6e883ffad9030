#pragma once

// Distances between an entity and another entity or a position, as the distance conditions
// define them (OpenSCENARIO 1.3 §8.3.1: DistanceCondition, RelativeDistanceCondition,
// TimeHeadwayCondition, TimeToCollisionCondition): in a coordinate system (entity: the
// triggering entity's frame; road / lane: along and across the road; world: world axes), of a
// type (longitudinal, lateral, euclidean), between reference points or, with freespace, between
// bounding boxes.

#include <cstdint>
#include <optional>

#include "corsa/xosc/enums.h"
#include "positions/position_resolver.h"
#include "state/entity.h"

namespace corsa::engine::detail {

struct SimState;

struct DistanceSpec {
  xosc::CoordinateSystem system = xosc::CoordinateSystem::kEntity;
  xosc::RelativeDistanceType type = xosc::RelativeDistanceType::kEuclidianDistance;
  bool freespace = false;
};

/// The distance from `from` to `to`. Longitudinal is positive when `to` is ahead of `from`
/// (in its direction of travel), lateral positive when `to` is to its left; euclidean is never
/// negative. Road and lane coordinates need both on the same road; otherwise the entity frame is
/// used instead.
double entity_distance(const SimState& state, const Entity& from, const Entity& to,
                       const DistanceSpec& spec);

/// What entity_distance reads of its two entities besides the map and their boxes (fixed for a
/// run, Entity::info): their poses and road coordinates and `from`'s lane direction. Equal to
/// the bit, the same distance (-0 and +0 differ, a NaN equals itself). One pair of entities is
/// asked about, the same `from` and `to` each time: an entity whose state's count of writes
/// stands since the inputs were taken (EntityMotion::state_changes) holds the pose and road
/// coordinates taken.
class EntityDistanceInputs {
 public:
  void take(const Entity& from, const Entity& to);
  bool same_as(const Entity& from, const Entity& to) const;

 private:
  struct Party {
    Pose pose;
    std::optional<RoadCoordinates> road;
    uint32_t changes = 0;  ///< the entity's count of its state's writes
  };
  Party from_, to_;
  bool from_on_road_ = false;
  int from_dir_ = 0;
  bool taken_ = false;
};

/// The same from an entity to a position (a point: freespace uses only `from`'s box).
double position_distance(const SimState& state, const Entity& from, const ResolvedPosition& to,
                         const DistanceSpec& spec);

/// The coordinate system a distance condition asks for: coordinateSystem, else the deprecated
/// alongRoute (true: road), else the entity frame.
xosc::CoordinateSystem coordinate_system(std::optional<xosc::CoordinateSystem> system,
                                         std::optional<bool> along_route);

}  // namespace corsa::engine::detail
