#include "world_props.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "noise_tile.h"
#include "scalar_math.h"

namespace corsa::sensors::detail {
namespace {

Material bark() {
  Material m = materials::plain("bark", linear_rgb(82, 64, 48), 0.95);
  m.pattern = Pattern::kBark;
  return m;
}

/// How a leaf cluster sits in its crown, which sets its green: the shaded inside, the crown's
/// body, or its sunlit top.
enum class LeafShade { kInner, kBody, kSunlit };

/// The greens of one tree: a palette picked by the seed (named by index so that the scene shares
/// them between trees), in three shades.
struct FoliagePalette {
  Material inner, body, sunlit;
};

FoliagePalette foliage_palette(RandomStream& rng) {
  static constexpr Rgb8 kLight[4] = {{76, 104, 44}, {90, 112, 50}, {66, 96, 48}, {100, 110, 56}};
  static constexpr Rgb8 kDark[4] = {{34, 54, 24}, {42, 60, 26}, {30, 48, 28}, {48, 56, 30}};
  const auto i = static_cast<size_t>(rng.uniform_int(0, 3));
  const Color light = linear_rgb(kLight[i].r, kLight[i].g, kLight[i].b);
  const Color dark = linear_rgb(kDark[i].r, kDark[i].g, kDark[i].b);
  auto shade = [&](const std::string& name, Color base, Color secondary) {
    Material m = materials::plain(name, base, 0.8);
    m.pattern = Pattern::kFoliage;
    m.secondary = secondary;
    return m;
  };
  const std::string name = "foliage " + std::to_string(i);
  // Inside a crown the leaves are lit only through gaps (the renderer's shadows and sky rays
  // darken them further); its top catches the sun and looks yellower.
  return {shade(name + " inner", light * 0.7, dark * 0.7), shade(name, light, dark),
          shade(name + " sunlit", light * Color{1.18, 1.12, 0.85}, dark * Color{1.2, 1.1, 0.9})};
}

const Material& shade_of(const FoliagePalette& p, LeafShade s) {
  return s == LeafShade::kInner ? p.inner : s == LeafShade::kBody ? p.body : p.sunlit;
}

Material steel() { return materials::metal("galvanised steel", linear_rgb(150, 152, 150), 0.45); }
Material dark_paint() { return materials::plain("signal housing", linear_rgb(28, 30, 30), 0.6); }

/// A lumpy blob: an ellipsoid whose radius varies with direction, `slices` x `stacks` vertices,
/// shading round (its normals recomputed from the displaced surface).
void blob(MeshBuilder& b, Vec3 c, Vec3 r, uint32_t seed, int slices = 18, int stacks = 11,
          double lumps = 0.45) {
  const size_t first = b.mesh().vertices.size();
  b.ellipsoid(c, r, Mat3{}, slices, stacks);
  // Push each vertex in or out by a smooth random amount, read from the 4-unit noise tile at
  // the blob's own scale (a blob 2.5 m across spans about two tiles whatever its size) and at a
  // place of the tile chosen by the seed, so that small blobs are as lumpy as large ones and
  // no two alike.
  ArticulatedMesh& mesh = b.edit();
  const double scale = 2.5 / std::max({r.x, r.y, r.z});
  const double ox = 4.0 * static_cast<double>((seed >> 2) & 255u) / 256.0;
  const double oy = 4.0 * static_cast<double>((seed >> 10) & 255u) / 256.0;
  for (size_t i = first; i < mesh.vertices.size(); ++i) {
    const Vec3 d = mesh.vertices[i] - c;
    const double bump = noise(static_cast<int>(seed % 4), (d.x * 3.0 + d.z * 2.0) * scale + ox,
                              (d.y * 3.0 - d.z) * scale + oy, 4.0, 0.0, false);
    mesh.vertices[i] = c + d * (1.0 - lumps + 2.0 * lumps * bump);
  }
  b.smooth_normals_from(first);
}

/// One flat pointed blade `length` metres long centred at `centre`, facing about `facing` (tipped
/// at random, mostly upward) and turned at random about it: a leaf, or a spray of needles.
void leaf_blade(MeshBuilder& b, RandomStream& rng, Vec3 centre, Vec3 facing, double length) {
  const Vec3 face = normalized(
      facing + Vec3{rng.uniform(-0.7, 0.7), rng.uniform(-0.7, 0.7), rng.uniform(-0.4, 1.0)});
  Vec3 e1, e2;
  perpendicular_basis(face, e1, e2);
  const double turn = rng.uniform(0.0, 2.0 * kPi);
  const Vec3 along = e1 * std::cos(turn) + e2 * std::sin(turn);
  const Vec3 across = cross(face, along);
  const double width = length * rng.uniform(0.45, 0.6);
  const uint32_t v0 = b.vertex(centre - along * (0.45 * length) - across * (0.5 * width));
  const uint32_t v1 = b.vertex(centre - along * (0.45 * length) + across * (0.5 * width));
  const uint32_t v2 = b.vertex(centre + along * (0.55 * length));
  b.triangle(v0, v1, v2);
}

/// A clump of leaves (centre `at`, radii `r`) on the side of a crown away from its centre
/// `crown`: a small round dark heart (the clump's own shade, seen between its leaves) and
/// `leaves` flat pointed blades on its outer side, each facing roughly outward but turned at
/// random and shaded flat, so that the clump's face glints leaf by leaf, its outline is ragged
/// and the sky shows between its leaves at its edge.
void leaf_clump(MeshBuilder& b, RandomStream& rng, const FoliagePalette& palette, LeafShade shade,
                Vec3 at, Vec3 r, Vec3 crown, int leaves) {
  b.material(palette.inner);
  blob(b, at, r * 0.6, static_cast<uint32_t>(rng.next_u64()), 7, 5, 0.4);
  b.material(shade_of(palette, shade));
  const Vec3 outward = normalized(at - crown + Vec3{0.0, 0.0, 0.3 * norm(r)});
  const double size = std::cbrt(r.x * r.y * r.z);
  for (int k = 0; k < leaves; ++k) {
    Vec3 d =
        normalized(Vec3{rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)});
    if (dot(d, outward) < -0.2) {
      d = d - outward * (2.0 * dot(d, outward));  // mirrored to the outer side
    }
    const double reach = rng.uniform(0.55, 1.0);
    const Vec3 centre{at.x + d.x * r.x * reach, at.y + d.y * r.y * reach, at.z + d.z * r.z * reach};
    // The blade's face: along the clump's surface normal there, tipped at random.
    leaf_blade(b, rng, centre, d, size * rng.uniform(0.45, 0.7));
  }
}

/// A mass of leaves inside the ellipsoid of radii `r` about `c`: a small dark core (the shaded
/// inside, seen through the gaps) and leaf clusters of radius `cluster` metres on its shell. A
/// crown seen from the street is clumps of leaves with sky between them, not one smooth lumpy
/// solid: the shell's clusters, each a small round blob at a random depth, give the outline its
/// bumps and gaps and the faces their many small shaded clumps; those deep in the mass take the
/// inner shade, those on top the sunlit one. `cover` is the clusters' summed cross-section over
/// the shell's area (below about 1.2 gaps stay where the draws leave them).
void leaf_mass(MeshBuilder& b, RandomStream& rng, const FoliagePalette& palette, Vec3 c, Vec3 r,
               double cluster, double cover) {
  b.material(palette.inner);
  blob(b, c, r * 0.45, static_cast<uint32_t>(rng.next_u64()), 12, 8);
  const double rm = std::cbrt(r.x * r.y * r.z);
  const double area = 4.0 * kPi * rm * rm;
  const int count = std::clamp(static_cast<int>(cover * area / (kPi * cluster * cluster)), 6, 90);
  for (int k = 0; k < count; ++k) {
    // Uniform on the sphere, fewer on the underside (light comes from above, and so do leaves).
    double z = rng.uniform(-1.0, 1.0);
    if (z < -0.3 && rng.uniform01() < 0.5) {
      z = -z;
    }
    const double a = rng.uniform(0.0, 2.0 * kPi);
    const double rho = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double depth = rng.uniform(0.62, 1.0);
    const Vec3 at{c.x + r.x * depth * rho * std::cos(a), c.y + r.y * depth * rho * std::sin(a),
                  c.z + r.z * depth * z};
    const double size = cluster * rng.uniform(0.6, 1.4);
    // Clusters hang flatter than round (leaves spread to the light).
    const Vec3 radii{size * rng.uniform(0.8, 1.25), size * rng.uniform(0.8, 1.25),
                     size * rng.uniform(0.55, 0.8)};
    const double tint = rng.uniform01();
    const LeafShade shade = depth < 0.75             ? LeafShade::kInner
                            : z > 0.35 && tint < 0.6 ? LeafShade::kSunlit
                            : z < -0.2 && tint < 0.5 ? LeafShade::kInner
                            : tint < 0.12            ? LeafShade::kSunlit
                                                     : LeafShade::kBody;
    leaf_clump(b, rng, palette, shade, at, radii, c, 36);
  }
}

/// The lobes of a broadleaved crown about `c` (radius `cr`, half height `ch`): three to five
/// masses of leaves round a central one, each on a limb from the top of the trunk at `fork`,
/// so that the crown's outline has the deep notches between a real tree's main limbs and the
/// limbs show below and between the masses.
void broadleaf_crown(MeshBuilder& b, RandomStream& rng, const FoliagePalette& palette,
                     const Material& wood, Vec3 fork, Vec3 c, double cr, double ch, double cluster,
                     double limb_r) {
  const int lobes = static_cast<int>(rng.uniform_int(3, 5));
  const double turn = rng.uniform(0.0, 2.0 * kPi);
  std::vector<std::pair<Vec3, Vec3>> masses;  // centre, radii
  masses.push_back({c + Vec3{0.0, 0.0, ch * rng.uniform(0.1, 0.25)},
                    Vec3{cr * 0.55, cr * 0.55, ch * rng.uniform(0.55, 0.7)}});
  for (int k = 0; k < lobes; ++k) {
    const double a = turn + 2.0 * kPi * (k + rng.uniform(-0.2, 0.2)) / lobes;
    const double out = cr * rng.uniform(0.4, 0.55);
    const double lobe_r = cr * rng.uniform(0.42, 0.6);
    masses.push_back({c + Vec3{out * std::cos(a), out * std::sin(a), ch * rng.uniform(-0.35, 0.2)},
                      Vec3{lobe_r, lobe_r * rng.uniform(0.8, 1.0), ch * rng.uniform(0.4, 0.6)}});
  }
  b.material(wood);
  for (const auto& [centre, radii] : masses) {
    // A limb from the fork into the mass, and a branch off it towards the mass's lower side.
    const Vec3 end = centre - Vec3{0.0, 0.0, 0.3 * radii.z};
    b.tube(fork, end, limb_r, 0.35 * limb_r, 6, false);
    const Vec3 mid = fork + (end - fork) * 0.5;
    const Vec3 side =
        mid + Vec3{0.0, 0.0, 0.25 * radii.z} +
        normalized(Vec3{end.x - fork.x + 0.3, end.y - fork.y - 0.2, 0.0}) * (0.6 * radii.x);
    b.tube(mid, side, 0.45 * limb_r, 0.2 * limb_r, 5, false);
  }
  for (const auto& [centre, radii] : masses) {
    leaf_mass(b, rng, palette, centre, radii, cluster, 0.8);
  }
}

/// A conifer's foliage: four tiers of drooping branches, each a dark cone (the shade under the
/// branches) under sprays of needles (blades, denser towards the tier's rim, where the
/// branches' tips make its ragged outline), narrowing to the top.
void conifer_tiers(MeshBuilder& b, RandomStream& rng, const FoliagePalette& palette,
                   double height) {
  const int tiers = 4;
  const double spray = std::clamp(0.05 * height, 0.25, 0.6);
  for (int i = 0; i < tiers; ++i) {
    const double z0 = height * (0.2 + 0.18 * i);
    const double z1 = z0 + 0.35 * height;
    const double r = 0.22 * height * (1.0 - 0.2 * i);
    b.material(palette.inner);
    b.tube({0, 0, z0}, {0, 0, z1}, 0.85 * r, 0.02, 12, true);
    b.material(palette.body);
    const double side = std::hypot(r, z1 - z0);
    const int sprays =
        std::clamp(static_cast<int>(2.5 * kPi * r * side / (spray * spray)), 20, 260);
    for (int k = 0; k < sprays; ++k) {
      // Towards the rim: the fraction of the way up the cone, squared.
      const double f = std::pow(rng.uniform01(), 1.6) * 0.92;
      const double a = rng.uniform(0.0, 2.0 * kPi);
      const double rf = r * (1.0 - f) * rng.uniform(0.85, 1.05);
      const Vec3 out{std::cos(a), std::sin(a), 0.0};
      const Vec3 at = out * rf + Vec3{0.0, 0.0, z0 + f * (z1 - z0) - 0.05 * r};
      // The cone's outward normal, leaning up by its slope.
      leaf_blade(b, rng, at, normalized(out * (z1 - z0) + Vec3{0.0, 0.0, r}),
                 spray * rng.uniform(0.7, 1.3));
    }
  }
}

}  // namespace

