#pragma once

// Private state of a Scene, shared by the renderers of this library (never installed).

#include <embree3/rtcore.h>

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "corsa/sensors/scene.h"
#include "light_list.h"
#include "mesh_builder.h"

namespace corsa::sensors::detail {

/// Labels and material of one geometry of the static scene.
/// Ray mask bit of the static instance in the top-level scenes (entities have every bit).
constexpr unsigned kStaticMask = 1u;

struct StaticGeometry {
  std::vector<SemanticClass> classes;  ///< per triangle, or one entry for all
  std::vector<MaterialId> materials;   ///< per triangle, or one entry for all
  uint32_t instance_id = 0;
  int signal = -1;      ///< index into SceneData::signal_ids (traffic-light heads), or -1
  double base_z = 0.0;  ///< lowest vertex, tracer frame (facades count floors from it)
  size_t triangles = 0;
  /// Texture coordinates (only for meshes that have them): per vertex, the triangles, and the
  /// texture-coordinate units per metre of each triangle (for the texture's mip level).
  std::vector<std::array<float, 2>> uvs;
  std::vector<std::array<uint32_t, 3>> uv_triangles;
  std::vector<float> uv_per_m;
  /// Shading normals per vertex and the triangles (only for meshes that have them).
  std::vector<std::array<float, 3>> normals;
  std::vector<std::array<uint32_t, 3>> normal_triangles;

  SemanticClass class_of(unsigned prim) const {
    return classes.size() == 1 ? classes[0] : classes[prim];
  }
  MaterialId material_of(unsigned prim) const {
    return materials.size() == 1 ? materials[0] : materials[prim];
  }
  /// The material of a hit in the far scene (SceneData::far_static): a dressed building's
  /// plain walls have one, every other geometry is the same there.
  MaterialId far_material_of(unsigned prim) const {
    return far_material ? *far_material : material_of(prim);
  }
  std::optional<MaterialId> far_material;  ///< set for dressed buildings (their plain mesh)
};

/// The shape of one entity in its own frame, with its Embree scene. Articulated shapes (wheels,
/// limbs) move their vertices every frame; the rest pose is kept.
struct EntityShape {
  engine::EntityCategory category = engine::EntityCategory::kCar;
  engine::Box box;
  std::string model3d;
  RTCScene scene = nullptr;
  RTCGeometry geometry = nullptr;
  ArticulatedMesh mesh;               ///< rest pose; `material` holds global ids after setup
  std::vector<MaterialId> materials;  ///< per triangle, global ids
  /// Poses the bones of the mesh for a snapshot (null: rigid). Returns one transform per bone
  /// (bone 0 first), entity frame.
  std::function<void(const engine::EntitySnapshot&, std::vector<Rigid>&)> pose;
  std::vector<Rigid> last_pose;  ///< bones of the last frame (to skip unchanged updates)
  std::vector<LampPatch> lamps;  ///< its lamps (entity frame, rest pose), light sources when lit
  bool seen = false;             ///< placed in the current frame

  EntityShape() = default;
  EntityShape(const EntityShape&) = delete;
  EntityShape& operator=(const EntityShape&) = delete;
  ~EntityShape();
};

/// One placed entity of the current frame.
struct EntityInstance {
  SemanticClass semantic = SemanticClass::kDynamic;
  uint32_t instance_id = 0;
  size_t snapshot_index = 0;  ///< index into SceneData::entities
  EntityShape* shape = nullptr;
  Mat3 normal_matrix;  ///< object-space normal to world normal (the pose's rotation)
  Rigid world_from_entity;
  uint32_t lights_on = 0;   ///< VehicleLight bits from the snapshot
  uint32_t lights_set = 0;  ///< bits the scenario set explicitly
};

constexpr size_t kCategoryCount = static_cast<size_t>(engine::EntityCategory::kObstacle) + 1;

struct SceneData {
  SceneOptions options;
  RTCDevice device = nullptr;
  RTCScene static_scene = nullptr;
  RTCScene top = nullptr;
  /// The static scene as far sky rays see it (same geomIDs): dressed buildings as their plain
  /// meshes (walls without the facade geometry), every other geometry shared with static_scene.
  /// In `top` the static instance has mask kStaticMask, so rays without that bit see only the
  /// entities there.
  RTCScene far_static = nullptr;
  std::vector<StaticGeometry> static_geometries;  ///< by geomID in static_scene
  std::vector<RTCGeometry> instance_pool;         ///< top-level instances, geomID = index + 1
  /// The same entities moving over an interval (Scene::set_entities with a motion span): two
  /// time steps each, Embree ray time 0 and 1 at the interval's ends; geomIDs as in `top`. Only
  /// the LiDAR traces it (a rolling shutter); null until a motion span is first given.
  RTCScene moving_top = nullptr;
  std::vector<RTCGeometry> moving_pool;
  double motion_span = 0.0;                                 ///< s, of the last set_entities
  std::vector<EntityInstance> instances;                    ///< this frame's, by pool index
  std::vector<engine::EntitySnapshot> entities;             ///< this frame's snapshot entities
  std::map<uint32_t, std::unique_ptr<EntityShape>> shapes;  ///< by entity instance id
  std::shared_ptr<EntityShapeSource> shape_source;
  std::vector<Material> materials;  ///< by MaterialId
  std::map<std::string, MaterialId> material_keys;
  std::array<MaterialId, kSemanticClassCount> class_materials{};
  std::vector<std::string> signal_ids;     ///< signals that switch traffic-light heads
  std::vector<std::string> signal_states;  ///< this frame's state strings, by index
  std::vector<uint8_t> signal_bulbs;       ///< lit bulbs, bit 0 red, 1 yellow, 2 green
  std::vector<LampPatch> static_lamps;     ///< street lamps and signal bulbs, tracer frame
  /// Labelled static objects by instance id: what they are, their bounds (map frame) and the
  /// signal index of traffic lights (-1 otherwise).
  struct ObjectRecord {
    ObjectInfo info;
    Bounds bounds;
    int signal = -1;
    /// Objects with their own box (parked vehicles): a scene of their triangles alone (tracer
    /// frame), the silhouette their occlusion in a camera is measured against.
    RTCScene alone = nullptr;
  };
  std::map<uint32_t, ObjectRecord> objects;
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
      return {g.class_of(prim_id), g.instance_id, -1};
    }
    const EntityInstance& e = instances[inst_id - 1];
    return {e.shape->mesh.classes[prim_id], e.instance_id, static_cast<int>(inst_id - 1)};
  }
  MaterialId material_of(unsigned inst_id, unsigned geom_id, unsigned prim_id) const {
    if (inst_id == 0) {
      return static_geometries[geom_id].material_of(prim_id);
    }
    return instances[inst_id - 1].shape->materials[prim_id];
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

/// The generated shape of an entity (entity_assets.cpp): its mesh in the entity frame and, for
/// articulated ones, how its bones move.
void build_entity_shape(const engine::EntitySnapshot& entity, uint64_t seed, EntityShape& shape);

}  // namespace corsa::sensors::detail
