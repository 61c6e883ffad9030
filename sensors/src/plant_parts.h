#pragma once

// Parts of the generated plants (private to vegetation.cpp): bark and leaf materials, smooth
// branches along curves, clumps of leaves and lobes of a crown filled with them.

#include <span>

#include "corsa/core/random.h"
#include "corsa/sensors/material.h"
#include "mesh_builder.h"
#include "vegetation.h"

namespace corsa::sensors::detail {

Material bark();

/// The leaves of one plant: the sunlit clumps and the darker ones inside and beneath.
struct Leaves {
  Material lit;
  Material shade;
};
/// Broadleaved greens (one of four) or needles (one of two blue-greens), drawn from `rng`;
/// named by index, so that the scene shares them between plants.
Leaves draw_leaves(RandomStream& rng, bool needles);

/// The mass a clump belongs to (a crown, a bush, a spruce's cone): an ellipsoid whose outward
/// direction a clump's normals are bent towards.
struct Mass {
  Vec3 centre;
  Vec3 radii;
};

/// A branch through `points` (two or more), radius r0 at the first and r1 at the last,
/// `segments` around, open at both ends (they end in the trunk or in the leaves), smooth.
void branch(MeshBuilder& b, std::span<const Vec3> points, double r0, double r1, int segments);

/// A clump of leaves: an ellipsoid of radii `r` along the columns of `axes` about `c`, `slices`
/// x `stacks`, made lumpy by noise at a place drawn from `seed`; its normals averaged over its
/// faces and bent away from the middle of `mass`.
void clump(MeshBuilder& b, Vec3 c, Vec3 r, const Mat3& axes, uint64_t seed, const Mass& mass,
           int slices, int stacks);

/// A part of a crown that leaves fill: an ellipsoid.
struct Lobe {
  Vec3 centre;
  Vec3 radii;
};
/// How a lobe is filled.
struct LobeStyle {
  double clump = 0.3;    ///< a clump's mean radius, m
  double density = 0.5;  ///< clumps per (lobe radius / clump radius)^2 / 4: how closed it is
  double flat = 0.75;    ///< a clump's height over its width
  int max_clumps = 40;
};

/// Fills a lobe with clumps, most in its outer part: fewer on its side towards the middle of the
/// mass and beneath (leaves grow towards the light), those inside and beneath in the shade
/// material, small tufts beside half of the outermost (a ragged outline). A clump within a
/// clearance is left out after its draws, so the rest of the plant stays as it was. Returns clumps
/// placed.
int fill_lobe(MeshBuilder& b, RandomStream& rng, const Lobe& lobe, const Mass& mass,
              const LobeStyle& style, const Leaves& leaves, std::span<const Clearance> clear);

/// A direction uniform on the unit sphere.
Vec3 on_sphere(RandomStream& rng);
/// True when p is within `margin` of a clearance's sphere.
bool in_clearance(Vec3 p, double margin, std::span<const Clearance> clear);

}  // namespace corsa::sensors::detail
