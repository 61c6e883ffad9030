#include "mesh_builder.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace corsa::sensors::detail {

MeshBuilder& MeshBuilder::material(const Material& m) {
  for (size_t i = 0; i < mesh_.materials.size(); ++i) {
    if (mesh_.materials[i].name == m.name) {
      material_ = static_cast<uint16_t>(i);
      has_material_ = true;
      return *this;
    }
  }
  mesh_.materials.push_back(m);
  material_ = static_cast<uint16_t>(mesh_.materials.size() - 1);
  has_material_ = true;
  return *this;
}

uint32_t MeshBuilder::vertex(Vec3 p, float u, float v) {
  mesh_.vertices.push_back(xf_.apply(p));
  mesh_.bone.push_back(bone_);
  mesh_.uvs.push_back({u, v});
  if (!mesh_.normals.empty()) {
    mesh_.normals.push_back({});  // flat until smooth_normals says otherwise
  }
  return static_cast<uint32_t>(mesh_.vertices.size() - 1);
}

void MeshBuilder::smooth_normals(size_t first_vertex, size_t first_triangle) {
  mesh_.normals.resize(mesh_.vertices.size());
  for (size_t i = first_vertex; i < mesh_.vertices.size(); ++i) {
    mesh_.normals[i] = {};
  }
  for (size_t k = first_triangle; k < mesh_.triangles.size(); ++k) {
    const auto& t = mesh_.triangles[k];
    // The cross product's length is twice the area: the weight comes with it.
    const Vec3 n = cross(mesh_.vertices[t[1]] - mesh_.vertices[t[0]],
                         mesh_.vertices[t[2]] - mesh_.vertices[t[0]]);
    for (const uint32_t v : t) {
      if (v >= first_vertex) {
        mesh_.normals[v] = mesh_.normals[v] + n;
      }
    }
  }
  for (size_t i = first_vertex; i < mesh_.vertices.size(); ++i) {
    mesh_.normals[i] = normalized(mesh_.normals[i]);
  }
}

void MeshBuilder::set_material(size_t triangle, const Material& m) {
  const uint16_t keep = material_;
  const bool had = has_material_;
  material(m);
  mesh_.material[triangle] = material_;
  material_ = keep;
  has_material_ = had;
}

void MeshBuilder::triangle(uint32_t a, uint32_t b, uint32_t c) {
  if (!has_material_) {
    material(materials::plain("default", {0.2, 0.2, 0.2}));
  }
  mesh_.triangles.push_back({a, b, c});
  mesh_.material.push_back(material_);
  mesh_.classes.push_back(class_);
}

void MeshBuilder::quad(uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
  triangle(a, b, c);
  triangle(a, c, d);
}