ArticulatedMesh make_tree(RandomStream& rng, double height, bool allow_conifer) {
  MeshBuilder b;
  b.semantic(SemanticClass::kVegetation);
  const bool conifer = allow_conifer && rng.uniform01() < 0.25;
  const double trunk_r = std::clamp(0.018 * height, 0.08, 0.25);
  const Material wood = bark();
  b.material(wood);
  if (conifer) {
    b.tube({0, 0, 0}, {0, 0, 0.9 * height}, trunk_r, 0.2 * trunk_r, 8, false);
    conifer_tiers(b, rng, foliage_palette(rng), height);
    return b.take();
  }
  const double crown_base = height * rng.uniform(0.3, 0.45);
  const double fork_z = crown_base + 0.08 * height;
  b.tube({0, 0, 0}, {0, 0, fork_z}, trunk_r, 0.75 * trunk_r, 8, false);
  const FoliagePalette palette = foliage_palette(rng);
  const double crown_h = height - crown_base;
  const double crown_r = std::min(3.4, crown_h * rng.uniform(0.32, 0.44));
  // Leaf clusters about 0.45 m across for an 8 m tree (0.055 of the height, 0.3-0.7 m).
  broadleaf_crown(b, rng, palette, wood, {0, 0, fork_z - 0.02 * height},
                  {0, 0, crown_base + 0.55 * crown_h}, crown_r, 0.5 * crown_h,
                  std::clamp(0.055 * height, 0.3, 0.7), 0.6 * trunk_r);
  return b.take();
}

