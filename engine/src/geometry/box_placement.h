#pragma once

// box_of (corsa/engine/oriented_box.h) for a caller that kept the cosine and sine of a heading:
// the contacts' update, whose entities mostly keep their heading from one step to the next.

#include "corsa/engine/oriented_box.h"

namespace corsa::engine::detail {

/// box_of(box, pose) from cos_h and sin_h, which std::cos(pose.h) and std::sin(pose.h) gave:
/// the same box, bit for bit (box_of is this with the two computed), without the two.
OrientedBox box_at_heading(const Box& box, const Pose& pose, double cos_h, double sin_h);

}  // namespace corsa::engine::detail
