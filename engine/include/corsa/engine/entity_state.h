#pragma once

// What the engine knows of one entity: its fixed description (EntityInfo, from the scenario's
// Entities) and its state at the current step (EntityState). Map coordinates in metres and
// radians, OpenDRIVE/OpenSCENARIO conventions (heading counter-clockwise from +x).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "corsa/engine/world_snapshot.h"

namespace corsa::engine {

/// The kind of OpenSCENARIO object an entity is (ObjectType, §6.2).
enum class ObjectKind : uint8_t { kVehicle, kPedestrian, kMiscObject, kExternal };

/// The fields a step reads first (the engine keeps an entity's run state in the order its steps
/// read it, and the name and model last, as no step reads them).
struct EntityInfo {
  ObjectKind kind = ObjectKind::kVehicle;
  EntityCategory category = EntityCategory::kCar;
  Box box;  ///< bounding box relative to the reference point (vehicles: rear axle centre)
  /// Performance of vehicles (m/s, m/s^2); zero when not a vehicle.
  double max_speed = 0.0;
  double max_acceleration = 0.0;
  double max_deceleration = 0.0;
  /// Performance maxAccelerationRate / maxDecelerationRate (m/s^3, 1.2+); zero when not given.
  double max_acceleration_rate = 0.0;
  double max_deceleration_rate = 0.0;
  std::string name;
  std::string model3d;
};

/// Road coordinates of an entity's reference point (OpenDRIVE 1.8 §2.3 reference line frame).
struct RoadCoordinates {
  uint32_t road = 0;     ///< index into the map's roads (xodr::Map::road)
  uint32_t section = 0;  ///< lane section index within the road
  int lane = 0;          ///< the lane containing the point (its id, > 0 left)
  double s = 0.0;        ///< m along the reference line
  double t = 0.0;        ///< m to the left of the reference line
};

struct EntityState {
  Pose pose;
  double speed = 0.0;          ///< m/s along the heading; negative when reversing
  double acceleration = 0.0;   ///< m/s^2, longitudinal, over the last step
  double lateral_speed = 0.0;  ///< m/s, across the heading (positive to the left)
  double yaw_rate = 0.0;       ///< rad/s over the last step
  double odometer = 0.0;       ///< m driven since the start (always increasing)
  bool placed = false;         ///< false until a position has been given (TeleportAction)
  /// VisibilityAction's sensors flag; with a SensorReferenceSet the flag of the sensors it does
  /// not name (WorldSnapshot's EntitySnapshot::sensor_exceptions has the named ones).
  bool visible = true;
  /// Nothing when the entity is off every lane (or the scenario has no road network).
  std::optional<RoadCoordinates> road;
};

/// One field of every entity of a run where the run keeps it, inside the engine's per-entity
/// records: each `stride` bytes after the one before.
template <class Field>
class EntityFields {
 public:
  EntityFields() = default;
  EntityFields(const Field* first, size_t count, size_t stride)
      : first_(reinterpret_cast<const std::byte*>(first)), count_(count), stride_(stride) {}

  size_t size() const { return count_; }
  const Field& operator[](size_t index) const {
    return *reinterpret_cast<const Field*>(first_ + index * stride_);
  }

 private:
  const std::byte* first_ = nullptr;
  size_t count_ = 0;
  size_t stride_ = 0;
};

/// The states of a run's entities (Simulation::states).
using EntityStates = EntityFields<EntityState>;
/// Each entity's count of its state's writes (Simulation::state_changes): while an entity's
/// count is one a reader saw, its state is the one it saw then, bit for bit.
using EntityStateChanges = EntityFields<uint32_t>;

}  // namespace corsa::engine
