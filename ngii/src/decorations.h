#pragma once

// B2 surface line marks -> lane roadMarks (§9.8), C1 traffic lights -> dynamic signals (§14),
// placed through the link placements of the converted roads.

#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/ngii/convert.h"
#include "road_builder.h"

namespace corsa::ngii::detail {

struct Decorations {
  size_t road_marks = 0;  ///< roadMark records written (not counting "none" gaps)
  size_t signals = 0;
};

Decorations decorate(xodr::MapData& map, const std::vector<LinkPlacement>& placements,
                     const Layers& layers, const Origin& origin, Diagnostics& diagnostics);

}  // namespace corsa::ngii::detail