ArticulatedMesh make_bush(RandomStream& rng, double size) {
  MeshBuilder b;
  b.semantic(SemanticClass::kVegetation);
  const FoliagePalette palette = foliage_palette(rng);
  const double r = 0.5 * size * rng.uniform(0.8, 1.0);
  const double cluster = std::clamp(0.1 * size, 0.12, 0.3);
  // Two or three overlapping masses: a bush is wider than high and seldom round.
  const int masses = static_cast<int>(rng.uniform_int(2, 3));
  const double turn = rng.uniform(0.0, 2.0 * kPi);
  for (int k = 0; k < masses; ++k) {
    const double a = turn + 2.0 * kPi * k / masses;
    const double out = r * rng.uniform(0.2, 0.35);
    const double mr = r * rng.uniform(0.7, 0.85);
    leaf_mass(b, rng, palette, {out * std::cos(a), out * std::sin(a), 0.7 * mr},
              {mr, mr * rng.uniform(0.8, 1.0), 0.85 * mr}, cluster, 1.1);
  }
  return b.take();
}

ArticulatedMesh make_street_light(double height, double reach) {
  MeshBuilder b;
  b.semantic(SemanticClass::kPole).material(steel());
  b.tube({0, 0, 0}, {0, 0, height}, 0.09, 0.06, 10, true);
  b.tube({0, 0, height - 0.15}, {reach, 0, height + 0.1}, 0.045, 0.04, 8, true);
  b.material(dark_paint());
  b.box({reach - 0.3, -0.16, height}, {reach + 0.35, 0.16, height + 0.14});
  // The lamp's diffuser faces down; it glows when it is dark, as bright as its 3,000 cd
  // (light_list.cpp) spread over its 0.13 m^2 make it: about 23,000 cd/m^2, 0.72 in the
  // renderer's radiance unit (kNitsPerUnit), in a warm LED white.
  b.material(materials::lamp("street lamp", linear_rgb(230, 225, 210), Color{0.8, 0.72, 0.55},
                             LightRole::kStreetLamp));
  b.box({reach - 0.25, -0.12, height - 0.02}, {reach + 0.3, 0.12, height});
  return b.take();
}

