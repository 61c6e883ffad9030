#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "corsa/sensors/box.h"
#include "corsa/sensors/geometry.h"
#include "corsa/sensors/material.h"
#include "corsa/sensors/semantic.h"

namespace corsa::sensors {

/// What a static object is, for the per-frame labels (traffic lights with their state, signs
/// with their type). OpenDRIVE signals carry their id, country, type, subtype and value.
struct ObjectInfo {
  std::string kind;       ///< "traffic_light", "traffic_sign", "street_light", "tree", ...
  std::string signal_id;  ///< OpenDRIVE signal id (traffic lights and signs); empty otherwise
  std::string country;
  std::string type;
  std::string subtype;
  std::optional<double> value;
  std::string text;
  /// The object's own oriented box (map frame) when it has one (parked vehicles); the labels
  /// give the axis-aligned bounds of its mesh otherwise.
  std::optional<Box3> box;
  /// The object's class when what it is tells it (parked vehicles: car); the labels give the
  /// class of most of its pixels otherwise (`static` without a semantic camera).
  std::optional<SemanticClass> semantic;
};

/// A triangle mesh placed in map coordinates (metres), with its labels: one semantic class per
/// triangle (or a single class for the whole mesh) and one instance id for the whole mesh, and
/// its look: a palette of materials with one index per triangle (or one for all), optional
/// texture coordinates.
struct StaticMesh {
  std::string name;  ///< for messages and label files (e.g. the model file and node)
  std::vector<Vec3> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;
  /// One class per triangle, or exactly one entry that applies to every triangle.
  std::vector<SemanticClass> classes;
  /// Instance id in instance-segmentation images and point labels; 0 means "no instance" (stuff).
  /// Scene::add_static_mesh assigns ids from kStaticInstanceBase when this is 0 and the class is a
  /// countable one (see is_countable_class).
  uint32_t instance_id = 0;
  /// Base colour for RGB rendering when the mesh has no materials; the class's look otherwise.
  std::optional<Rgb8> color;
  /// Material palette; empty: the `color`, or the look of each triangle's class.
  std::vector<Material> materials;
  /// One index into `materials` per triangle, or one for all (empty: all use materials[0]).
  std::vector<uint16_t> material_indices;
  /// Texture coordinates per vertex (empty when the mesh has none).
  std::vector<std::array<float, 2>> uvs;
  /// Shading normals per vertex (unit, map frame), interpolated over each triangle so that a
  /// smooth surface made of flat triangles (the ground, tree crowns and trunks) shades without
  /// facets; empty: each triangle shades with its own flat normal. A triangle whose three
  /// normals are zero shades flat too (the flat parts of a mesh that has smooth ones).
  std::vector<Vec3> normals;
  /// Traffic-light heads: the OpenDRIVE signal id whose state (WorldSnapshot::signals) switches
  /// the bulbs (materials with LightRole kSignalRed/Yellow/Green).
  std::string signal_id;
  /// What the object is, for the labels; empty kind: not labelled.
  ObjectInfo object;
};

/// Instance ids of static meshes start here so that they never collide with the engine's 1-based
/// entity instance ids (which stay below this in any realistic scenario).
inline constexpr uint32_t kStaticInstanceBase = 32768;

/// Classes of things one can count (buildings, poles, signs, trees, props): their meshes get an
/// instance id of their own. Stuff (road, sidewalk, terrain, marks, sky) does not.
bool is_countable_class(SemanticClass c);

}  // namespace corsa::sensors
