#pragma once

// Position and its ten kinds (OpenSCENARIO 1.3 §6.4 / XSD "Position"). Metres and radians;
// headings counter-clockwise from +x; road/lane coordinates as in OpenDRIVE (s along the
// reference line, t and lane ids positive to the left).

#include <memory>
#include <optional>
#include <string>
#include <variant>

#include "corsa/xosc/common.h"
#include "corsa/xosc/enums.h"

namespace corsa::xosc {

struct Route;
struct Trajectory;

/// Orientation: absolute, or relative to the reference (road, lane, entity) when type is
/// kRelative. Unset angles are 0.
struct Orientation {
  std::optional<double> h;  ///< heading, rad
  std::optional<double> p;  ///< pitch, rad
  std::optional<double> r;  ///< roll, rad
  std::optional<ReferenceContext> type;
  Source source;
};

struct WorldPosition {
  double x = 0.0;
  double y = 0.0;
  std::optional<double> z;
  std::optional<double> h;
  std::optional<double> p;
  std::optional<double> r;
  Source source;
};

/// Offset (dx, dy, dz) in world axes from an entity's reference point.
struct RelativeWorldPosition {
  std::string entity_ref;
  double dx = 0.0;
  double dy = 0.0;
  std::optional<double> dz;
  std::optional<Orientation> orientation;
  Source source;
};

/// Offset in the referenced entity's local frame (x forward, y left).
struct RelativeObjectPosition {
  std::string entity_ref;
  double dx = 0.0;
  double dy = 0.0;
  std::optional<double> dz;
  std::optional<Orientation> orientation;
  Source source;
};

struct RoadPosition {
  std::string road_id;
  double s = 0.0;
  double t = 0.0;
  std::optional<Orientation> orientation;
  Source source;
};

struct RelativeRoadPosition {
  std::string entity_ref;
  double ds = 0.0;
  double dt = 0.0;
  std::optional<Orientation> orientation;
  Source source;
};

struct LanePosition {
  std::string road_id;
  std::string lane_id;  ///< OpenDRIVE lane id as text (an integer in practice)
  double s = 0.0;
  std::optional<double> offset;  ///< lateral offset from the lane centre, m
  std::optional<Orientation> orientation;
  Source source;
};

/// Lane-relative to an entity: dLane lanes over, ds along the road or dsLane along the lane.
struct RelativeLanePosition {
  std::string entity_ref;
  int d_lane = 0;
  std::optional<double> ds;
  std::optional<double> ds_lane;
  std::optional<double> offset;
  std::optional<Orientation> orientation;
  Source source;
};

struct PositionOfCurrentEntity {
  std::string entity_ref;
  Source source;
};
struct PositionInRoadCoordinates {
  double path_s = 0.0;
  double t = 0.0;
  Source source;
};
struct PositionInLaneCoordinates {
  std::string lane_id;
  std::optional<double> lane_offset;
  double path_s = 0.0;
  Source source;
};
using InRoutePosition =
    std::variant<PositionOfCurrentEntity, PositionInRoadCoordinates, PositionInLaneCoordinates>;

/// Position along a route. The route is shared (it may come from a catalog) and read-only.
struct RoutePosition {
  std::shared_ptr<const Route> route;
  std::optional<Orientation> orientation;
  InRoutePosition in_route;
  Source source;
};

/// Geographic position. 1.2 spellings are in degrees; the 1.0/1.1 latitude/longitude (radians)
/// are converted to degrees on load (with a deprecation warning).
struct GeoPosition {
  std::optional<double> latitude_deg;
  std::optional<double> longitude_deg;
  std::optional<double> altitude;  ///< m
  std::optional<int> vertical_road_selection;
  std::optional<Orientation> orientation;
  Source source;
};

/// Position at arc length s (and lateral t) along a trajectory.
struct TrajectoryPosition {
  std::shared_ptr<const Trajectory> trajectory;
  double s = 0.0;
  std::optional<double> t;
  std::optional<Orientation> orientation;
  Source source;
};

using PositionKind =
    std::variant<WorldPosition, RelativeWorldPosition, RelativeObjectPosition, RoadPosition,
                 RelativeRoadPosition, LanePosition, RelativeLanePosition, RoutePosition,
                 GeoPosition, TrajectoryPosition>;

/// Position: exactly one of the kinds above.
struct Position {
  PositionKind kind;
  Source source;
};

}  // namespace corsa::xosc
