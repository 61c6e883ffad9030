#pragma once

// The ray-casting scene: static geometry (road mesh, terrain, roadside objects, building models)
// committed once, and the scenario's entities, each with its own generated (or loaded) shape in
// its own frame, placed by an instance transform every frame and articulated where it moves
// (wheels turn and steer, people walk) without rebuilding the static geometry. Every primitive
// carries a semantic class, an instance id and a material.

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "corsa/engine/world_snapshot.h"
#include "corsa/sensors/geometry.h"
#include "corsa/sensors/material.h"
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
  /// Run seed: vehicle paint and model variants, people's builds and clothes are drawn from it
  /// and each entity's name, so the same seed gives the same look.
  uint64_t seed = 0;
};

/// Builds the shape of an entity the scene has not seen before (for users' model3d files);
/// returns false to let the scene generate one by category. Called on the thread that calls
/// Scene::set_entities.
class EntityShapeSource {
 public:
  virtual ~EntityShapeSource() = default;
  /// Fills `mesh` in the entity's frame (x forward, y left, z up, metres; the snapshot's
  /// reference point at the origin) when it provides one.
  virtual bool shape_of(const engine::EntitySnapshot& entity, StaticMesh& mesh) = 0;
};

/// What one ray hit.
struct RayHit {
  double distance = 0.0;  ///< metres along the (unit) ray direction
  Vec3 point;             ///< map coordinates
  Vec3 normal;            ///< unit geometric normal in map coordinates, facing the ray origin
  SemanticClass semantic = SemanticClass::kUnlabeled;
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
  /// Adds a material to the table (an equal one already there is reused) and returns its id.
  MaterialId add_material(const Material& material);
  const Material& material(MaterialId id) const;
  size_t material_count() const;
  /// Where shapes of entities come from before the built-in generators (may be null).
  void set_entity_shape_source(std::shared_ptr<EntityShapeSource> source);
  /// Builds the static acceleration structure; call once after adding static geometry (adding
  /// more later needs another commit).
  void commit();

  /// Places the entities for the next frame (invisible ones are left out): only their instance
  /// transforms, the articulated parts (wheels, limbs) and the small top-level structure are
  /// rebuilt. An entity seen for the first time gets its shape (generated from its category,
  /// bounding box, name and the run seed, or from the shape source). With a `motion_span` (s)
  /// the LiDAR also sees each entity move over that interval centred on the snapshot's time (its
  /// velocity and yaw rate), for the rolling shutter of a spinning sensor; cameras see the
  /// snapshot's instant.
  void set_entities(std::span<const engine::EntitySnapshot> entities, double motion_span = 0.0);
  /// The traffic-signal states of the next frame (OpenSCENARIO TrafficSignalState strings by
  /// OpenDRIVE signal id): they switch the bulbs of the traffic-light meshes.
  void set_signals(std::span<const engine::SignalSnapshot> signals);
  /// The state string of a signal in the current frame ("" when the scenario gave none).
  std::string signal_state(const std::string& signal_id) const;
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
