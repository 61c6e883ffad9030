#pragma once

// The NGII feature layers (layers.h FeatureLayer) -> OpenDRIVE, each on the road of the A2 link
// it names (LinkID), else on the nearest road within 30 m:
// - B1 safety signs -> static signals (country KR, type = the B1 class, value = a speed limit
//   in Remark) at the sign board's centre;
// - B3 surface marks -> objects with the mark's outline (road corners): crosswalks (Type 5)
//   with zebra markings, arrows (Type 1) as roadMark objects with the NGII Kind as subtype;
// - C3 barriers -> railing / barrier objects with an open outline along the line, one per road
//   the line runs beside, heights by type (guard rail 0.8 m, kerb 0.15 m, wall 2 m, ...);
// - C4 speed bumps -> obstacle objects (subtype speedBump, 0.1 m) with the bump's outline;
// - C6 posts -> pole objects (signal posts 6 m, sign posts 3 m);
// - A3 sections with RoadType 2-5 -> tunnel / bridge records over the s ranges inside them;
// - A4 subsidiary sections, A5 parking lots -> patch / parkingSpace objects with outlines;
// - B2 stop lines (Kind 530, across the lanes, so no lane roadMark) -> roadMark objects.
// OpenDRIVE 1.8 §13 (objects, outlines, markings, tunnels, bridges), §14 (signals).

#include <vector>

#include "corsa/ngii/convert.h"
#include "road_builder.h"

namespace corsa::ngii::detail {

struct FeatureCounts {
  size_t signals = 0;     ///< B1 signs placed
  size_t objects = 0;     ///< objects made (B3, C3, C4, C6, A4, A5, B2 stop lines)
  size_t structures = 0;  ///< tunnel and bridge records from A3
};

FeatureCounts place_features(xodr::MapData& map, const std::vector<LinkPlacement>& placements,
                             const Layers& layers, const Origin& origin);

}  // namespace corsa::ngii::detail
