#pragma once

// The straight street the sensor benchmarks render: a road along +x from x = -100 to 300 m,
// `road_half_width` metres each side of y = 0, a 16 cm centre mark 1 cm above it, 4 m sidewalks
// 15 cm high on both sides, and flat land of lane type `outside` out to |y| = 300 m. Map frame,
// metres.

#include <cstdint>

#include "corsa/xodr/road_mesh.h"

namespace corsa::bench {

inline xodr::RoadMesh street_mesh(double road_half_width, xodr::LaneType outside) {
  using xodr::LaneType;
  xodr::RoadMesh road;
  auto quad = [&](double y0, double y1, double z, LaneType type, bool mark) {
    const auto base = static_cast<uint32_t>(road.vertices.size());
    road.vertices.push_back({-100.0, y0, z});
    road.vertices.push_back({300.0, y0, z});
    road.vertices.push_back({300.0, y1, z});
    road.vertices.push_back({-100.0, y1, z});
    road.triangles.push_back({base, base + 1, base + 2});
    road.triangles.push_back({base, base + 2, base + 3});
    xodr::TriangleInfo info;
    info.lane_type = type;
    info.kind = mark ? xodr::SurfaceKind::kRoadMark : xodr::SurfaceKind::kLane;
    road.info.push_back(info);
    road.info.push_back(info);
  };
  const double w = road_half_width;
  quad(-w, w, 0.0, LaneType::kDriving, false);
  quad(-0.08, 0.08, 0.01, LaneType::kDriving, true);
  quad(-w - 4.0, -w, 0.15, LaneType::kSidewalk, false);
  quad(w, w + 4.0, 0.15, LaneType::kSidewalk, false);
  quad(-300.0, -w - 4.0, 0.0, outside, false);
  quad(w + 4.0, 300.0, 0.0, outside, false);
  return road;
}

}  // namespace corsa::bench
