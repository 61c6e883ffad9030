// Generated vegetation and the shading normals of generated meshes: round shapes carry unit
// vertex normals that the camera interpolates at Embree's barycentrics, flat faces keep their
// hard edges, and tree crowns are clumps of leaves with a ragged outline and sky between them.

#include <embree3/rtcore.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <set>
#include <vector>

#include "corsa/core/random.h"
#include "corsa/sensors/scene.h"
#include "mesh_builder.h"
#include "scene_data.h"
#include "shading.h"
#include "world_props.h"

using namespace corsa;
using namespace corsa::sensors;
using detail::ArticulatedMesh;
using detail::MeshBuilder;

namespace {

bool is_zero(Vec3 n) { return n.x == 0.0 && n.y == 0.0 && n.z == 0.0; }

Vec3 face_normal(const ArticulatedMesh& m, const std::array<uint32_t, 3>& t) {
  return normalized(
      cross(m.vertices[t[1]] - m.vertices[t[0]], m.vertices[t[2]] - m.vertices[t[0]]));
}

/// Every shading normal is unit or zero (a flat face's), and a smooth triangle's vertex normals
/// lie on its outer side (within 90 degrees of its face normal): smooth, not flipped.
void check_normals(const ArticulatedMesh& m) {
  REQUIRE(m.normals.size() == m.vertices.size());
  for (const Vec3& n : m.normals) {
    if (!is_zero(n)) {
      REQUIRE(std::fabs(norm(n) - 1.0) < 1e-9);
    }
  }
  size_t outward = 0, smooth = 0;
  for (const auto& t : m.triangles) {
    if (is_zero(m.normals[t[0]]) || is_zero(m.normals[t[1]]) || is_zero(m.normals[t[2]])) {
      continue;
    }
    const Vec3 f = face_normal(m, t);
    for (const uint32_t i : t) {
      ++smooth;
      outward += dot(m.normals[i], f) > 0.0 ? 1 : 0;
    }
  }
  REQUIRE(smooth > 0);
  // Displaced blobs fold a few thin triangles over; nearly all agree with their faces.
  CHECK(static_cast<double>(outward) / static_cast<double>(smooth) > 0.97);
}

/// Rays along +y through a grid over the x-z plane (`step` metres), against a scene holding
/// only `mesh`: the hit mask, row by row from the bottom, and whether every hit is vegetation.
struct Silhouette {
  int nx = 0, nz = 0;
  std::vector<uint8_t> hit;
  bool all_vegetation = true;
  size_t hits() const { return static_cast<size_t>(std::count(hit.begin(), hit.end(), 1)); }
  bool at(int i, int k) const { return hit[static_cast<size_t>(k) * nx + i] != 0; }
};

Silhouette silhouette(const ArticulatedMesh& mesh, double half_width, double height, double step) {
  Scene scene;
  scene.add_static_mesh(detail::to_static_mesh(mesh, Rigid{}, "tree"));
  scene.commit();
  Silhouette s;
  s.nx = static_cast<int>(2.0 * half_width / step);
  s.nz = static_cast<int>(height / step);
  s.hit.assign(static_cast<size_t>(s.nx) * s.nz, 0);
  for (int k = 0; k < s.nz; ++k) {
    for (int i = 0; i < s.nx; ++i) {
      const Vec3 o{-half_width + (i + 0.5) * step, -30.0, (k + 0.5) * step};
      const auto h = scene.intersect(o, {0.0, 1.0, 0.0}, 60.0);
      if (h) {
        s.hit[static_cast<size_t>(k) * s.nx + i] = 1;
        s.all_vegetation = s.all_vegetation && h->semantic == SemanticClass::kVegetation;
      }
    }
  }
  return s;
}

/// Misses with hits on both sides along their row and their column: sky seen through the crown.
size_t enclosed_gaps(const Silhouette& s) {
  size_t gaps = 0;
  for (int k = 0; k < s.nz; ++k) {
    for (int i = 0; i < s.nx; ++i) {
      if (s.at(i, k)) {
        continue;
      }
      bool left = false, right = false, below = false, above = false;
      for (int j = 0; j < i && !left; ++j) left = s.at(j, k);
      for (int j = i + 1; j < s.nx && !right; ++j) right = s.at(j, k);
      for (int j = 0; j < k && !below; ++j) below = s.at(i, j);
      for (int j = k + 1; j < s.nz && !above; ++j) above = s.at(i, j);
      gaps += left && right && below && above ? 1 : 0;
    }
  }
  return gaps;
}

double turn(Vec2 o, Vec2 a, Vec2 b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

/// The area of the convex hull of the hit cells' corners (cells squared), by the monotone chain.
double hull_area(const Silhouette& s) {
  std::vector<Vec2> p;
  for (int k = 0; k < s.nz; ++k) {
    for (int i = 0; i < s.nx; ++i) {
      if (s.at(i, k)) {
        for (int c = 0; c < 4; ++c) {
          p.push_back({static_cast<double>(i + (c & 1)), static_cast<double>(k + (c >> 1))});
        }
      }
    }
  }
  std::sort(p.begin(), p.end(),
            [](Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  std::vector<Vec2> h(2 * p.size());
  size_t n = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (n >= 2 && turn(h[n - 2], h[n - 1], p[i]) <= 0.0) --n;
    h[n++] = p[i];
  }
  for (size_t i = p.size() - 1, lower = n + 1; i-- > 0;) {
    while (n >= lower && turn(h[n - 2], h[n - 1], p[i]) <= 0.0) --n;
    h[n++] = p[i];
  }
  double area = 0.0;
  for (size_t i = 0; i + 1 < n; ++i) {
    area += h[i].x * h[i + 1].y - h[i + 1].x * h[i].y;
  }
  return 0.5 * std::fabs(area);
}

/// The crown's part of a silhouette: rows from `z0` metres up.
Silhouette crown_rows(const Silhouette& s, double z0, double step) {
  Silhouette c = s;
  const int k0 = static_cast<int>(z0 / step);
  c.nz = s.nz - k0;
  c.hit.assign(s.hit.begin() + static_cast<std::ptrdiff_t>(k0) * s.nx, s.hit.end());
  return c;
}

}  // namespace

TEST_CASE("tubes and ellipsoids carry unit normals, boxes and caps none (hard edges)",
          "[sensors][vegetation][normals]") {
  MeshBuilder b;
  b.tube({0, 0, 0}, {0, 0, 2}, 0.3, 0.3, 8, true);
  const size_t after_tube = b.mesh().vertices.size();
  b.box({1, 1, 0}, {2, 2, 1});
  const size_t after_box = b.mesh().vertices.size();
  b.ellipsoid({5, 0, 1}, {1, 1, 1}, Mat3{}, 12, 8);
  const ArticulatedMesh m = b.take();
  check_normals(m);
  size_t side = 0, flat = 0;
  for (size_t i = 0; i < after_tube; ++i) {
    if (is_zero(m.normals[i])) {
      ++flat;  // the caps' own rims and centres
      continue;
    }
    ++side;
    // A straight tube's side normal is radial: horizontal, along the vertex's offset.
    const Vec3 radial = normalized(Vec3{m.vertices[i].x, m.vertices[i].y, 0.0});
    CHECK(dot(m.normals[i], radial) == Approx(1.0).margin(1e-9));
  }
  CHECK(side == 16);
  CHECK(flat == 18);
  for (size_t i = after_tube; i < after_box; ++i) {
    CHECK(is_zero(m.normals[i]));
  }
  for (size_t i = after_box; i < m.vertices.size(); ++i) {
    const Vec3 radial = normalized(m.vertices[i] - Vec3{5, 0, 1});
    CHECK(dot(m.normals[i], radial) == Approx(1.0).margin(1e-9));
  }
  // Placed in the map, the normals turn with the mesh; flat vertices stay zero.
  const Rigid pose = rigid_from_pose(10.0, 0.0, 0.0, 0.5 * std::numbers::pi, 0.0, 0.0);
  const StaticMesh placed = detail::to_static_mesh(m, pose, "parts");
  REQUIRE(placed.normals.size() == m.vertices.size());
  for (size_t i = 0; i < m.vertices.size(); ++i) {
    const Vec3 expected = pose.rotation * m.normals[i];
    CHECK(norm(placed.normals[i] - expected) < 1e-12);
  }
}

TEST_CASE("a static hit shades with its vertex normals interpolated at Embree's barycentrics",
          "[sensors][vegetation][normals]") {
  // One triangle in the plane z = 0 with three different vertex normals, and a second one whose
  // third vertex has none (a flat face).
  StaticMesh mesh;
  mesh.name = "normals";
  mesh.vertices = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {10, 0, 0}, {14, 0, 0}, {10, 4, 0}};
  mesh.triangles = {{0, 1, 2}, {3, 4, 5}};
  mesh.classes = {SemanticClass::kStatic};
  const Vec3 na = normalized(Vec3{-0.3, -0.2, 1.0});
  const Vec3 nb = normalized(Vec3{0.5, 0.0, 1.0});
  const Vec3 nc = normalized(Vec3{0.0, 0.6, 1.0});
  mesh.normals = {na, nb, nc, na, nb, Vec3{}};
  Scene scene;
  scene.add_static_mesh(mesh);
  scene.commit();
  const detail::SceneData& d = scene.data();
  auto trace = [&](Vec3 origin, Vec3 dir) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray.org_x = static_cast<float>(origin.x);
    rh.ray.org_y = static_cast<float>(origin.y);
    rh.ray.org_z = static_cast<float>(origin.z);
    rh.ray.dir_x = static_cast<float>(dir.x);
    rh.ray.dir_y = static_cast<float>(dir.y);
    rh.ray.dir_z = static_cast<float>(dir.z);
    rh.ray.tfar = 100.0f;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(d.top, &context, &rh);
    REQUIRE(rh.hit.geomID != RTC_INVALID_GEOMETRY_ID);
    detail::SurfaceHit h;
    h.inst_id = rh.hit.instID[0];
    h.geom_id = rh.hit.geomID;
    h.prim_id = rh.hit.primID;
    h.u = rh.hit.u;
    h.v = rh.hit.v;
    h.view_dir = normalized(dir);
    h.position = origin + h.view_dir * static_cast<double>(rh.ray.tfar);
    h.normal = {0.0, 0.0, 1.0};
    return h;
  };
  for (const Vec2 p : {Vec2{1.0, 1.0}, Vec2{2.5, 0.5}, Vec2{0.3, 3.1}, Vec2{0.2, 0.2}}) {
    const detail::SurfaceHit h = trace({p.x, p.y, 5.0}, {0.0, 0.0, -1.0});
    // The barycentric weights of the point, from its coordinates (the triangle is a right
    // angle of side 4 at the origin).
    const double wb = p.x / 4.0, wc = p.y / 4.0, wa = 1.0 - wb - wc;
    const Vec3 expected = normalized(na * wa + nb * wb + nc * wc);
    const Vec3 n = detail::static_shading_normal(d.static_geometries[h.geom_id], h);
    CHECK(std::fabs(norm(n) - 1.0) < 1e-9);
    CHECK(norm(n - expected) < 1e-5);
  }
  // The flat face shades with its own normal.
  const detail::SurfaceHit flat = trace({11.0, 1.0, 5.0}, {0.0, 0.0, -1.0});
  const Vec3 n = detail::static_shading_normal(d.static_geometries[flat.geom_id], flat);
  CHECK(norm(n - Vec3{0.0, 0.0, 1.0}) < 1e-12);
  // Seen at a grazing angle from the side its normals lean away from, the interpolated
  // normal is tilted back to face the eye.
  const detail::SurfaceHit grazing = trace({-20.0, 0.5, 1.0}, normalized(Vec3{20.5, 0.0, -1.0}));
  const Vec3 g = detail::static_shading_normal(d.static_geometries[grazing.geom_id], grazing);
  CHECK(-dot(g, grazing.view_dir) > 0.0);
  CHECK(std::fabs(norm(g) - 1.0) < 1e-9);
}

