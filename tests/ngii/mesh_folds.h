#pragma once

// Roads whose mesh folds over itself: a lane border or road mark beyond the reference line's
// centre of curvature (its normals cross), which `corsa map render` and the sensors leave out
// of the road surface (xodr/road_mesh.h warns once per road).

#include <cstddef>

#include "corsa/xodr/map.h"

namespace corsa::test {

/// Mesh tolerance (m) of the fold count: that of `corsa map render --scale 0.25` (0.3 pixel).
constexpr double kFoldTolerance = 0.075;

/// How many roads of `map` fold (lane surfaces and road marks meshed at kFoldTolerance);
/// CORSA_MEASURE_LIST=1 prints each warning on stderr.
size_t folded_roads(const xodr::Map& map);

}  // namespace corsa::test
