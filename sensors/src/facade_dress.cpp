// Facades for building meshes that bring only a colour (a model's nodes, extruded footprints):
// their vertical rectangles become walls of the facade generator (facade.h), the rest of the
// mesh (roofs, walls of other shapes) keeps the flat look it was given.

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <vector>

#include "facade.h"

namespace corsa::sensors::detail {
namespace {

constexpr double kMinWallWidth = 3.0;   // m: narrower walls keep the flat look
constexpr double kMinWallHeight = 2.5;  // m

/// The triangles of a mesh that lie in one vertical plane (facing `normal`, horizontal, unit).
struct WallPlane {
  Vec3 normal;
  double offset = 0.0;  ///< normal . point
  std::vector<size_t> triangles;
  double area = 0.0;
};

/// Vertical triangles grouped by plane (normal to 1e-4, offset to a millimetre), in the order
/// of their first triangle.
std::vector<WallPlane> vertical_planes(const StaticMesh& mesh) {
  std::vector<WallPlane> planes;
  std::map<std::array<int64_t, 3>, size_t> index;  // the plane's rounded normal and offset
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const Vec3 a = mesh.vertices[tri[0]];
    const Vec3 c = cross(mesh.vertices[tri[1]] - a, mesh.vertices[tri[2]] - a);
    const double len = norm(c);
    if (len < 1e-9 || std::fabs(c.z) > 1e-3 * len) {
      continue;
    }
    const double h = std::hypot(c.x, c.y);
    const Vec3 n{c.x / h, c.y / h, 0.0};
    const double offset = n.x * a.x + n.y * a.y;
    const std::array<int64_t, 3> key = {std::llround(n.x * 1e4), std::llround(n.y * 1e4),
                                        std::llround(offset * 1e3)};
    const auto [it, added] = index.try_emplace(key, planes.size());
    if (added) {
      planes.push_back({n, offset, {}, 0.0});
    }
    WallPlane& plane = planes[it->second];
    plane.triangles.push_back(t);
    plane.area += 0.5 * len;
  }
  return planes;
}

/// The plane's triangles as one facade wall when they exactly fill a rectangle large enough.
std::optional<FacadeWall> rectangle_of(const StaticMesh& mesh, const WallPlane& p) {
  const Vec3 along{-p.normal.y, p.normal.x, 0.0};  // the outside on its right
  double s0 = 1e300, s1 = -1e300, z0 = 1e300, z1 = -1e300;
  for (const size_t t : p.triangles) {
    for (const uint32_t v : mesh.triangles[t]) {
      const Vec3 q = mesh.vertices[v];
      const double s = q.x * along.x + q.y * along.y;
      s0 = std::min(s0, s), s1 = std::max(s1, s);
      z0 = std::min(z0, q.z), z1 = std::max(z1, q.z);
    }
  }
  const double width = s1 - s0, height = z1 - z0;
  if (width < kMinWallWidth || height < kMinWallHeight ||
      std::fabs(p.area - width * height) > 1e-3 * width * height) {
    return std::nullopt;
  }
  const Vec3 base{p.normal.x * p.offset + along.x * s0, p.normal.y * p.offset + along.y * s0, z0};
  return FacadeWall{.a = base, .b = base + along * width, .height = height, .street = true};
}

}  // namespace

StaticMesh dress_building(StaticMesh mesh, const Material& rest, uint64_t seed) {
  std::vector<FacadeWall> walls;
  std::vector<char> replaced(mesh.triangles.size(), 0);
  for (const WallPlane& p : vertical_planes(mesh)) {
    if (const auto wall = rectangle_of(mesh, p)) {
      walls.push_back(*wall);
      for (const size_t t : p.triangles) {
        replaced[t] = 1;
      }
    }
  }
  if (walls.empty()) {
    mesh.materials = {rest};
    mesh.color.reset();
    return mesh;
  }
  RandomStream rng(seed);
  FacadeBrief brief;
  brief.wall = rest.base_color;
  brief.floor_h = 0.0;
  brief.ground_h = -1.0;
  brief.seed = static_cast<uint32_t>(seed);
  const FacadeStyle style = draw_facade_style(rng, brief);
  MeshBuilder b;
  b.semantic(SemanticClass::kBuilding);
  for (const FacadeWall& w : walls) {
    add_facade_wall(b, w, style, rng);
  }
  const ArticulatedMesh& facade = b.mesh();
  // The kept triangles use `rest` (palette entry 0); the facade's palette follows.
  StaticMesh out;
  out.name = std::move(mesh.name);
  out.instance_id = mesh.instance_id;
  out.classes = {SemanticClass::kBuilding};
  out.signal_id = std::move(mesh.signal_id);
  out.object = std::move(mesh.object);
  out.vertices = std::move(mesh.vertices);
  out.uvs = mesh.uvs.empty() ? std::vector<std::array<float, 2>>(out.vertices.size(), {0.0f, 0.0f})
                             : std::move(mesh.uvs);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (!replaced[t]) {
      out.triangles.push_back(mesh.triangles[t]);
      out.material_indices.push_back(0);
    }
  }
  const auto first = static_cast<uint32_t>(out.vertices.size());
  out.vertices.insert(out.vertices.end(), facade.vertices.begin(), facade.vertices.end());
  out.uvs.insert(out.uvs.end(), facade.uvs.begin(), facade.uvs.end());
  for (size_t t = 0; t < facade.triangles.size(); ++t) {
    const auto& tri = facade.triangles[t];
    out.triangles.push_back({tri[0] + first, tri[1] + first, tri[2] + first});
    out.material_indices.push_back(static_cast<uint16_t>(facade.material[t] + 1));
  }
  out.materials.push_back(rest);
  out.materials.insert(out.materials.end(), facade.materials.begin(), facade.materials.end());
  return out;
}

}  // namespace corsa::sensors::detail
