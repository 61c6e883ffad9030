#pragma once

// Small scenes with known answers for the sensor tests.

#include <string>

#include "corsa/engine/world_snapshot.h"
#include "corsa/sensors/scene.h"
#include "corsa/xodr/road_mesh.h"

namespace corsa::test {

/// A square road surface of half-size `half` metres at height z = 0, two triangles.
inline xodr::RoadMesh flat_road(double half = 500.0) {
  xodr::RoadMesh mesh;
  mesh.vertices = {{-half, -half, 0.0}, {half, -half, 0.0}, {half, half, 0.0}, {-half, half, 0.0}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  xodr::TriangleInfo info;
  info.lane_type = xodr::LaneType::kDriving;
  mesh.info = {info, info};
  return mesh;
}

/// An axis-aligned box obstacle entity: centre (x, y, z_bottom + height / 2).
inline engine::EntitySnapshot box_entity(
    uint32_t id, const std::string& name, double x, double y, double length, double width,
    double height, engine::EntityCategory category = engine::EntityCategory::kObstacle) {
  engine::EntitySnapshot e;
  e.instance_id = id;
  e.name = name;
  e.category = category;
  e.pose.x = x;
  e.pose.y = y;
  e.box.center_z = height / 2.0;
  e.box.length = length;
  e.box.width = width;
  e.box.height = height;
  return e;
}

}  // namespace corsa::test
