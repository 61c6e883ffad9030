#pragma once

// Road marks (OpenDRIVE 1.8 §11.8 <roadMark>) as painted lines along the lane borders: what the
// road mesh turns into thin strips, and what the map renderer draws.

#include <cstdint>
#include <string_view>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/xodr/road_mesh.h"

namespace corsa::xodr {

class Map;

/// One painted line: a solid line, one dash of a broken line, or one of the two lines of a
/// double mark, sampled along s like the lane surface under it (same chord tolerance).
struct MarkLine {
  uint32_t road_index = 0;
  int32_t lane_id = 0;  ///< the lane whose outer border carries the mark (0: the centre lane)
  LaneType lane_type = LaneType::kNone;  ///< that lane's type
  bool in_junction = false;
  MarkColor color = MarkColor::kWhite;
  double width = 0.12;  ///< m
  /// Points on the surface (lane height included) lifted by the mark's height or
  /// MeshOptions::mark_lift: the line's middle and its left (+t) and right (-t) edges, all the
  /// same length, in s order (at a jump of the cross-section two points 1e-7 m apart in s).
  std::vector<Vec3> center;
  std::vector<Vec3> left;
  std::vector<Vec3> right;
  std::vector<double> s;  ///< road s of each point (m)
};

/// Keyword road mark types (§11.8 e_roadMarkType) and how they are drawn. Dash lengths for
/// `broken` are 3 m of paint and 9 m of gap, counted along the reference line from the start of
/// the record; double lines are `width` apart, the first named one inside (centre lane: left).
/// `botts dots` are 0.15 m dots every 1.2 m. `none`, `grass`, `curb` and `edge` are not paint
/// and give nothing; `custom` and unknown types give nothing and a warning (the <type>/<line>
/// details of custom marks are not in the model).
std::vector<MarkLine> build_road_marks(const Map& map, const MeshOptions& options,
                                       corsa::Diagnostics& diagnostics);

/// Colour of a roadMark record's `color` text ("standard" is white); kNone for a name it does
/// not know.
MarkColor mark_color_from_name(std::string_view name);

}  // namespace corsa::xodr
