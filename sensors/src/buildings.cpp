#include "corsa/sensors/buildings.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "corsa/core/random.h"
#include "mesh_builder.h"

namespace corsa::sensors {
namespace {

double signed_area(const std::vector<Vec2>& ring) {
  double a = 0.0;
  for (size_t i = 0; i < ring.size(); ++i) {
    const Vec2& p = ring[i];
    const Vec2& q = ring[(i + 1) % ring.size()];
    a += p.x * q.y - q.x * p.y;
  }
  return 0.5 * a;
}

}  // namespace

StaticMesh extrude_footprint(const Footprint& f) {
  std::vector<Vec2> ring;
  for (const Vec2& p : f.ring) {
    if (ring.empty() || std::hypot(p.x - ring.back().x, p.y - ring.back().y) > 1e-9) {
      ring.push_back(p);
    }
  }
  if (ring.size() > 1 &&
      std::hypot(ring.front().x - ring.back().x, ring.front().y - ring.back().y) <= 1e-9) {
    ring.pop_back();
  }
  if (ring.size() < 3 || !(f.height > 0.0)) {
    throw std::invalid_argument("footprint '" + f.name + "' needs 3 points and a height");
  }
  if (signed_area(ring) < 0.0) {
    std::reverse(ring.begin(), ring.end());
  }
  StaticMesh mesh;
  mesh.name = f.name;
  mesh.classes = {SemanticClass::kBuilding};
  mesh.color = f.color;
  const auto n = static_cast<uint32_t>(ring.size());
  const double top = f.base_z + f.height;
  // Walls: each edge its own quad (4 vertices) so that corners stay sharp.
  for (uint32_t i = 0; i < n; ++i) {
    const Vec2& a = ring[i];
    const Vec2& b = ring[(i + 1) % n];
    const auto base = static_cast<uint32_t>(mesh.vertices.size());
    mesh.vertices.push_back({a.x, a.y, f.base_z});
    mesh.vertices.push_back({b.x, b.y, f.base_z});
    mesh.vertices.push_back({b.x, b.y, top});
    mesh.vertices.push_back({a.x, a.y, top});
    mesh.triangles.push_back({base, base + 1, base + 2});
    mesh.triangles.push_back({base, base + 2, base + 3});
  }
  const auto roof = static_cast<uint32_t>(mesh.vertices.size());
  for (const Vec2& p : ring) {
    mesh.vertices.push_back({p.x, p.y, top});
  }
  const auto roof_triangles = detail::ear_clip(ring);
  if (roof_triangles.empty()) {
    throw std::invalid_argument("footprint is not a simple polygon");
  }
  for (const auto& t : roof_triangles) {
    mesh.triangles.push_back({roof + t[0], roof + t[1], roof + t[2]});
  }
  return mesh;
}

std::vector<Footprint> street_district(double length, double street_half_width, uint64_t seed) {
  RandomStream rng(seed);
  std::vector<Footprint> out;
  static constexpr Rgb8 kFacades[] = {
      {196, 184, 160}, {170, 170, 175}, {150, 120, 100}, {210, 205, 195}, {120, 130, 140}};
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? 1.0 : -1.0;
    double x = rng.uniform(2.0, 8.0);
    int index = 0;
    while (x < length) {
      const double frontage = rng.uniform(12.0, 28.0);
      const double depth = rng.uniform(12.0, 22.0);
      const double setback = street_half_width + rng.uniform(2.0, 5.0);
      const double x1 = std::min(x + frontage, length);
      Footprint f;
      f.name = std::string(side == 0 ? "north_" : "south_") + std::to_string(index++);
      f.height = rng.uniform(9.0, 45.0);
      f.color = kFacades[rng.uniform_int(0, 4)];
      const double y0 = sign * setback;
      const double y1 = sign * (setback + depth);
      if (rng.uniform01() < 0.3 && x1 - x > 14.0) {
        // L shape: the back half narrower.
        const double xm = x + 0.5 * (x1 - x);
        const double ym = sign * (setback + 0.5 * depth);
        f.ring = {{x, y0}, {x1, y0}, {x1, ym}, {xm, ym}, {xm, y1}, {x, y1}};
      } else {
        f.ring = {{x, y0}, {x1, y0}, {x1, y1}, {x, y1}};
      }
      out.push_back(std::move(f));
      x = x1 + rng.uniform(3.0, 9.0);
    }
  }
  return out;
}

}  // namespace corsa::sensors
