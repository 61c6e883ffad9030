#include "plant_parts.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "noise_tile.h"
#include "scalar_math.h"

namespace corsa::sensors::detail {

namespace {

/// Share of the mass's outward direction added to a clump's own (unit) normals: under 1, so
/// that the sum stays on the outer side of every face of the clump.
constexpr double kBend = 0.6;

}  // namespace

Material bark() {
  Material m = materials::plain("bark", linear_rgb(82, 64, 48), 0.95);
  m.pattern = Pattern::kBark;
  return m;
}

Leaves draw_leaves(RandomStream& rng, bool needles) {
  static constexpr Rgb8 kLight[4] = {{76, 104, 44}, {90, 112, 50}, {66, 96, 48}, {100, 110, 56}};
  static constexpr Rgb8 kDark[4] = {{34, 54, 24}, {42, 60, 26}, {30, 48, 28}, {48, 56, 30}};
  static constexpr Rgb8 kNeedle[2] = {{44, 70, 46}, {54, 74, 42}};
  static constexpr Rgb8 kNeedleDark[2] = {{18, 36, 26}, {24, 40, 22}};
  const auto i = static_cast<size_t>(rng.uniform_int(0, needles ? 1 : 3));
  const Rgb8 light = needles ? kNeedle[i] : kLight[i];
  const Rgb8 dark = needles ? kNeedleDark[i] : kDark[i];
  const std::string name = (needles ? "needles " : "foliage ") + std::to_string(i);
  Leaves l;
  l.lit = materials::plain(name, linear_rgb(light.r, light.g, light.b), 0.8);
  l.lit.pattern = Pattern::kFoliage;
  l.lit.secondary = linear_rgb(dark.r, dark.g, dark.b);
  // Leaves inside a crown and on its underside are older, darker and seen by their backs.
  l.shade = l.lit;
  l.shade.name = name + " shade";
  l.shade.base_color = l.lit.base_color * 0.62;
  l.shade.secondary = l.lit.secondary * 0.7;
  return l;
}

void branch(MeshBuilder& b, std::span<const Vec3> points, double r0, double r1, int segments) {
  const size_t n = points.size();
  if (n < 2) {
    return;
  }
  std::vector<std::vector<Vec3>> rings(n);
  Vec3 e1, e2;
  perpendicular_basis(normalized(points[1] - points[0]), e1, e2);
  for (size_t i = 0; i < n; ++i) {
    // The ring's frame carried along the curve (parallel transport): no twist where it bends.
    const Vec3 t = normalized(points[std::min(i + 1, n - 1)] - points[i == 0 ? 0 : i - 1]);
    e1 = normalized(e1 - t * dot(e1, t));
    e2 = cross(t, e1);
    const double r = r0 + (r1 - r0) * static_cast<double>(i) / static_cast<double>(n - 1);
    for (int k = 0; k < segments; ++k) {
      const double a = 2.0 * kPi * k / segments;
      rings[i].push_back(points[i] + (e1 * std::cos(a) + e2 * std::sin(a)) * r);
    }
  }
  const size_t first_vertex = b.mesh().vertices.size();
  const size_t first_triangle = b.triangle_count();
  b.loft(rings, false);
  b.smooth_normals(first_vertex, first_triangle);
}

void clump(MeshBuilder& b, Vec3 c, Vec3 r, const Mat3& axes, uint64_t seed, const Mass& mass,
           int slices, int stacks) {
  const size_t first_vertex = b.mesh().vertices.size();
  const size_t first_triangle = b.triangle_count();
  b.ellipsoid(c, r, axes, slices, stacks);
  // Each vertex pushed in or out by a smooth random amount read from the 4-unit noise tile at
  // the clump's own scale (about two tiles across whatever its size) and at a place of the tile
  // chosen by the seed: no two clumps alike.
  ArticulatedMesh& mesh = b.edit();
  const double scale = 2.5 / std::max({r.x, r.y, r.z});
  const double ox = 4.0 * static_cast<double>((seed >> 2) & 255u) / 256.0;
  const double oy = 4.0 * static_cast<double>((seed >> 10) & 255u) / 256.0;
  for (size_t i = first_vertex; i < mesh.vertices.size(); ++i) {
    const Vec3 d = mesh.vertices[i] - c;
    const double bump = noise(static_cast<int>(seed % 4), (d.x * 3.0 + d.z * 2.0) * scale + ox,
                              (d.y * 3.0 - d.z) * scale + oy, 4.0, 0.0, false);
    mesh.vertices[i] = c + d * (0.7 + 0.6 * bump);
  }
  b.smooth_normals(first_vertex, first_triangle);
  for (size_t i = first_vertex; i < mesh.vertices.size(); ++i) {
    // The gradient of the mass's ellipsoid: its outward direction there.
    const Vec3 d = mesh.vertices[i] - mass.centre;
    const Vec3 out =
        normalized(Vec3{d.x / (mass.radii.x * mass.radii.x), d.y / (mass.radii.y * mass.radii.y),
                        d.z / (mass.radii.z * mass.radii.z)});
    mesh.normals[i] = normalized(mesh.normals[i] + out * kBend);
  }
}

Vec3 on_sphere(RandomStream& rng) {
  const double z = rng.uniform(-1.0, 1.0);
  const double a = rng.uniform(0.0, 2.0 * kPi);
  const double rho = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {rho * std::cos(a), rho * std::sin(a), z};
}

bool in_clearance(Vec3 p, double margin, std::span<const Clearance> clear) {
  return std::any_of(clear.begin(), clear.end(),
                     [&](const Clearance& c) { return norm(p - c.centre) < c.radius + margin; });
}

int fill_lobe(MeshBuilder& b, RandomStream& rng, const Lobe& lobe, const Mass& mass,
              const LobeStyle& style, const Leaves& leaves, std::span<const Clearance> clear) {
  const double rm = std::cbrt(lobe.radii.x * lobe.radii.y * lobe.radii.z);
  const int count =
      std::clamp(static_cast<int>(style.density * 4.0 * rm * rm / (style.clump * style.clump)), 3,
                 style.max_clumps);
  const Vec3 out = normalized(lobe.centre - mass.centre);
  int placed = 0;
  for (int k = 0; k < count; ++k) {
    Vec3 d = on_sphere(rng);
    // Mirrored to the outer side six times in ten when it faces the middle of the mass, and to
    // the upper side half the time when it points down.
    const double inward = dot(d, out);
    if (inward < -0.3 && rng.uniform01() < 0.6) {
      d = d - out * (2.0 * inward);
    }
    if (d.z < -0.4 && rng.uniform01() < 0.5) {
      d.z = -d.z;
    }
    const double depth = rng.uniform(0.3, 1.0);
    const double size = style.clump * rng.uniform(0.6, 1.4);
    const Vec3 r{size * rng.uniform(0.75, 1.3), size * rng.uniform(0.75, 1.3),
                 size * style.flat * rng.uniform(0.8, 1.2)};
    const uint64_t seed = rng.next_u64();
    const bool tuft = rng.uniform01() < 0.5 && depth > 0.8;
    const Vec3 at{lobe.centre.x + d.x * lobe.radii.x * depth,
                  lobe.centre.y + d.y * lobe.radii.y * depth,
                  lobe.centre.z + d.z * lobe.radii.z * depth};
    if (in_clearance(at, 1.6 * size, clear)) {
      continue;
    }
    // Inside the lobe the clumps are seen only through gaps, in the shade: coarser ones do.
    const bool inner = depth < 0.65;
    b.material(d.z < -0.3 || inner ? leaves.shade : leaves.lit);
    clump(b, at, r, Mat3{}, seed, mass, inner ? 6 : 7, inner ? 4 : 5);
    ++placed;
    if (tuft) {
      // A spray of leaves standing out of the clump: the outline's small notches and points.
      clump(b, at + d * (0.95 * size), r * 0.4, Mat3{}, seed >> 7, mass, 5, 4);
    }
  }
  return placed;
}

}  // namespace corsa::sensors::detail