ArticulatedMesh make_traffic_light(SignalLayout layout, double bottom, double head_height) {
  MeshBuilder b;
  const bool horizontal = layout != SignalLayout::kVertical3;
  const int bulbs = layout == SignalLayout::kHorizontal4 ? 4 : 3;
  const double cell = horizontal ? head_height : head_height / 3.0;  // bulb pitch
  const double w = horizontal ? cell * bulbs : cell * 1.1;
  const double h = horizontal ? cell * 1.1 : head_height;
  // Post: beside the head for vertical lights, a mast arm for horizontal ones. The mast stands
  // 2 m beyond the head's +y end: on the right of the traffic the head faces (+y is the facing
  // drivers' right; the kerb side under right-hand traffic), so that a head hung over the lanes
  // keeps its post off them.
  b.semantic(SemanticClass::kPole).material(steel());
  if (horizontal) {
    b.tube({-0.2, 0.5 * w + 2.0, 0}, {-0.2, 0.5 * w + 2.0, bottom + 0.5 * h + 0.3}, 0.12, 0.1, 10,
           true);
    b.tube({-0.2, 0.5 * w + 2.0, bottom + 0.5 * h + 0.25},
           {-0.2, -0.5 * w, bottom + 0.5 * h + 0.25}, 0.06, 0.05, 8, true);
  } else {
    b.tube({-0.2, 0, 0}, {-0.2, 0, bottom + h}, 0.07, 0.06, 10, true);
  }
  b.semantic(SemanticClass::kTrafficLight).material(dark_paint());
  b.box({-0.15, -0.5 * w, bottom}, {0.12, 0.5 * w, bottom + h});
  const LightRole roles4[4] = {LightRole::kSignalRed, LightRole::kSignalYellow,
                               LightRole::kSignalGreen, LightRole::kSignalGreen};
  const Color lens[3] = {linear_rgb(70, 8, 8), linear_rgb(80, 55, 5), linear_rgb(5, 60, 30)};
  // Saturated glows: no channel should clip towards white before the red one does.
  const Color glow[3] = {Color{6.0, 0.08, 0.03}, Color{6.0, 2.6, 0.05}, Color{0.08, 5.0, 2.2}};
  for (int i = 0; i < bulbs; ++i) {
    const int k = std::min(i, 2);
    const LightRole role = roles4[i];
    const char* names[3] = {"signal red", "signal yellow", "signal green"};
    b.material(materials::lamp(names[k], lens[k], glow[k], role));
    Vec3 c;
    if (horizontal) {
      c = {0.125, 0.5 * w - cell * (i + 0.5), bottom + 0.5 * h};
    } else {
      c = {0.125, 0.0, bottom + h - cell * (i + 0.5)};
    }
    b.tube(c, c + Vec3{0.02, 0, 0}, 0.36 * cell, 0.36 * cell, 14, true);
    // Visor over each bulb.
    b.material(dark_paint());
    b.box(c + Vec3{0.0, -0.4 * cell, 0.36 * cell}, c + Vec3{0.18, 0.4 * cell, 0.42 * cell});
  }
  return b.take();
}