TEST_CASE("a broadleaved tree's crown is leaf clumps: ragged outline, sky between, round clumps",
          "[sensors][vegetation]") {
  auto rng = RandomStream::derive(17, "tree kerb 3");
  const ArticulatedMesh tree = detail::make_tree(rng, 8.0, false);
  check_normals(tree);
  // Every triangle is vegetation; its foliage comes in several greens (shaded inside, body,
  // sunlit top) besides the bark.
  for (const SemanticClass c : tree.classes) {
    REQUIRE(c == SemanticClass::kVegetation);
  }
  std::set<uint16_t> used(tree.material.begin(), tree.material.end());
  CHECK(used.size() >= 4);
  const double step = 0.05;
  const Silhouette side = silhouette(tree, 5.0, 8.5, step);
  REQUIRE(side.hits() > 1000);
  CHECK(side.all_vegetation);
  // The crown from the side: sky seen through it, and an outline far from convex (the notches
  // between its masses and clumps). One closed lumpy solid has neither.
  const Silhouette crown = crown_rows(side, 4.0, step);
  const double filled = static_cast<double>(crown.hits());
  CHECK(static_cast<double>(enclosed_gaps(crown)) > 0.02 * filled);
  CHECK(filled / hull_area(crown) < 0.85);
  // The trunk shows below the crown: a narrow column of hits at the foot.
  const Silhouette foot = silhouette(tree, 5.0, 1.0, step);
  CHECK(foot.hits() > 0);
  CHECK(static_cast<double>(foot.hits()) < 0.2 * foot.nx * foot.nz);
}

