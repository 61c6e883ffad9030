#pragma once

// One RoadPlan -> one OpenDRIVE road: the reference line is the reference lane's left edge
// (bent at the ends to meet the lanes' end lines square), fitted with lines, arcs and clothoids;
// the lanes' offsets, heights and widths are measured at stations along it and turned into
// elevation, superelevation, laneOffset and width polynomials; speeds from MaxSpeed.

#include <optional>
#include <vector>

#include "corsa/ngii/convert.h"
#include "end_lines.h"
#include "lane_widths.h"
#include "network.h"
#include "road_plan.h"

namespace corsa::ngii::detail {

struct BuiltRoad {
  xodr::Road road;  ///< id, name, junction and links are left for the caller
  /// Per plan lane: (link, s_start, s_end) of every source link along it.
  struct Span {
    int link = -1;
    double s_start = 0.0;
    double s_end = 0.0;
  };
  std::vector<std::vector<Span>> spans;
  double lane_error = 0.0;       ///< largest lane centre error at the stations (m), against
                                 ///< the smoothed lane lines it was fitted to
  double source_error = 0.0;     ///< the same against the source polylines as surveyed
  double reference_error = 0.0;  ///< plan view fit error (m)
  /// Largest distance (m) of a lane centre's start or end from its surveyed line's, over the
  /// lanes that start or end beside the others (not at zero width).
  double end_error = 0.0;
  /// A lane border lies beyond the reference line's centre of curvature at a station (the
  /// mesh folds over there).
  bool folds = false;
  int kinks = 0;
};

/// Whether a lane border of the fitted `road` (one lane section, lanes on the right), or a road
/// mark up to 0.1 m outside it, lies beyond the reference line's centre of curvature somewhere
/// along it, or runs sideways across the normals more than twice as fast as it goes forward
/// (sampled every 2 cm): where the road mesh folds over itself, or its triangles between samples
/// a few decimetres apart turn over.
bool fitted_road_folds(const xodr::Road& road);

/// Where a road's lane borders are to lie where it starts and ends: one map point (horizontal)
/// per border b_0..b_n, left to right, or nothing where the border solver's is kept. The
/// borders are moved onto them at the end and eased back to the solver's (a smoothstep over
/// 1.5 m, or 3 m per metre moved, at most 45 % of the road's length: the marks give each lane
/// its own width right up to the joint, and a longer ease takes more of the lane off them), so
/// that two lanes of different widths meet edge to edge at a joint (lane_joints.h).
struct EndBorders {
  std::vector<std::optional<Vec2>> start;  ///< empty: none at the start
  std::vector<std::optional<Vec2>> end;
  bool empty() const { return start.empty() && end.empty(); }
};

/// m over which a move of an end's borders by `largest_move` (m, the largest of its borders')
/// is eased back along a road `road_length` long (EndBorders: a smoothstep, whose steepest
/// slant is 1.5 times the move over this).
double end_border_ramp(double largest_move, double road_length);

/// `widths`: the plan lanes' measured widths (lane_widths.h), one per lane; `ends`: the lines
/// the road starts and ends on (end_lines.h); `borders`: where its lane borders are to lie at
/// its ends.
BuiltRoad build_road(const RoadPlan& plan, const Network& network, const Origin& origin,
                     const std::vector<WidthProfile>& widths, const RoadEndLines& ends,
                     const ConvertOptions& options, const EndBorders& borders = {});

}  // namespace corsa::ngii::detail
