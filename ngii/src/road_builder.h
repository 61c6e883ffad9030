#pragma once

// One RoadPlan -> one OpenDRIVE road: the reference line is the reference lane's left edge
// (bent at the ends to meet the lanes' end lines square), fitted with lines, arcs and clothoids;
// the lanes' offsets, heights and widths are measured at stations along it and turned into
// elevation, superelevation, laneOffset and width polynomials; speeds from MaxSpeed.

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

/// `widths`: the plan lanes' measured widths (lane_widths.h), one per lane; `ends`: the lines
/// the road starts and ends on (end_lines.h).
BuiltRoad build_road(const RoadPlan& plan, const Network& network, const Origin& origin,
                     const std::vector<WidthProfile>& widths, const RoadEndLines& ends,
                     const ConvertOptions& options);

}  // namespace corsa::ngii::detail
