#pragma once

// The lanes a car follower will drive next, as the acc controller looks along them
// (controllers/acc_controller.cpp): its own lane from where it is, then each lane its chooser
// takes at a lane end, up to the sensor range.

#include <array>
#include <cstddef>
#include <cstdint>

#include "corsa/xodr/lane_graph.h"

namespace corsa::xodr {
class Map;
}

namespace corsa::engine::detail {

inline constexpr size_t kMaxPieces = 16;  ///< lane pieces looked along (zero-length lanes too)

/// One lane (of one lane section) on the path ahead: road coordinates of where the path enters
/// it, the direction it is driven in, and the path distance (m, along s) at the entry.
/// No member initialisers: a LanePath is made for every vehicle every step and sets only the
/// pieces it uses (aggregate initialisation sets every field).
struct PathPiece {
  uint32_t road;
  uint32_t section;
  int lane;
  xodr::LaneNode node;
  double s_entry;
  int dir;
  double distance;
};

struct LanePath {
  std::array<PathPiece, kMaxPieces> pieces;  ///< the first `count` are set, the rest unset
  size_t count = 0;
};

struct LaneFollow;

/// The path the acc controller looks along from `lane` for a vehicle without a route (the
/// straightest lane at each lane end), up to its sensor range: where a vehicle put there will
/// drive (controllers/acc_controller.cpp).
LanePath lane_path_of(const xodr::Map& map, const LaneFollow& lane);

}  // namespace corsa::engine::detail
