#pragma once

#include <compare>
#include <cstdint>

namespace corsa::xodr {

/// One lane of a loaded map: road index (into MapData::roads), lane section index (into
/// Road::lane_sections) and lane id (> 0 left, < 0 right of the centre lane).
struct LaneRef {
  uint32_t road = 0;
  uint32_t section = 0;
  int32_t lane = 0;

  friend auto operator<=>(const LaneRef&, const LaneRef&) = default;
};

}  // namespace corsa::xodr
