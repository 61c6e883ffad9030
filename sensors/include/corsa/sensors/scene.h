#pragma once

// The ray-casting scene: static geometry (road mesh, building models) committed once, and the
// scenario's entities as instances of per-category prototype shapes moved every frame without
// rebuilding the static geometry. Every primitive carries a semantic class and an instance id.

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "corsa/engine/world_snapshot.h"
#include "corsa/sensors/geometry.h"
#include "corsa/sensors/semantic.h"
#include "corsa/sensors/static_mesh.h"
#include "corsa/xodr/road_mesh.h"

namespace corsa::sensors {

namespace detail {
struct SceneData;
}

struct SceneOptions {
  /// Map point subtracted from every coordinate before the single-precision ray tracer sees it
  /// (UTM-sized coordinates would otherwise lose centimetres). Pick a point inside the map.
  Vec3 origin;
};

/// What one ray hit.
struct RayHit {
  double distance = 0.0;  ///< metres along the (unit) ray direction
  Vec3 point;             ///< map coordinates
  Vec3 normal;            ///< unit geometric normal in map coordinates, facing the ray origin
  SemanticClass semantic = SemanticClass::kNone;
  uint32_t instance_id = 0;
  int entity_index = -1;  ///< index into the entities of the last set_entities, -1 for static
};

/// An axis-aligned box in map coordinates.
struct Bounds {
  Vec3 min{1e300, 1e300, 1e300};
  Vec3 max{-1e300, -1e300, -1e300};
  bool empty() const { return min.x > max.x; }
};

class Scene {
 public:
  explicit Scene(const SceneOptions& options = {});
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;
  Scene(Scene&&) noexcept;
  Scene& operator=(Scene&&) noexcept;

  /// Adds the road surface: lanes by lane type, road marks as lane markings. Instance id 0.
  void add_road_mesh(const xodr::RoadMesh& mesh);
  /// Adds a static mesh; returns the instance id it carries (assigned when mesh.instance_id == 0
  /// for buildings and static objects). Throws std::invalid_argument on inconsistent data.
  uint32_t add_static_mesh(StaticMesh mesh);
  /// Replaces the prototype shape for an entity category. The mesh is in unit-box coordinates
  /// ([-0.5, 0.5] on each axis, x forward, y left, z up) and is scaled to each entity's bounding
  /// box. The class of the mesh is ignored (the entity's category decides).
  void set_prototype(engine::EntityCategory category, const StaticMesh& unit_mesh);
  /// Builds the static acceleration structure; call once after adding static geometry (adding
  /// more later needs another commit).
  void commit();

  /// Places the entities for the next frame (invisible ones are left out): only their instance
  /// transforms and the small top-level structure are rebuilt.
  void set_entities(std::span<const engine::EntitySnapshot> entities);
  std::span<const engine::EntitySnapshot> entities() const;

  /// Closest hit along a ray (direction need not be unit), up to max_distance metres.
  std::optional<RayHit> intersect(Vec3 origin, Vec3 direction, double max_distance) const;

  Bounds static_bounds() const;
  const SceneOptions& options() const;
  size_t static_mesh_count() const;
  size_t static_triangle_count() const;

  /// Internal state for the renderers in this library.
  const detail::SceneData& data() const { return *data_; }

 private:
  std::unique_ptr<detail::SceneData> data_;
};

}  // namespace corsa::sensors
