#pragma once

// Display colours of lane types and road marks, shared by the mesh files' materials and the
// top-down map picture so that both look alike.

#include <cstdint>

#include "corsa/xodr/model.h"
#include "corsa/xodr/road_mesh.h"

namespace corsa::xodr {

struct Rgb {
  uint8_t r = 0;
  uint8_t g = 0;
  uint8_t b = 0;
};

/// Surface colour of a lane type: driving lanes asphalt grey, sidewalks light paving, shoulders
/// and borders a paler grey, biking lanes red-brown, parking blue-grey, medians and grass-like
/// types green, rail and tram brown.
Rgb lane_type_color(LaneType type);
/// Paint colour of a road mark ("standard" and white are off-white, yellow is amber).
Rgb mark_color_rgb(MarkColor color);

}  // namespace corsa::xodr
