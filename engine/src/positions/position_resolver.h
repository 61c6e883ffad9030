#pragma once

// Position (OpenSCENARIO 1.3 §6.4) -> a pose in the map, against the current run state: World,
// RelativeWorld, RelativeObject, Road, RelativeRoad, Lane, RelativeLane, Route, Geo and
// Trajectory positions. Relative positions read the referenced entity's current state, so
// conditions resolve them anew on every evaluation.

#include <cstdint>
#include <optional>

#include "corsa/xodr/map.h"
#include "corsa/xosc/positions.h"

namespace corsa::engine::detail {

struct SimState;

/// A point in road coordinates (OpenDRIVE 1.8 §2.3).
struct RoadPoint {
  uint32_t road = 0;
  double s = 0.0;
  double t = 0.0;
  std::optional<int> lane;  ///< the lane meant (Lane positions) or containing the point
};

struct ResolvedPosition {
  xodr::WorldPose pose;           ///< world pose; heading per the Orientation rules
  std::optional<RoadPoint> road;  ///< road coordinates when the position is on a road
};

/// Resolves `position`. `self` is the entity the position is for (if any; e.g. TeleportAction's
/// actor), used where the standard refers to "the current entity". Throws corsa::InputError
/// located at the position for a missing road, lane or entity, s beyond a road, a referenced
/// entity without a position, an unsupported geoReference.
ResolvedPosition resolve_position(const xosc::Position& position, const SimState& state,
                                  std::optional<uint32_t> self);

/// Road coordinates of a world point (nearest lane within `max_distance`), or nothing.
std::optional<RoadPoint> locate_point(const xodr::Map& map, double x, double y,
                                      double max_distance);
/// The same from a map's answer already at hand (xodr::Map::locate): nothing when there is
/// none or it lies farther than max_distance (m).
std::optional<RoadPoint> road_point_within(const std::optional<xodr::LanePosition>& located,
                                           double max_distance);

/// The reference entity of a relative position, or nothing for absolute kinds.
const std::string* referenced_entity(const xosc::Position& position);

}  // namespace corsa::engine::detail
