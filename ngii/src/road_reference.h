#pragma once

// The polyline a road's reference line is fitted to: the reference lane's centre shifted left
// by half its width (its left edge), eased where a tight left turn would fold it, and bent near
// each end so that the road's end cross-section runs through the ends of all its lanes.
//
// Why bend: an OpenDRIVE road ends along the normal of its reference line (§8.2), so every lane
// ends on one straight line across the road. NGII lanes of one road end at a stop line, which
// is often skewed; a square end would cut the outer lanes short (or long) by metres. Turning the
// reference line's last metres so that its normal follows the lanes' common end line lets each
// lane end where its link does (the lanes themselves keep their course: their offsets are
// measured along those turned normals).

#include <optional>
#include <vector>

#include "corsa/ngii/curve_fit.h"
#include "polyline.h"

namespace corsa::ngii::detail {

/// Clearance (m) kept between a road's right edge and its reference line's centre of curvature
/// in right turns (relax_right_turns, and the refits of the plan view where its records turn
/// more tightly).
constexpr double kFoldClearance = 0.5;

/// A polyline vertex as a vector.
inline Vec2 to_vec(const Point2& p) { return {p.x, p.y}; }

/// A straight line across the road through the lane ends: a point and a unit direction.
struct EndLine {
  Vec2 point;
  Vec2 across;
};

/// The line through `ends` (lane end points, left to right) within 0.25 m, leaving out the
/// ends farthest off it when needed; nothing when fewer than two remain.
std::optional<EndLine> end_line(std::vector<Vec2> ends);

/// Whether lane end `p` is on `line` (within the 0.25 m end_line allows).
bool on_end_line(const EndLine& line, Vec2 p);

/// A polyline for the plan-view fit, with the headings its ends must have so that the normals
/// there run through the lane ends.
struct ReferencePolyline {
  std::vector<Point2> points;
  double start_heading = 0.0;  ///< rad
  double end_heading = 0.0;
  /// The road's greatest width (m, all lanes right of the reference line): the plan-view fit
  /// turns right no more tightly than this allows (CurveFitOptions::max_right_curvature).
  double widest = 0.0;
  /// The lanes lie left of the line (it runs along the road's right edge, the inside of a
  /// right turn): its left turns are the ones that could fold them.
  bool lanes_left = false;
};

/// The reference lane's vertices moved left by `half_widths` (per vertex), along the normal of
/// the chord over +-1 m; in tight left turns the shift shrinks to keep the shifted line's radius
/// at least 1.5 m (the laneOffset takes up the difference, §9.3). The end headings are the
/// lane's own there.
ReferencePolyline shifted_left(const Polyline& lane, const std::vector<double>& half_widths);

/// Whether a one-lane road along `lane` is better fitted along its right edge: it turns right
/// overall (by more than kInsideTurn, 0.5 rad), and its centre nowhere turns right at a radius
/// under kMinShiftRadius (1.5 m; curvature from chords of 1 m each way), where the right edge
/// could not follow it. Its lane then lies left of the reference line, on the outside of the turn,
/// where lane borders cannot fold over (they would lie beyond the centre of curvature on the
/// inside; K-City's right-turn junction paths turn at radii of 2-4 m under lanes 3.5-5 m wide).
/// With `tight_corners` the radius is not asked for (the last resort of a lane that folds
/// along its left edge).
bool along_right_edge(const Polyline& lane, bool tight_corners = false);

/// Smooths `reference` (lanes on its right; with `lanes_left` mirrored: left turns) where it
/// turns right more tightly than the road is wide (`road_width` per vertex, m): the road's right
/// edge would lie beyond the centre of curvature there and fold over. Such turns are survey jogs of
/// a few decimetres within a metre, or sparse vertices turning at sharp corners; the lanes' offsets
/// keep following the survey. The first and last 2 m stay (the normals at the ends run through the
/// lane ends), or only the first and last 0.5 m where a tight turn lies within 2 m of that end.
void relax_right_turns(std::vector<Point2>& points, const std::vector<double>& road_width,
                       bool lanes_left = false);

/// Smooths `points` within kRelaxReach (2 m) of the arc lengths `at` (m along the polyline),
/// as relax_right_turns does, by a Gaussian average of sigma 1 m; the first and last 2 m stay
/// (0.5 m at an end within 2 m of which an arc length of `at` lies: a short record meeting the
/// end's heading that turns too tightly).
void ease_near(std::vector<Point2>& points, const std::vector<double>& at);

/// Arc lengths (m) where the records of `fit` turn right (with `lanes_left`: left) more tightly
/// than `curvature` (1/m, positive): at each such record's tightest end.
std::vector<double> tight_right_turns(const CurveFit& fit, double curvature,
                                      bool lanes_left = false);

/// How far (m) the road's edges lie from the start and end anchors at most (0: not known). An
/// end that turns short of its line by `residual` (the turn that fits without folding) runs on
/// along its end heading by span x tan(residual), up to 9 cm, where that is under 15 cm: the
/// corner of its end edge left short of the line then reaches it, or nearly.
struct EndSpans {
  double start = 0.0;
  double end = 0.0;
};

/// `reference` bent near its start and end (road_end_bend.cpp) to meet `start` / `end` (when given)
/// square: it ends heading across the line, on the line's parallel through the anchor (the
/// reference lane's own end point). `road_width` (m) sets how gently it turns (the outermost lane
/// must not fold); a turn that does not fit into the road is made only partly. Lines more than 50
/// degrees off square are left alone; an end nearly square to its line (its outermost lane
/// within 1 cm of it) is not bent but, where it lies up to 0.25 m short of the line, extended
/// along its course onto it. An end that turns short of its line runs on past it (`spans`).
ReferencePolyline align_ends(ReferencePolyline reference, const std::optional<EndLine>& start,
                             const std::optional<EndLine>& end, Vec2 start_anchor, Vec2 end_anchor,
                             double road_width, EndSpans spans = {});

}  // namespace corsa::ngii::detail
