#pragma once

// B2 surface line marks -> lane roadMarks (§9.8), C1 traffic lights -> dynamic signals (§14)
// with their controllers, A2 RoadType -> tunnel and bridge records (§13.13-14), placed through
// the link placements of the converted roads.

#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/ngii/convert.h"
#include "road_builder.h"

namespace corsa::ngii::detail {

struct Decorations {
  size_t road_marks = 0;  ///< roadMark records written (not counting "none" gaps)
  size_t signals = 0;
  size_t controllers = 0;  ///< signal controllers (one per intersection approach)
  size_t structures = 0;   ///< tunnel and bridge records
};

Decorations decorate(xodr::MapData& map, const std::vector<LinkPlacement>& placements,
                     const Layers& layers, const Origin& origin, Diagnostics& diagnostics);

}  // namespace corsa::ngii::detail
