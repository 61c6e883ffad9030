#pragma once

// A road's heights from its lanes' heights (OpenDRIVE 1.8 §8.4): at every station, the lanes'
// centres (horizontal offset t, height z) are fitted with a plane across the road, giving the
// elevation at the reference line and the superelevation (roll). Where the lanes do not lie on a
// plane (a banked track whose outer lanes rise ever more steeply), the road gets no
// superelevation but a lateral shape instead: at chosen stations, a curve through the lane
// centres' heights (cubic pieces in t, §8.4.3), interpolated linearly between stations.

#include <vector>

#include "corsa/ngii/convert.h"
#include "corsa/xodr/model.h"

namespace corsa::ngii::detail {

/// One lane's centre at one station.
struct LaneHeightSample {
  double t = 0.0;   ///< horizontal offset from the reference line (m, + left)
  double z = 0.0;   ///< height (m)
  bool own = true;  ///< on the lane itself (not extrapolated past its ends)
};

/// Fills road.elevation and either road.superelevation or road.shapes from the samples at
/// stations `s` (samples[i][k]: lane k at station i). Returns the superelevation roll (rad) at
/// each station (0 without superelevation), by which horizontal offsets turn into t.
std::vector<double> fit_lateral_profile(xodr::Road& road, const std::vector<double>& s,
                                        const std::vector<std::vector<LaneHeightSample>>& samples,
                                        const ConvertOptions& options);

}  // namespace corsa::ngii::detail
