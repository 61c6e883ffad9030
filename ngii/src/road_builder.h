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
  int kinks = 0;
};

/// `widths`: the plan lanes' measured widths (lane_widths.h), one per lane; `ends`: the lines
/// the road starts and ends on (end_lines.h).
BuiltRoad build_road(const RoadPlan& plan, const Network& network, const Origin& origin,
                     const std::vector<WidthProfile>& widths, const RoadEndLines& ends,
                     const ConvertOptions& options);

}  // namespace corsa::ngii::detail
