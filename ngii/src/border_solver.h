#pragma once

// Lane borders at one station of a road from what was measured there: each lane's centre
// offset and its width. A small least-squares problem over the borders b_0..b_n (t, m, + left;
// lane k spans [b_{k+1}, b_k]): each lane's centre (b_k + b_{k+1}) / 2 should match its measured
// centre (weighted heavily, the weight raised until within 2 cm), each width b_k - b_{k+1} its
// width target, and the inner border of the reference lane stays near 0 (the reference line is
// that lane's left edge; the laneOffset takes up what it cannot follow, OpenDRIVE 1.8 §9.3).

#include <cstddef>
#include <vector>

namespace corsa::ngii::detail {

struct LaneTarget {
  double centre = 0.0;  ///< measured centre offset (m)
  double width = 0.0;   ///< width target (m)
  /// false: the centre is not where the lane is (a lane splitting off a neighbour, whose link
  /// still runs inside that neighbour): only the width counts, held firmly.
  bool centred = true;
};

/// Borders b_0..b_n for n = lanes.size() lanes; `reference` is the lane whose inner border is
/// kept near t = 0.
std::vector<double> solve_borders(const std::vector<LaneTarget>& lanes, size_t reference);

}  // namespace corsa::ngii::detail
