#pragma once

// Paved ground beside a lane that continues into a narrower one. Where a lane ends and the lane
// it is joined to starts narrower (or ends narrower before a wider one starts), the marks of the
// two links give widths that differ at the joint: a lane flaring where the next lanes split
// off, a road edge that steps at a lane-count change, a lane at the tip of a painted median.
// Moving either lane's borders to meet the other's would take its centre off its link (the
// lanes differ in width on one side, or the narrower one has a lane of its road beside it; see
// lane_joints.h), so the ground the wider lane's end covers beyond the narrower road's edge was
// left unpaved. Here the narrower road gets a `shoulder` lane outside its outermost lane on that
// side (OpenDRIVE 1.8 §9.5.1 lane types: paved, not for traffic; no road mark), as wide as the
// step at the joint and narrowing to zero along a smoothstep (§9.5.2 lane width, zero slope at
// both ends), so the paved surface is continuous while every lane centre stays on its link.

#include <cstddef>

#include "corsa/xodr/model.h"

namespace corsa::ngii::detail {

/// Adds the shoulder lanes to `map`'s roads (one lane section each; others are left alone) at
/// joined lane ends whose end edge reaches more than 5 cm beyond the outer edge of every road
/// joined there, over ground no lane covers, the two roads' headings within 10 degrees. Each
/// carries `<userData code="ngii:mouth-fill">` naming the lane end it continues. Returns how
/// many were added.
size_t fill_lane_mouths(xodr::MapData& map);

}  // namespace corsa::ngii::detail