void MeshBuilder::box(Vec3 lo, Vec3 hi) {
  uint32_t v[8];
  for (int i = 0; i < 8; ++i) {
    v[i] = vertex({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  }
  // Counter-clockwise seen from outside.
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    quad(v[f[0]], v[f[1]], v[f[2]], v[f[3]]);
  }
}

void perpendicular_basis(Vec3 axis, Vec3& e1, Vec3& e2) {
  const Vec3 helper = std::fabs(axis.z) < 0.9 ? Vec3{0.0, 0.0, 1.0} : Vec3{1.0, 0.0, 0.0};
  e1 = normalized(cross(helper, axis));
  e2 = cross(axis, e1);
}

void MeshBuilder::tube(Vec3 a, Vec3 b, double r0, double r1, int segments, bool caps) {
  const Vec3 axis = normalized(b - a);
  Vec3 e1, e2;
  perpendicular_basis(axis, e1, e2);
  std::vector<std::vector<Vec3>> rings(2);
  for (int i = 0; i < segments; ++i) {
    const double t = 2.0 * std::numbers::pi * i / segments;
    const Vec3 dir = e1 * std::cos(t) + e2 * std::sin(t);
    rings[0].push_back(a + dir * r0);
    rings[1].push_back(b + dir * r1);
  }
  loft(rings, caps);
}

void MeshBuilder::ellipsoid(Vec3 centre, Vec3 radii, const Mat3& axes, int slices, int stacks) {
  const uint32_t bottom = vertex(centre + axes * Vec3{0.0, 0.0, -radii.z});
  const uint32_t top = vertex(centre + axes * Vec3{0.0, 0.0, radii.z});
  std::vector<uint32_t> grid;
  for (int j = 1; j < stacks; ++j) {
    const double phi = std::numbers::pi * j / stacks - 0.5 * std::numbers::pi;
    for (int i = 0; i < slices; ++i) {
      const double theta = 2.0 * std::numbers::pi * i / slices;
      const Vec3 local{radii.x * std::cos(phi) * std::cos(theta),
                       radii.y * std::cos(phi) * std::sin(theta), radii.z * std::sin(phi)};
      grid.push_back(vertex(centre + axes * local));
    }
  }
  auto at = [&](int j, int i) { return grid[static_cast<size_t>(j) * slices + (i % slices)]; };
  for (int i = 0; i < slices; ++i) {
    triangle(bottom, at(0, i + 1), at(0, i));
    triangle(top, at(stacks - 2, i), at(stacks - 2, i + 1));
  }
  for (int j = 0; j + 1 < stacks - 1; ++j) {
    for (int i = 0; i < slices; ++i) {
      quad(at(j, i), at(j, i + 1), at(j + 1, i + 1), at(j + 1, i));
    }
  }
}

void MeshBuilder::loft(const std::vector<std::vector<Vec3>>& rings, bool cap_ends) {
  if (rings.size() < 2 || rings.front().size() < 3) {
    return;
  }
  const size_t n = rings.front().size();
  std::vector<uint32_t> ids;
  ids.reserve(rings.size() * n);
  for (const auto& ring : rings) {
    for (const Vec3& p : ring) {
      ids.push_back(vertex(p));
    }
  }
  for (size_t r = 0; r + 1 < rings.size(); ++r) {
    for (size_t i = 0; i < n; ++i) {
      const size_t j = (i + 1) % n;
      quad(ids[r * n + i], ids[r * n + j], ids[(r + 1) * n + j], ids[(r + 1) * n + i]);
    }
  }
  if (cap_ends) {
    for (int end = 0; end < 2; ++end) {
      const auto& ring = end == 0 ? rings.front() : rings.back();
      Vec3 c;
      for (const Vec3& p : ring) {
        c = c + p;
      }
      const uint32_t centre = vertex(c * (1.0 / static_cast<double>(n)));
      const size_t base = end == 0 ? 0 : (rings.size() - 1) * n;
      for (size_t i = 0; i < n; ++i) {
        const uint32_t a = ids[base + i];
        const uint32_t b = ids[base + (i + 1) % n];
        if (end == 0) {
          triangle(centre, b, a);
        } else {
          triangle(centre, a, b);
        }
      }
    }
  }
}

void MeshBuilder::polygon(const std::vector<Vec3>& points,
                          const std::vector<std::array<float, 2>>& uvs) {
  if (points.size() < 3) {
    return;
  }
  std::vector<uint32_t> ids;
  for (size_t i = 0; i < points.size(); ++i) {
    const auto uv = i < uvs.size() ? uvs[i] : std::array<float, 2>{0.0f, 0.0f};
    ids.push_back(vertex(points[i], uv[0], uv[1]));
  }
  for (size_t i = 1; i + 1 < ids.size(); ++i) {
    triangle(ids[0], ids[i], ids[i + 1]);
  }
}

namespace {

double ring_turn(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

bool in_ear(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  return ring_turn(a, b, p) >= 0.0 && ring_turn(b, c, p) >= 0.0 && ring_turn(c, a, p) >= 0.0;
}

}  // namespace

std::vector<std::array<uint32_t, 3>> ear_clip(const std::vector<Vec2>& ring) {
  if (ring.size() < 3) {
    return {};
  }
  std::vector<uint32_t> remaining(ring.size());
  for (uint32_t i = 0; i < ring.size(); ++i) {
    remaining[i] = i;
  }
  std::vector<std::array<uint32_t, 3>> triangles;
  while (remaining.size() > 3) {
    const size_t n = remaining.size();
    bool clipped = false;
    for (size_t i = 0; i < n; ++i) {
      const uint32_t a = remaining[(i + n - 1) % n], b = remaining[i], c = remaining[(i + 1) % n];
      if (ring_turn(ring[a], ring[b], ring[c]) <= 0.0) {
        continue;  // reflex corner
      }
      bool ear = true;
      for (uint32_t k : remaining) {
        if (k != a && k != b && k != c && in_ear(ring[k], ring[a], ring[b], ring[c])) {
          ear = false;
          break;
        }
      }
      if (ear) {
        triangles.push_back({a, b, c});
        remaining.erase(remaining.begin() + static_cast<std::ptrdiff_t>(i));
        clipped = true;
        break;
      }
    }
    if (!clipped) {
      return {};  // every ear fails: the ring crosses itself
    }
  }
  triangles.push_back({remaining[0], remaining[1], remaining[2]});
  return triangles;
}

bool MeshBuilder::filled_ring(const std::vector<Vec3>& ring) {
  std::vector<Vec3> points;
  for (const Vec3& p : ring) {
    if (points.empty() || std::hypot(p.x - points.back().x, p.y - points.back().y) > 1e-6) {
      points.push_back(p);
    }
  }
  while (points.size() > 1 && std::hypot(points.front().x - points.back().x,
                                         points.front().y - points.back().y) <= 1e-6) {
    points.pop_back();  // a closed outline repeats its first corner
  }
  double area = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    const Vec3& q = points[(i + 1) % points.size()];
    area += p.x * q.y - q.x * p.y;
  }
  if (area < 0.0) {
    std::reverse(points.begin(), points.end());
  }
  std::vector<Vec2> flat;
  flat.reserve(points.size());
  for (const Vec3& p : points) {
    flat.push_back({p.x, p.y});
  }
  const auto triangles = ear_clip(flat);
  if (triangles.empty()) {
    return false;
  }
  std::vector<uint32_t> ids;
  for (const Vec3& p : points) {
    ids.push_back(vertex(p));
  }
  for (const auto& t : triangles) {
    triangle(ids[t[0]], ids[t[1]], ids[t[2]]);
  }
  return true;
}

StaticMesh to_static_mesh(const ArticulatedMesh& mesh, const Rigid& placement, std::string name) {
  StaticMesh out;
  out.name = std::move(name);
  out.vertices.reserve(mesh.vertices.size());
  for (const Vec3& v : mesh.vertices) {
    out.vertices.push_back(placement.apply(v));
  }
  out.triangles = mesh.triangles;
  out.classes = mesh.classes;
  out.materials = mesh.materials;
  out.material_indices = mesh.material;
  bool any_uv = false;
  for (const auto& uv : mesh.uvs) {
    any_uv = any_uv || uv[0] != 0.0f || uv[1] != 0.0f;
  }
  if (any_uv) {
    out.uvs = mesh.uvs;
  }
  if (mesh.normals.size() == mesh.vertices.size()) {
    out.normals.reserve(mesh.normals.size());
    for (const Vec3& n : mesh.normals) {
      out.normals.push_back(placement.rotation * n);
    }
  }
  return out;
}

}  // namespace corsa::sensors::detail
