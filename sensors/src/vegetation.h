#pragma once

// Generated plants (private): broadleaved trees of four forms, conifers of two and bushes. A
// crown is no closed solid: limbs fork from the trunk into it, and the leaves hang in clumps in
// lobes at the ends of the branches, with sky between the lobes at the outline and the shaded
// inside seen through the gaps. Trunks, limbs and clumps carry vertex normals (they shade
// smooth, not faceted); a clump's are bent away from the middle of its crown, so that the crown
// shades as one mass, lit on top and dark beneath, as a real one does. Every plant is drawn
// from the random stream it is given (the same stream, the same plant), in its own frame (z up,
// the foot at the origin), every triangle of class vegetation.

#include <span>

#include "corsa/core/random.h"
#include "mesh_builder.h"

namespace corsa::sensors::detail {

/// A sphere (the plant's frame, metres) a crown's leaves and twigs keep out of: the room street
/// crews prune around a lamp head.
struct Clearance {
  Vec3 centre;
  double radius = 0.0;
};

enum class TreeForm {
  kRound,      ///< lime, maple: an ovoid crown on four or five limbs and a leader
  kSpreading,  ///< plane, oak: a broad crown on three or four wide limbs
  kColumnar,   ///< fastigiate hornbeam or oak: a narrow crown on steep limbs
  kYoung,      ///< a young street tree: a small open crown high on a thin trunk
  kSpruce,     ///< whorls of drooping branches of needle sprays, narrowing to the top
  kPine,       ///< a tall bare trunk under a flat irregular crown of needle sprays
};

/// A form: a broadleaved one, or when `allow_conifer` three times in ten a conifer.
TreeForm draw_tree_form(RandomStream& rng, bool allow_conifer);

/// A tree `height` metres tall of the given form, its crown clear of `clear`.
ArticulatedMesh make_tree(RandomStream& rng, double height, TreeForm form,
                          std::span<const Clearance> clear = {});
/// A tree of a form drawn first from `rng` (draw_tree_form).
ArticulatedMesh make_tree(RandomStream& rng, double height, bool allow_conifer = true,
                          std::span<const Clearance> clear = {});
/// A bush about `size` metres across: a dome of leaf clumps, compact or loose.
ArticulatedMesh make_bush(RandomStream& rng, double size);

}  // namespace corsa::sensors::detail