TEST_CASE("trees and bushes are the same for a seed and differ between seeds",
          "[sensors][vegetation]") {
  auto tree = [](uint64_t seed, const char* name) {
    auto rng = RandomStream::derive(seed, name);
    return detail::make_tree(rng, 9.0);
  };
  const ArticulatedMesh a = tree(5, "tree 1");
  const ArticulatedMesh b = tree(5, "tree 1");
  REQUIRE(a.vertices.size() == b.vertices.size());
  for (size_t i = 0; i < a.vertices.size(); ++i) {
    REQUIRE(a.vertices[i].x == b.vertices[i].x);
    REQUIRE(a.vertices[i].y == b.vertices[i].y);
    REQUIRE(a.vertices[i].z == b.vertices[i].z);
    REQUIRE(norm(a.normals[i] - b.normals[i]) == 0.0);
  }
  CHECK(a.triangles == b.triangles);
  CHECK(a.material == b.material);
  const ArticulatedMesh c = tree(5, "tree 2");
  CHECK((c.vertices.size() != a.vertices.size() || c.vertices[40].x != a.vertices[40].x));

  auto r1 = RandomStream::derive(8, "bush"), r2 = RandomStream::derive(8, "bush"),
       r3 = RandomStream::derive(9, "bush");
  const ArticulatedMesh p = detail::make_bush(r1, 1.5);
  const ArticulatedMesh q = detail::make_bush(r2, 1.5);
  const ArticulatedMesh s = detail::make_bush(r3, 1.5);
  check_normals(p);
  REQUIRE(p.vertices.size() == q.vertices.size());
  CHECK(p.vertices.back().x == q.vertices.back().x);
  CHECK((s.vertices.size() != p.vertices.size() || s.vertices.back().x != p.vertices.back().x));
}

TEST_CASE("a conifer's tiers have ragged rims of needle sprays", "[sensors][vegetation]") {
  // Draw until a conifer comes (one in four trees off the kerb): its trunk runs up through
  // the tiers (the first tube's top, vertex 1, at 0.9 of the height), a broadleaved tree's
  // forks below the middle.
  ArticulatedMesh conifer;
  for (uint64_t seed = 0; seed < 40 && conifer.vertices.empty(); ++seed) {
    auto rng = RandomStream::derive(seed, "conifer");
    ArticulatedMesh t = detail::make_tree(rng, 10.0, true);
    if (t.vertices[1].z > 8.0) {
      conifer = std::move(t);
    }
  }
  REQUIRE(!conifer.vertices.empty());
  check_normals(conifer);
  const double step = 0.05;
  const Silhouette side = silhouette(conifer, 3.0, 10.0, step);
  const Silhouette crown = crown_rows(side, 2.0, step);
  // Stacked smooth cones give about 0.86.
  CHECK(static_cast<double>(crown.hits()) / hull_area(crown) < 0.82);
}
