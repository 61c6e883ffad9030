#pragma once

// 3D models in and out through assimp: FBX, OBJ, glTF/GLB, 3DS (and whatever else assimp reads),
// placed into map coordinates through a georeference, a scale and an offset.

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/sensors/geometry.h"
#include "corsa/sensors/rig.h"
#include "corsa/sensors/scene.h"
#include "corsa/sensors/semantic.h"
#include "corsa/sensors/static_mesh.h"

namespace corsa::sensors {

enum class UpAxis { kAuto, kZ, kY };

/// Where a model goes. Two georeferencing modes:
/// - with `anchor`: the model is in local metres (x east, y north, up) around the anchor point,
///   given in `model_crs` (e.g. longitude/latitude in EPSG:4326); the anchor is transformed to
///   the map CRS and the model rotated by the grid convergence there, so north stays north;
/// - without: every vertex is in `model_crs` and is transformed on its own.
/// Empty CRSs mean the model is already in map coordinates. Order: up-axis fix, scale, heading
/// (radians, counter-clockwise about up), georeference, then `offset` (map metres).
struct ModelPlacement {
  std::string model_crs;
  std::string map_crs;
  std::optional<Vec3> anchor;
  double scale = 1.0;
  double heading = 0.0;
  Vec3 offset;
  UpAxis up_axis = UpAxis::kAuto;  ///< auto: y-up for glTF/GLB (the glTF convention), else z-up
  SemanticClass semantic = SemanticClass::kBuilding;
  /// Receives located warnings (a texture that cannot be read); may be null.
  Diagnostics* diagnostics = nullptr;
};

/// Shapes of entities from their OpenSCENARIO model3d files (any format assimp reads, with
/// their materials and textures), scaled to each entity's bounding box (the model's bounds
/// stretched onto the box; models face +x with z up, glTF/GLB turned z-up). Relative model3d
/// paths are resolved against `base` (the scenario's folder). Entities without model3d take the
/// user's model from `models` (the command line's --entity-model and the rig's <EntityModel>s,
/// each located by its `origin`, else by `rig_file`, in messages): the first naming the entity,
/// else the first for its category; with none they keep their generated shape. A file that is
/// missing or cannot be read is one located warning (at the rig's element or the command-line
/// option for `models`) and the entity gets its generated shape.
/// The OpenSCENARIO vehicle, pedestrian and misc-object category names an EntityModel may
/// name ("car", "van", ..., "pedestrian", ..., "obstacle"), in the standard's order.
const std::vector<std::string>& entity_category_names();

class ModelShapeSource : public EntityShapeSource {
 public:
  ModelShapeSource(std::filesystem::path base, Diagnostics& diagnostics,
                   std::vector<EntityModel> models = {}, std::string rig_file = {});
  bool shape_of(const engine::EntitySnapshot& entity, StaticMesh& mesh) override;
  /// True when the entity names a model (its model3d, or a rig model for its name or category):
  /// shape_of tries that model before any generated shape.
  bool names_model(const engine::EntitySnapshot& entity) const;

 private:
  const EntityModel* model_for(const engine::EntitySnapshot& entity) const;

  std::filesystem::path base_;
  Diagnostics& diagnostics_;
  std::vector<EntityModel> models_;
  std::string rig_file_;
  std::map<std::string, std::optional<std::vector<StaticMesh>>> loaded_;
};

/// Loads every mesh of the model as its own StaticMesh (one instance per node mesh), named
/// "<file>:<node>". A missing or broken file, or one without triangles, throws
/// corsa::InputError naming the file.
std::vector<StaticMesh> load_model(const std::filesystem::path& path,
                                   const ModelPlacement& placement);

/// Writes meshes as a model file; files appear under their names only when complete. `format` is
/// an assimp exporter id: "fbxa" (ASCII FBX 7.5), "fbx" (binary FBX, which assimp 5.2 itself
/// cannot read back), "gltf2", "glb2", "obj", "3ds". With `y_up`, z-up vertices are written y-up
/// (as glTF requires). Each mesh becomes one node with its name and colour. The FBX exporter
/// stamps the creation time into the file; the other formats are byte-identical for equal input.
void write_model(const std::vector<StaticMesh>& meshes, const std::filesystem::path& path,
                 const std::string& format, bool y_up = false);

}  // namespace corsa::sensors
