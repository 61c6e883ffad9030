#pragma once

// Private state of a Scene, shared by the renderers of this library (never installed).

#include <embree3/rtcore.h>

#include <array>
#include <optional>
#include <vector>

#include "corsa/sensors/scene.h"

namespace corsa::sensors::detail {

/// Labels and material of one geometry of the static scene.
struct StaticGeometry {
  std::vector<SemanticClass> classes;  ///< per triangle, or one entry for all
  uint32_t instance_id = 0;
  std::optional<Rgb8> color;  ///< from the model; otherwise the class decides
  size_t triangles = 0;
};

/// One placed entity of the current frame.
struct EntityInstance {
  SemanticClass semantic = SemanticClass::kObstacle;
  uint32_t instance_id = 0;
  size_t snapshot_index = 0;  ///< index into SceneData::entities
  Mat3 normal_matrix;         ///< object-space normal to world normal (inverse transpose)
};

constexpr size_t kCategoryCount = static_cast<size_t>(engine::EntityCategory::kObstacle) + 1;

struct SceneData {
  SceneOptions options;
  RTCDevice device = nullptr;
  RTCScene static_scene = nullptr;
  RTCScene top = nullptr;
  std::array<RTCScene, kCategoryCount> prototypes{};
  std::vector<StaticGeometry> static_geometries;  ///< by geomID in static_scene
  std::vector<RTCGeometry> instance_pool;         ///< top-level instances, geomID = index + 1
  std::vector<EntityInstance> instances;          ///< this frame's, by pool index
  std::vector<engine::EntitySnapshot> entities;   ///< this frame's snapshot entities
  Bounds bounds;
  size_t triangle_count = 0;
  bool committed = false;

  ~SceneData();

  /// Semantic class and instance id of a hit (instID from RTCHit; RTC_INVALID_GEOMETRY_ID when
  /// the top scene itself was hit, which never happens: everything is instanced).
  struct Label {
    SemanticClass semantic;
    uint32_t instance_id;
    int entity;  ///< pool index, -1 static
  };
  Label label(unsigned inst_id, unsigned geom_id, unsigned prim_id) const {
    if (inst_id == 0) {
      const StaticGeometry& g = static_geometries[geom_id];
      const SemanticClass c = g.classes.size() == 1 ? g.classes[0] : g.classes[prim_id];
      return {c, g.instance_id, -1};
    }
    const EntityInstance& e = instances[inst_id - 1];
    return {e.semantic, e.instance_id, static_cast<int>(inst_id - 1)};
  }
  /// World-space normal from Embree's object-space geometric normal.
  Vec3 world_normal(unsigned inst_id, Vec3 ng) const {
    if (inst_id == 0) {
      return normalized(ng);
    }
    return normalized(instances[inst_id - 1].normal_matrix * ng);
  }
  /// Map coordinates to the tracer's local frame and back.
  Vec3 to_local(Vec3 p) const { return p - options.origin; }
  Vec3 to_map(Vec3 p) const { return p + options.origin; }
};

/// Default prototype shapes in unit-box coordinates (prototypes.cpp).
StaticMesh default_prototype(engine::EntityCategory category);

}  // namespace corsa::sensors::detail
