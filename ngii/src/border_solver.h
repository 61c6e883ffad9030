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

/// Narrows the outermost lane on the inside of a turn of the reference line (`curvature`,
/// 1/m, + left) where its outer border would lie within `clearance` (m) of the centre of
/// curvature or beyond it: there the lane's border folds over itself (OpenDRIVE 1.8 §9.3:
/// borders are offsets along the reference line's normals, which cross at that centre). The
/// lane keeps its centre and narrows on both sides, to no less than `min_width` (m; a lane
/// whose centre is that close to the turn's centre keeps min_width and folds less). Such turns
/// are junction paths whose sparse survey vertices turn at radii of 1-3 m under lanes 3.5-5 m
/// wide: the real lane edge there is the kerb corner, nearer the lane's centre.
void narrow_inside_of_turn(std::vector<LaneTarget>& lanes, double curvature, double clearance,
                           double min_width);

/// Borders b_0..b_n for n = lanes.size() lanes; `reference` is the lane whose inner border is
/// kept near t = 0.
std::vector<double> solve_borders(const std::vector<LaneTarget>& lanes, size_t reference);

}  // namespace corsa::ngii::detail