ArticulatedMesh make_sign(const SignFace& face, double width, double height, double bottom,
                          const std::string& name) {
  MeshBuilder b;
  b.semantic(SemanticClass::kPole).material(steel());
  b.tube({-0.05, 0, 0}, {-0.05, 0, bottom + 0.8 * height}, 0.035, 0.035, 8, true);
  b.semantic(SemanticClass::kTrafficSign);
  Material m = sign_face_material(face, name);
  // The face polygon follows the shape (circles as 24-gons), uv over its square.
  std::vector<Vec3> points;
  std::vector<std::array<float, 2>> uvs;
  auto add = [&](double u, double v) {
    points.push_back({0.0, (0.5 - u) * width, bottom + v * height});
    uvs.push_back({static_cast<float>(u), static_cast<float>(v)});
  };
  switch (face.shape) {
    case SignShape::kCircle:
      for (int i = 0; i < 24; ++i) {
        const double a = 2.0 * kPi * i / 24.0;
        add(0.5 + 0.5 * std::cos(a), 0.5 + 0.5 * std::sin(a));
      }
      break;
    case SignShape::kTriangleUp:
      add(0.0, 0.11), add(1.0, 0.11), add(0.5, 0.975);
      break;
    case SignShape::kTriangleDown:
      add(0.5, 0.025), add(1.0, 0.89), add(0.0, 0.89);
      break;
    case SignShape::kOctagon:
      for (int i = 0; i < 8; ++i) {
        const double a = 2.0 * kPi * (i + 0.5) / 8.0;
        const double r = 0.5 / std::cos(kPi / 8.0);
        add(0.5 + r * std::cos(a), 0.5 + r * std::sin(a));
      }
      break;
    case SignShape::kDiamond:
      add(0.5, 0.0), add(1.0, 0.5), add(0.5, 1.0), add(0.0, 0.5);
      break;
    default:
      add(0.0, 0.0), add(1.0, 0.0), add(1.0, 1.0), add(0.0, 1.0);
      break;
  }
  b.material(m);
  b.polygon(points, uvs);
  // The back: grey metal a little behind.
  std::vector<Vec3> back;
  for (auto it = points.rbegin(); it != points.rend(); ++it) {
    back.push_back(*it - Vec3{0.015, 0.0, 0.0});
  }
  b.material(steel());
  b.polygon(back, {});
  return b.take();
}

