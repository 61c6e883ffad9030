// Ground everywhere: a height field of 4 m cells over the road network and 200 m around it
// (larger cells over a network beyond about 8 km x 8 km, so that the field stays within 2^22
// cells),
// kept just under the road surface where there is road (from the lowest road point near each
// vertex) and relaxed smoothly (Laplace) in between and beyond, then a skirt out to 20 km so
// that the horizon is ground, not sky. Class terrain (grass and dirt).

#include <algorithm>
#include <cmath>
#include <limits>

#include "world_build.h"

namespace corsa::sensors::detail {

void build_ground(WorldBuild& w, const xodr::RoadMesh& road) {
  if (road.vertices.empty()) {
    return;
  }
  constexpr double kMargin = 200.0;
  constexpr double kBelow = 0.08;  // m under the lowest road point around a vertex
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const auto& v : road.vertices) {
    x0 = std::min(x0, v.x), y0 = std::min(y0, v.y), x1 = std::max(x1, v.x), y1 = std::max(y1, v.y);
  }
  x0 -= kMargin, y0 -= kMargin, x1 += kMargin, y1 += kMargin;
  // 4 m cells while they number at most 2^22 (about 8 km x 8 km); beyond, cells as large as
  // keep that count, so a long motorway's ground takes no more memory than a city's (2^25 cells
  // of 4 m, roads 40 km apart, took 12.9 GB and 157 s of CPU time in `corsa run --rig`).
  constexpr double kMaxCells = 1 << 22;
  const double area = (x1 - x0) * (y1 - y0);
  const double cell = area / 16.0 <= kMaxCells ? 4.0 : std::sqrt(area / kMaxCells);
  const int nx = static_cast<int>(std::ceil((x1 - x0) / cell)) + 1;
  const int ny = static_cast<int>(std::ceil((y1 - y0) / cell)) + 1;
  const double inf = std::numeric_limits<double>::infinity();
  // Lowest road surface per cell: every road triangle sampled at most 1.5 m apart.
  std::vector<double> cell_min(static_cast<size_t>(nx) * ny, inf);
  auto mark = [&](double x, double y, double z) {
    const int i = std::clamp(static_cast<int>((x - x0) / cell), 0, nx - 1);
    const int j = std::clamp(static_cast<int>((y - y0) / cell), 0, ny - 1);
    double& c = cell_min[static_cast<size_t>(j) * nx + i];
    c = std::min(c, z);
  };
  for (const auto& t : road.triangles) {
    const auto& a = road.vertices[t[0]];
    const auto& b = road.vertices[t[1]];
    const auto& c = road.vertices[t[2]];
    const double longest =
        std::max({std::hypot(b.x - a.x, b.y - a.y), std::hypot(c.x - b.x, c.y - b.y),
                  std::hypot(a.x - c.x, a.y - c.y)});
    const int n = std::max(1, static_cast<int>(std::ceil(longest / 1.5)));
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; i + j <= n; ++j) {
        const double u = static_cast<double>(i) / n;
        const double v = static_cast<double>(j) / n;
        const double s = 1.0 - u - v;
        mark(s * a.x + u * b.x + v * c.x, s * a.y + u * b.y + v * c.y, s * a.z + u * b.z + v * c.z);
      }
    }
  }
  // Vertex heights: below every road cell around them (2 cells each way), free elsewhere.
  std::vector<double> h(static_cast<size_t>(nx) * ny, inf);
  std::vector<char> fixed(h.size(), 0);
  double sum = 0.0;
  size_t count = 0;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      double low = inf;
      for (int dj = -2; dj <= 1; ++dj) {
        for (int di = -2; di <= 1; ++di) {
          const int ci = i + di, cj = j + dj;
          if (ci >= 0 && cj >= 0 && ci < nx && cj < ny) {
            low = std::min(low, cell_min[static_cast<size_t>(cj) * nx + ci]);
          }
        }
      }
      if (low < inf) {
        h[static_cast<size_t>(j) * nx + i] = low - kBelow;
        fixed[static_cast<size_t>(j) * nx + i] = 1;
        sum += low;
        ++count;
      }
    }
  }
  const double mean = count > 0 ? sum / static_cast<double>(count) - kBelow : 0.0;
  for (size_t k = 0; k < h.size(); ++k) {
    if (!fixed[k]) {
      h[k] = mean;
    }
  }
  // Relax the free vertices towards their neighbours' average (Gauss-Seidel, fixed sweep
  // order: the same result every run), never above a neighbouring road-bound vertex.
  for (int iter = 0; iter < 300; ++iter) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        const size_t k = static_cast<size_t>(j) * nx + i;
        if (fixed[k]) {
          continue;
        }
        double s = 0.0;
        int n = 0;
        if (i > 0) s += h[k - 1], ++n;
        if (i + 1 < nx) s += h[k + 1], ++n;
        if (j > 0) s += h[k - nx], ++n;
        if (j + 1 < ny) s += h[k + nx], ++n;
        h[k] = s / n;
      }
    }
  }
  w.ground = GroundField{x0, y0, cell, nx, ny, h};
  StaticMesh ground;
  ground.name = "ground";
  ground.classes = {SemanticClass::kTerrain};
  ground.vertices.reserve(h.size() + 64);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      ground.vertices.push_back({x0 + i * cell, y0 + j * cell, h[static_cast<size_t>(j) * nx + i]});
    }
  }
  // Smooth shading normals from the field's slopes (central differences): with flat normals each
  // 4 m triangle of a slope would take its own shade in the sun (facets on hills and banks).
  ground.normals.reserve(ground.vertices.capacity());
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const auto at = [&](int ii, int jj) {
        return h[static_cast<size_t>(std::clamp(jj, 0, ny - 1)) * nx + std::clamp(ii, 0, nx - 1)];
      };
      const double dx = (at(i + 1, j) - at(i - 1, j)) / (2.0 * cell);
      const double dy = (at(i, j + 1) - at(i, j - 1)) / (2.0 * cell);
      ground.normals.push_back(normalized(Vec3{-dx, -dy, 1.0}));
    }
  }
  for (int j = 0; j + 1 < ny; ++j) {
    for (int i = 0; i + 1 < nx; ++i) {
      const auto a = static_cast<uint32_t>(j * nx + i);
      const auto b = a + 1;
      const auto c = a + static_cast<uint32_t>(nx) + 1;
      const auto d = a + static_cast<uint32_t>(nx);
      ground.triangles.push_back({a, b, c});
      ground.triangles.push_back({a, c, d});
    }
  }
  // Skirt: the border ring joined to a ring 20 km out at the border's mean height.
  std::vector<uint32_t> border;
  for (int i = 0; i < nx - 1; ++i) border.push_back(static_cast<uint32_t>(i));
  for (int j = 0; j < ny - 1; ++j) border.push_back(static_cast<uint32_t>(j * nx + nx - 1));
  for (int i = nx - 1; i > 0; --i) border.push_back(static_cast<uint32_t>((ny - 1) * nx + i));
  for (int j = ny - 1; j > 0; --j) border.push_back(static_cast<uint32_t>(j * nx));
  double edge = 0.0;
  for (uint32_t b : border) edge += ground.vertices[b].z;
  edge /= static_cast<double>(border.size());
  const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
  std::vector<uint32_t> outer;
  for (uint32_t b : border) {
    const Vec3 p = ground.vertices[b];
    const double d = std::hypot(p.x - cx, p.y - cy);
    const double k = 20000.0 / std::max(d, 1.0);
    outer.push_back(static_cast<uint32_t>(ground.vertices.size()));
    ground.vertices.push_back({cx + (p.x - cx) * k, cy + (p.y - cy) * k, edge - 2.0});
    ground.normals.push_back({0.0, 0.0, 1.0});
  }
  for (size_t i = 0; i < border.size(); ++i) {
    const size_t n = (i + 1) % border.size();
    ground.triangles.push_back({border[i], outer[i], outer[n]});
    ground.triangles.push_back({border[i], outer[n], border[n]});
  }
  w.report.ground_triangles = ground.triangles.size();
  w.scene.add_static_mesh(std::move(ground));
}

}  // namespace corsa::sensors::detail
