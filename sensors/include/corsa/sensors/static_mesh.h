#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "corsa/sensors/geometry.h"
#include "corsa/sensors/semantic.h"

namespace corsa::sensors {

/// A triangle mesh placed in map coordinates (metres), with its labels: one semantic class per
/// triangle (or a single class for the whole mesh) and one instance id for the whole mesh.
struct StaticMesh {
  std::string name;  ///< for messages and label files (e.g. the model file and node)
  std::vector<Vec3> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;
  /// One class per triangle, or exactly one entry that applies to every triangle.
  std::vector<SemanticClass> classes;
  /// Instance id in instance-segmentation images and point labels; 0 means "no instance" (stuff).
  /// Scene::add_static_mesh assigns ids from kStaticInstanceBase when this is 0 and the class is a
  /// countable one (buildings, static objects).
  uint32_t instance_id = 0;
  std::optional<Rgb8> color;  ///< base colour for RGB rendering; class default when absent
};

/// Instance ids of static meshes start here so that they never collide with the engine's 1-based
/// entity instance ids (which stay below this in any realistic scenario).
inline constexpr uint32_t kStaticInstanceBase = 32768;

}  // namespace corsa::sensors
