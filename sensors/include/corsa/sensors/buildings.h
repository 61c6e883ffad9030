#pragma once

// Simple building models: footprint polygons extruded to a height (walls and a flat roof), for
// scenes and for producing the bundled model files (FBX, glTF) that exercise the import path.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "corsa/core/vec.h"
#include "corsa/sensors/static_mesh.h"

namespace corsa::sensors {

struct Footprint {
  std::string name;
  std::vector<Vec2> ring;  ///< simple polygon (x, y in metres), either orientation
  double height = 10.0;    ///< metres above base_z
  double base_z = 0.0;
  std::optional<Rgb8> color;
};

/// Walls (normals outward) and a roof (ear-clipped, normals up); class building. Throws
/// std::invalid_argument for fewer than three distinct points or a non-positive height.
StaticMesh extrude_footprint(const Footprint& footprint);

/// Rows of rectangular and L-shaped buildings on both sides of a straight street along +x
/// starting at the origin (`length` metres long, kerb at |y| = street_half_width), in local
/// metres; sizes and heights are drawn from `seed`.
std::vector<Footprint> street_district(double length, double street_half_width, uint64_t seed);

}  // namespace corsa::sensors