Material sign_face_material(const SignFace& face, const std::string& name) {
  Material m;
  m.name = name;
  m.pattern = Pattern::kSignFace;
  m.sign = face;
  m.roughness = 0.5;
  m.base_color = face.fill;
  return m;
}

Material road_paint() {
  Material m = materials::plain("road paint", linear_rgb(232, 232, 222), 0.6);
  m.pattern = Pattern::kPaint;
  m.secondary = linear_rgb(92, 92, 94);
  m.params[0] = 0.5;
  return m;
}

ArticulatedMesh make_rail(double length, bool fence) {
  MeshBuilder b;
  b.semantic(fence ? SemanticClass::kFence : SemanticClass::kGuardRail).material(steel());
  const int posts = std::max(2, static_cast<int>(std::ceil(length / 2.0)) + 1);
  for (int i = 0; i < posts; ++i) {
    const double x = length * i / (posts - 1);
    if (fence) {
      b.tube({x, 0, 0}, {x, 0, 1.8}, 0.03, 0.03, 6, true);
    } else {
      b.box({x - 0.05, -0.08, 0.0}, {x + 0.05, 0.0, 0.75});
    }
  }
  if (fence) {
    // Galvanised wire mesh: seen from the road mostly the light wires against what is behind.
    Material mesh_panel = materials::plain("fence panel", linear_rgb(168, 172, 166), 0.6);
    mesh_panel.pattern = Pattern::kMetalGrid;
    mesh_panel.secondary = linear_rgb(92, 98, 90);
    b.material(mesh_panel);
    b.box({0, -0.01, 0.05}, {length, 0.01, 1.75});
  } else {
    b.box({0, 0.0, 0.48}, {length, 0.12, 0.78});  // the W beam, towards the road (+y)
  }
  return b.take();
}

}  // namespace corsa::sensors::detail
