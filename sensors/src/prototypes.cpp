// Default entity shapes: unions of boxes inside the unit box [-0.5, 0.5]^3 (x forward, y left,
// z up), scaled to each entity's bounding box by its instance transform. Shapes only need to be
// plausible silhouettes for the cameras and LiDAR; labels use the bounding box itself.

#include "scene_data.h"

namespace corsa::sensors::detail {
namespace {

void add_box(StaticMesh& mesh, Vec3 lo, Vec3 hi) {
  const auto base = static_cast<uint32_t>(mesh.vertices.size());
  for (int i = 0; i < 8; ++i) {
    mesh.vertices.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  }
  // Counter-clockwise seen from outside.
  const uint32_t faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6},   // -z, +z
                                 {0, 1, 4}, {1, 5, 4}, {2, 6, 3}, {3, 6, 7},   // -y, +y
                                 {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};  // -x, +x
  for (const auto& f : faces) {
    mesh.triangles.push_back({base + f[0], base + f[1], base + f[2]});
  }
}

}  // namespace

StaticMesh default_prototype(engine::EntityCategory category) {
  using engine::EntityCategory;
  StaticMesh mesh;
  mesh.name = "prototype";
  mesh.classes = {SemanticClass::kObstacle};
  switch (category) {
    case EntityCategory::kCar:
    case EntityCategory::kVan:
    case EntityCategory::kTruck:
    case EntityCategory::kBus:
      // Body over the full box up to 55% of the height, cabin above its middle part.
      add_box(mesh, {-0.5, -0.5, -0.5}, {0.5, 0.5, 0.05});
      add_box(mesh, {-0.32, -0.45, 0.05}, {0.22, 0.45, 0.5});
      break;
    case EntityCategory::kPedestrian:
    case EntityCategory::kWheelchair:
      // Legs and torso, then a narrower head.
      add_box(mesh, {-0.5, -0.5, -0.5}, {0.5, 0.5, 0.32});
      add_box(mesh, {-0.25, -0.25, 0.32}, {0.25, 0.25, 0.5});
      break;
    case EntityCategory::kMotorbike:
    case EntityCategory::kBicycle:
      // Frame low and long, rider upright over the middle.
      add_box(mesh, {-0.5, -0.2, -0.5}, {0.5, 0.2, -0.05});
      add_box(mesh, {-0.25, -0.5, -0.05}, {0.15, 0.5, 0.5});
      break;
    default:
      add_box(mesh, {-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5});
      break;
  }
  return mesh;
}

}  // namespace corsa::sensors::detail
