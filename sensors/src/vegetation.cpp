#include "vegetation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "plant_parts.h"
#include "scalar_math.h"

namespace corsa::sensors::detail {
namespace {

/// The look of a broadleaved form (and of the pine, whose crown is built the same way).
struct CrownForm {
  double base_lo, base_hi;    ///< the clear trunk's share of the height
  double width_lo, width_hi;  ///< the crown's radius over its height
  double max_radius;          ///< m
  int limbs_lo, limbs_hi;
  double lean_lo, lean_hi;  ///< the limbs' angle from the vertical, rad
  int lobes_lo, lobes_hi;   ///< lobes per limb
  double lobe;              ///< a lobe's radius over the crown's
  double lobe_flat;         ///< a lobe's height over its width
  double clump;             ///< a clump's radius over the tree's height
  double density;           ///< LobeStyle::density
  double flat;              ///< LobeStyle::flat
  double trunk;             ///< trunk radius over the height
  bool leader;              ///< a central stem up into the crown's top
  bool needles;
};

// Shares from street trees as they stand (a lime of 10 m: a clear trunk of 3-4 m, a crown some
// 7 m across; a plane's crown wider than tall; a fastigiate hornbeam's 2-3 m across).
constexpr CrownForm kRound{0.30, 0.42, 0.34, 0.42,  4.0,  4,    5,     0.45, 0.75, 2,
                           3,    0.5,  0.8,  0.035, 0.55, 0.75, 0.018, true, false};
constexpr CrownForm kSpreading{0.26, 0.36, 0.5, 0.62, 5.0, 3,   4,    0.75,  1.0,  2,
                               3,    0.5,  0.7, 0.04, 0.5, 0.7, 0.02, false, false};
constexpr CrownForm kColumnar{0.12, 0.22, 0.16, 0.2,  2.0, 5,    6,     0.1,  0.22, 2,
                              3,    0.7,  1.3,  0.03, 0.4, 0.85, 0.016, true, false};
constexpr CrownForm kYoung{0.4, 0.5,  0.28, 0.36, 2.2, 3,   4,     0.35, 0.6,  1,
                           2,   0.55, 0.9,  0.03, 0.4, 0.8, 0.011, true, false};
constexpr CrownForm kPine{0.55, 0.7, 0.3,  0.42, 3.5, 3,    5,    0.55, 0.95, 1,
                          2,    0.5, 0.45, 0.04, 0.6, 0.45, 0.02, true, true};

/// Distance from p along the unit direction d to the surface of the mass's ellipsoid (p
/// inside it).
double to_surface(const Mass& m, Vec3 p, Vec3 d) {
  const Vec3 q{(p.x - m.centre.x) / m.radii.x, (p.y - m.centre.y) / m.radii.y,
               (p.z - m.centre.z) / m.radii.z};
  const Vec3 e{d.x / m.radii.x, d.y / m.radii.y, d.z / m.radii.z};
  const double a = dot(e, e);
  const double b = dot(q, e);
  const double c = dot(q, q) - 1.0;
  return (-b + std::sqrt(std::max(0.0, b * b - a * c))) / a;
}

/// A point of the polyline a-b-c at t in [0, 1] (b at t = 0.5).
Vec3 along(const std::array<Vec3, 3>& p, double t) {
  return t < 0.5 ? p[0] + (p[1] - p[0]) * (2.0 * t) : p[1] + (p[2] - p[1]) * (2.0 * t - 1.0);
}

/// A crown of lobes on limbs: each limb leans out of the fork towards its own side of the
/// crown, and its lobes hang about it on twigs from the limb's outer half.
void limbs_and_lobes(MeshBuilder& b, RandomStream& rng, const CrownForm& f, const Mass& crown,
                     Vec3 fork, double trunk_r, double height, const Leaves& leaves,
                     std::span<const Clearance> clear) {
  const int limbs = static_cast<int>(rng.uniform_int(f.limbs_lo, f.limbs_hi));
  const double phase = rng.uniform(0.0, 2.0 * kPi);
  const double r = crown.radii.x;
  const LobeStyle style{.clump = std::clamp(f.clump * height, 0.16, 0.42),
                        .density = f.density,
                        .flat = f.flat,
                        .max_clumps = 32};
  for (int k = 0; k < limbs; ++k) {
    const double a = phase + 2.0 * kPi * (k + rng.uniform(-0.3, 0.3)) / limbs;
    const double lean = rng.uniform(f.lean_lo, f.lean_hi);
    const Vec3 start = fork - Vec3{0.0, 0.0, 0.25 * trunk_r * k};
    const Vec3 dir{std::sin(lean) * std::cos(a), std::sin(lean) * std::sin(a), std::cos(lean)};
    const double length = to_surface(crown, start, dir) * rng.uniform(0.6, 0.78);
    const std::array<Vec3, 3> limb = {
        start, start + dir * (0.5 * length) + Vec3{0.0, 0.0, 0.06 * length}, start + dir * length};
    b.material(bark());
    branch(b, limb, 0.5 * trunk_r, 0.1 * trunk_r, 7);
    const int lobes = static_cast<int>(rng.uniform_int(f.lobes_lo, f.lobes_hi));
    for (int j = 0; j < lobes; ++j) {
      const double az = a + rng.uniform(-0.6, 0.6) * kPi / limbs;
      const double z = rng.uniform(-0.5, 0.85);
      const double rho = std::sqrt(1.0 - z * z);
      const double depth = rng.uniform(0.45, 0.7);
      const Vec3 centre =
          crown.centre + Vec3{rho * std::cos(az) * r * depth, rho * std::sin(az) * r * depth,
                              z * crown.radii.z * depth};
      const double lr = f.lobe * r * rng.uniform(0.8, 1.2);
      const Lobe lobe{centre, {lr, lr, std::min(lr * f.lobe_flat, 0.7 * crown.radii.z)}};
      // The twig from the limb's point nearest the lobe, three quarters of the way into it.
      Vec3 from = along(limb, 0.5);
      for (double t : {0.75, 1.0}) {
        if (norm(along(limb, t) - centre) < norm(from - centre)) {
          from = along(limb, t);
        }
      }
      const Vec3 to = from + (centre - from) * 0.75;
      if (!in_clearance(to, 0.1, clear)) {
        const std::array<Vec3, 2> twig = {from, to};
        b.material(bark());
        branch(b, twig, std::max(0.15 * trunk_r, 0.02), 0.012, 5);
      }
      fill_lobe(b, rng, lobe, crown, style, leaves, clear);
    }
  }
}

ArticulatedMesh crowned_tree(RandomStream& rng, double height, const CrownForm& f,
                             std::span<const Clearance> clear) {
  MeshBuilder b;
  b.semantic(SemanticClass::kVegetation);
  const Leaves leaves = draw_leaves(rng, f.needles);
  const double trunk_r = std::clamp(f.trunk * height, 0.05, 0.3);
  const double base = height * rng.uniform(f.base_lo, f.base_hi);
  const double crown_h = height - base;
  const double r = std::min(f.max_radius, crown_h * rng.uniform(f.width_lo, f.width_hi));
  // Trunks lean a little and their crowns sit over where they lean to.
  const double lean_a = rng.uniform(0.0, 2.0 * kPi);
  const double lean = rng.uniform(0.0, 0.03) * height;
  const Vec3 top{lean * std::cos(lean_a), lean * std::sin(lean_a), 0.0};
  const Mass crown{top + Vec3{0.0, 0.0, base + 0.5 * crown_h}, {r, r, 0.5 * crown_h}};
  const Vec3 fork = top + Vec3{0.0, 0.0, base + 0.12 * crown_h};
  b.material(bark());
  // From under the ground (roots in the soil or the paving) to the fork, flared at the foot.
  const std::array<Vec3, 4> trunk = {Vec3{0.0, 0.0, -0.3}, Vec3{0.0, 0.0, 0.3},
                                     fork * 0.55 + Vec3{0.0, 0.0, 0.1}, fork};
  branch(b, trunk, 1.35 * trunk_r, 0.75 * trunk_r, 10);
  if (f.leader) {
    const std::array<Vec3, 3> leader = {
        fork, crown.centre + Vec3{rng.uniform(-0.1, 0.1) * r, rng.uniform(-0.1, 0.1) * r, 0.0},
        crown.centre + Vec3{0.0, 0.0, 0.6 * crown.radii.z}};
    branch(b, leader, 0.6 * trunk_r, 0.1 * trunk_r, 7);
  }
  limbs_and_lobes(b, rng, f, crown, fork, trunk_r, height, leaves, clear);
  if (f.leader) {
    const double lr = f.lobe * r * rng.uniform(0.7, 1.0);
    const Lobe top_lobe{crown.centre + Vec3{0.0, 0.0, 0.62 * crown.radii.z},
                        {lr, lr, std::min(lr * f.lobe_flat, 0.5 * crown.radii.z)}};
    const LobeStyle style{.clump = std::clamp(f.clump * height, 0.16, 0.42),
                          .density = f.density,
                          .flat = f.flat,
                          .max_clumps = 32};
    fill_lobe(b, rng, top_lobe, crown, style, leaves, clear);
  }
  return b.take();
}

/// A spruce: whorls of drooping branches, each a limb with needle sprays along it, longest at
/// the foot of the crown, and a spire at the top.
ArticulatedMesh spruce(RandomStream& rng, double height, std::span<const Clearance> clear) {
  MeshBuilder b;
  b.semantic(SemanticClass::kVegetation);
  const Leaves leaves = draw_leaves(rng, true);
  const double trunk_r = std::clamp(0.02 * height, 0.06, 0.3);
  const double lowest = height * rng.uniform(0.06, 0.15);
  const double reach = std::min(3.0, height * rng.uniform(0.19, 0.24));
  const Mass cone{{0.0, 0.0, lowest + 0.35 * (height - lowest)},
                  {reach, reach, 0.5 * (height - lowest)}};
  b.material(bark());
  const std::array<Vec3, 3> trunk = {Vec3{0.0, 0.0, -0.3}, Vec3{0.0, 0.0, 0.5 * height},
                                     Vec3{0.0, 0.0, height}};
  branch(b, trunk, 1.2 * trunk_r, 0.02, 8);
  const double step = height * rng.uniform(0.055, 0.07);
  double phase = rng.uniform(0.0, 2.0 * kPi);
  for (double z = lowest; z < height - 0.6; z += step * rng.uniform(0.85, 1.15)) {
    const double frac = (z - lowest) / (height - lowest);
    const double length = reach * std::pow(1.0 - frac, 0.9) + 0.25;
    const int n = static_cast<int>(rng.uniform_int(5, 7));
    phase += 0.7;
    for (int j = 0; j < n; ++j) {
      const double a = phase + 2.0 * kPi * (j + rng.uniform(-0.25, 0.25)) / n;
      const double len = length * rng.uniform(0.8, 1.1);
      const double droop = len * rng.uniform(0.2, 0.4);
      const Vec3 out{std::cos(a), std::sin(a), 0.0};
      const Vec3 start{0.0, 0.0, z};
      const std::array<Vec3, 3> limb = {start,
                                        start + out * (0.55 * len) + Vec3{0, 0, -0.55 * droop},
                                        start + out * len + Vec3{0, 0, -0.8 * droop}};
      if (len > 0.5 && !in_clearance(limb[2], 0.1, clear)) {
        b.material(bark());
        branch(b, limb, 0.3 * trunk_r * (1.0 - frac) + 0.015, 0.012, 5);
      }
      // Sprays hang along the branch, flat and drooping, each as long as its share of it.
      const int sprays = len > 1.2 ? 3 : len > 0.6 ? 2 : 1;
      const Vec3 dir = normalized(out + Vec3{0.0, 0.0, -0.3});
      const Vec3 side{-std::sin(a), std::cos(a), 0.0};
      const Vec3 up = cross(dir, side);
      const Mat3 axes{{{dir.x, side.x, up.x}, {dir.y, side.y, up.y}, {dir.z, side.z, up.z}}};
      for (int s = 0; s < sprays; ++s) {
        const double t = (s + 0.8) / (sprays + 0.3);
        const double piece = len / sprays;
        const Vec3 at = along(limb, t);
        const Vec3 r{0.6 * piece + 0.12, 0.3 * len + 0.1, rng.uniform(0.1, 0.16) + 0.04 * piece};
        const uint64_t seed = rng.next_u64();
        if (in_clearance(at, 1.3 * std::max(r.x, r.y), clear)) {
          continue;
        }
        b.material(frac < 0.3 && s == 0 ? leaves.shade : leaves.lit);
        clump(b, at, r, axes, seed, cone, 7, 4);
      }
    }
  }
  b.material(leaves.lit);
  clump(b, {0.0, 0.0, height - 0.45}, {0.22, 0.22, 0.6}, Mat3{}, rng.next_u64(), cone, 6, 5);
  return b.take();
}

}  // namespace

TreeForm draw_tree_form(RandomStream& rng, bool allow_conifer) {
  const double u = rng.uniform01();
  const double v = rng.uniform01();
  if (allow_conifer && u < 0.3) {
    return u < 0.18 ? TreeForm::kSpruce : TreeForm::kPine;
  }
  return v < 0.35   ? TreeForm::kRound
         : v < 0.6  ? TreeForm::kSpreading
         : v < 0.75 ? TreeForm::kColumnar
                    : TreeForm::kYoung;
}

ArticulatedMesh make_tree(RandomStream& rng, double height, TreeForm form,
                          std::span<const Clearance> clear) {
  switch (form) {
    case TreeForm::kRound:
      return crowned_tree(rng, height, kRound, clear);
    case TreeForm::kSpreading:
      return crowned_tree(rng, height, kSpreading, clear);
    case TreeForm::kColumnar:
      return crowned_tree(rng, height, kColumnar, clear);
    case TreeForm::kYoung:
      // Newly planted: smaller than the trees grown up around it.
      return crowned_tree(rng, height * rng.uniform(0.6, 0.8), kYoung, clear);
    case TreeForm::kSpruce:
      return spruce(rng, height, clear);
    case TreeForm::kPine:
      return crowned_tree(rng, height, kPine, clear);
  }
  return {};
}

ArticulatedMesh make_tree(RandomStream& rng, double height, bool allow_conifer,
                          std::span<const Clearance> clear) {
  const TreeForm form = draw_tree_form(rng, allow_conifer);
  return make_tree(rng, height, form, clear);
}

ArticulatedMesh make_bush(RandomStream& rng, double size) {
  MeshBuilder b;
  b.semantic(SemanticClass::kVegetation);
  const Leaves leaves = draw_leaves(rng, false);
  const double r = 0.5 * size * rng.uniform(0.8, 1.0);
  // Compact (a clipped shrub, a dense dome) or loose (taller, open, its stems seen at the foot).
  const bool loose = rng.uniform01() < 0.35;
  const double rz = r * (loose ? rng.uniform(0.8, 1.1) : rng.uniform(0.55, 0.7));
  const Mass dome{{0.0, 0.0, 0.8 * rz}, {r, r, rz}};
  if (loose) {
    b.material(bark());
    const int stems = static_cast<int>(rng.uniform_int(3, 5));
    for (int k = 0; k < stems; ++k) {
      const double a = rng.uniform(0.0, 2.0 * kPi);
      const std::array<Vec3, 2> stem = {
          Vec3{0.0, 0.0, -0.1},
          Vec3{0.5 * r * std::cos(a), 0.5 * r * std::sin(a), dome.centre.z + 0.3 * rz}};
      branch(b, stem, 0.025, 0.01, 5);
    }
  }
  const LobeStyle style{.clump = std::clamp(0.24 * r, 0.1, 0.35),
                        .density = loose ? 0.55 : 0.9,
                        .flat = 0.8,
                        .max_clumps = 60};
  fill_lobe(b, rng, {dome.centre, dome.radii}, dome, style, leaves, {});
  return b.take();
}

}  // namespace corsa::sensors::detail
