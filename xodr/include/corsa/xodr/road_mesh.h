#pragma once

// Triangulated road surface for the sensors and segmentation labels: lane surfaces (every lane
// type, so sidewalks and shoulders are there too) and road marks as thin strips slightly above.

#include <array>
#include <cstdint>
#include <vector>

#include "corsa/xodr/model.h"

namespace corsa::xodr {

struct Vec3 {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
};

enum class SurfaceKind : uint8_t { kLane, kRoadMark };

/// What a triangle belongs to.
struct TriangleInfo {
  uint32_t road_index = 0;  ///< index into MapData::roads
  int32_t lane_id = 0;
  LaneType lane_type = LaneType::kNone;
  SurfaceKind kind = SurfaceKind::kLane;
  bool in_junction = false;
};

/// Triangles in map coordinates (metres), counter-clockwise seen from above (normals up).
struct RoadMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;
  std::vector<TriangleInfo> info;  ///< one per triangle
};

}  // namespace corsa::xodr
