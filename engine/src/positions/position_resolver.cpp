#include "positions/position_resolver.h"

#include <cmath>
#include <numbers>
#include <type_traits>

#include "corsa/core/strings.h"
#include "corsa/xodr/lane_graph.h"
#include "corsa/xodr/map_parts.h"
#include "geometry/angle.h"
#include "lanes/lane_follow.h"
#include "positions/geo_reference.h"
#include "positions/position_common.h"
#include "positions/route_path.h"
#include "positions/trajectory_path.h"
#include "state/lenient.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

// Orientation of a position relative to an entity: by default the entity's own.
void orient_on_entity(xodr::WorldPose& pose, const Pose& reference,
                      const std::optional<xosc::Orientation>& orientation) {
  if (!orientation || orientation->type == xosc::ReferenceContext::kRelative) {
    const double dh = orientation ? orientation->h.value_or(0.0) : 0.0;
    const double dp = orientation ? orientation->p.value_or(0.0) : 0.0;
    const double dr = orientation ? orientation->r.value_or(0.0) : 0.0;
    pose.h = wrap_angle(reference.h + dh);
    pose.p = reference.p + dp;
    pose.r = reference.r + dr;
  } else {
    pose.h = orientation->h.value_or(0.0);
    pose.p = orientation->p.value_or(0.0);
    pose.r = orientation->r.value_or(0.0);
  }
}

ResolvedPosition world(const xosc::WorldPosition& p, const SimState& state) {
  ResolvedPosition out;
  out.pose = {p.x, p.y, p.z.value_or(0.0), p.h.value_or(0.0), p.p.value_or(0.0), p.r.value_or(0.0)};
  if (state.map != nullptr) {
    out.road = locate_point(*state.map, p.x, p.y, 0.0);
    if (out.road && !p.z) {
      out.pose.z = xodr::surface_pose(*state.map, out.road->road, out.road->s, out.road->t).z;
    }
  }
  return out;
}

ResolvedPosition finish_free(ResolvedPosition out, const SimState& state) {
  if (state.map != nullptr) {
    out.road = locate_point(*state.map, out.pose.x, out.pose.y, 0.0);
  }
  return out;
}

ResolvedPosition relative_world(const xosc::RelativeWorldPosition& p, const SimState& state) {
  const Entity& ref = need_entity(state, p.entity_ref, p.source);
  ResolvedPosition out;
  out.pose.x = ref.state().pose.x + p.dx;
  out.pose.y = ref.state().pose.y + p.dy;
  out.pose.z = ref.state().pose.z + p.dz.value_or(0.0);
  orient_on_entity(out.pose, ref.state().pose, p.orientation);
  return finish_free(out, state);
}

ResolvedPosition relative_object(const xosc::RelativeObjectPosition& p, const SimState& state) {
  const Entity& ref = need_entity(state, p.entity_ref, p.source);
  const double c = std::cos(ref.state().pose.h);
  const double s = std::sin(ref.state().pose.h);
  ResolvedPosition out;
  out.pose.x = ref.state().pose.x + c * p.dx - s * p.dy;
  out.pose.y = ref.state().pose.y + s * p.dx + c * p.dy;
  out.pose.z = ref.state().pose.z + p.dz.value_or(0.0);
  orient_on_entity(out.pose, ref.state().pose, p.orientation);
  return finish_free(out, state);
}

// What a relative Orientation of a lane position turns from: the lane's direction of travel, so
// that h = pi relative on a left lane of right-hand traffic faces +s, as esmini turns it for a
// LanePosition and a RelativeLanePosition given by dsLane (its reading of one given by ds turns
// from the road's +s: relative_lane below). 1.3
// LanePosition turns it from "the (s,t)-coordinate system of the target lane" ("counting from
// the tangent to the lane s-axis"), RelativeLanePosition from that "of the lane where the target
// position is located"; which way a lane's s-axis runs the standard leaves open (§6.3: "The
// definition of the s- and t-axes depends on the reference part of the road in use"), and a
// missing Orientation, "the relative reference context with Heading=Pitch=Roll=0", faces the
// lane's traffic only if it runs the way the lane is driven.
constexpr OrientationFrame kLanePositionFrame = OrientationFrame::kLane;

// A missing Orientation as "the relative reference context with Heading=Pitch=Roll=0" (1.3),
// so that in the road frame it faces the road's +s whatever the lane. RoadPosition and
// RelativeRoadPosition read so under both readings: 1.3 turns their relative heading from "the
// tangent to the road s-axis", the reference line's. esmini reads so every road-based position
// (its OSCPositionRoad turns a missing heading from the reference line, and its relative
// positions mark a missing heading relative); without it, orient_on_road faces the lane's
// traffic.
std::optional<xosc::Orientation> missing_as_relative(
    const std::optional<xosc::Orientation>& orientation) {
  if (orientation) {
    return orientation;
  }
  xosc::Orientation zero;
  zero.type = xosc::ReferenceContext::kRelative;
  return zero;
}

ResolvedPosition road(const xosc::RoadPosition& p, const SimState& state) {
  const xodr::Map& map = need_map(state, p.source, "RoadPosition");
  const uint32_t road_index = need_road(map, p.road_id, p.source);
  const double s = checked_s(state, map, road_index, p.s, p.source);
  return on_road(map, road_index, s, p.t, std::nullopt, missing_as_relative(p.orientation));
}

ResolvedPosition lane(const xosc::LanePosition& p, const SimState& state) {
  const xodr::Map& map = need_map(state, p.source, "LanePosition");
  const uint32_t road_index = need_road(map, p.road_id, p.source);
  const double s = checked_s(state, map, road_index, p.s, p.source);
  const int lane_id = parse_lane_id(p.lane_id, p.source, true);
  if (lane_id == 0) {
    // The centre lane (OpenDRIVE: lane 0, no width): on the reference line, plus the offset; the
    // entity then follows the lane it stands in.
    return on_road(map, road_index, s, p.offset.value_or(0.0), std::nullopt, p.orientation);
  }
  const double t = need_lane_center(map, road_index, s, lane_id, p.source) + p.offset.value_or(0.0);
  return on_road(map, road_index, s, t, lane_id, p.orientation, kLanePositionFrame);
}

// Where the reference entity is on the road (it must be on one).
const RoadCoordinates& need_road_coordinates(const Entity& ref, const std::string& name,
                                             const xosc::Source& source) {
  if (!ref.state().placed && ref.removed && ref.removed_road) {
    return *ref.removed_road;  // deleted: where it was (need_entity warned)
  }
  if (!ref.state().road) {
    fail(source, "entity '" + name +
                     "' is not on a road, so a road-relative position cannot "
                     "refer to it");
  }
  return *ref.state().road;
}

// Walks `ds` metres in road +s direction from (road, lane, s) along the lane graph, so that a
// relative position may reach past the end of the reference entity's road.
LaneFollow walk(const xodr::Map& map, const RoadCoordinates& from, double ds,
                const xosc::Source& source) {
  LaneFollow follow;
  if (!attach_to_lane(map, follow, from.road, from.s, from.t, from.lane,
                      map.reference(from.road, from.s).hdg)) {
    fail(source, "the reference entity's lane cannot be followed");
  }
  const AdvanceResult moved = advance_along_lanes(map, follow, ds, nullptr);
  if (moved.hit_end) {
    fail(source, "the position lies beyond the end of the road network (" + format_double(ds) +
                     " m along the lane of the reference entity)");
  }
  return follow;
}

ResolvedPosition relative_road(const xosc::RelativeRoadPosition& p, const SimState& state) {
  const xodr::Map& map = need_map(state, p.source, "RelativeRoadPosition");
  const Entity& ref = need_entity(state, p.entity_ref, p.source);
  const RoadCoordinates& rc = need_road_coordinates(ref, p.entity_ref, p.source);
  const LaneFollow at = walk(map, rc, p.ds, p.source);
  // Keep the reference entity's offset from its lane centre (turned with the road when the walk
  // crossed onto a road of opposite s direction), then add dt.
  const double t =
      followed_lane_center_t(map, at, at.lane).value_or(0.0) + at.dir * at.lateral + p.dt;
  return on_road(map, at.road, at.s, t, std::nullopt, missing_as_relative(p.orientation));
}

// Whether the reference entity faces the road's +s where it stands (its heading within a
// quarter turn of the reference line's).
bool reference_faces_plus_s(const xodr::Map& map, const Entity& ref, const RoadCoordinates& rc) {
  return std::cos(ref.state().pose.h - map.reference(rc.road, rc.s).hdg) > 0.0;
}

// esmini's reading of a RelativeLanePosition given by dsLane (`--semantics esmini`; its
// Position::EvaluateRelation in the direction mode along the lane): dsLane runs the way the
// reference entity's lane is driven (by the lane id's side and the road's traffic rule),
// whichever way the entity faces; dLane and offset keep their sign only for an entity facing +s
// on a right lane of right-hand traffic or facing -s on a left lane of left-hand traffic, and
// are mirrored otherwise.
struct EsminiAlongLaneSigns {
  double ds = 1.0;
  int lateral = 1;
};

EsminiAlongLaneSigns esmini_along_lane_signs(const xodr::Map& map, const Entity& ref,
                                             const RoadCoordinates& rc) {
  const bool left_hand = map.road(rc.road).rule == xodr::TrafficRule::kLeftHand;
  const bool lane_toward_minus_s = left_hand ? rc.lane < 0 : rc.lane > 0;
  const bool faces_plus_s = reference_faces_plus_s(map, ref, rc);
  const bool keep =
      (faces_plus_s && rc.lane < 0 && !left_hand) || (!faces_plus_s && rc.lane > 0 && left_hand);
  return {lane_toward_minus_s ? -1.0 : 1.0, keep ? 1 : -1};
}

// A RelativeLanePosition given by dsLane whose lane id plus dLane names no lane there (from lane
// 1 of a road with one lane a side, dLane 1: lane 2): the author's intent is the lane dLane lanes
// toward the reference entity's left, the centre lane not counted, as esmini reads every dLane
// of a dsLane position (esmini's star_position_types: from lane 1, facing -s, dLane 1 is lane
// -1). Read so, with a warning that names esmini's count, when that lane exists; otherwise the
// lane stays as the standard gives it, and need_lane_center reports it. Lane ids grow toward the
// left of an entity facing +s: for a reference facing +s esmini's count is the standard's but for
// the centre lane, which it skips outward, so a lane past the last one stays past (an error). For
// a reference facing -s the two counts run opposite ways and can meet: from lane 3 of three lanes
// a side, dLane -1 is lane 2 by the standard's count and dLane 1 is lane 2 by esmini's.
int lane_toward_reference_left(const xodr::Map& map, const Entity& ref, const RoadCoordinates& rc,
                               const LaneFollow& at, int lane_id,
                               const xosc::RelativeLanePosition& p, const SimState& state) {
  if (lane_id == 0 || lane_center_t(map, at.road, at.s, lane_id)) return lane_id;
  const int toward_left = reference_faces_plus_s(map, ref, rc) ? 1 : -1;
  const int left = lane_across_centre(at.lane, at.dir * toward_left * p.d_lane);
  if (left == 0 || !lane_center_t(map, at.road, at.s, left)) return lane_id;
  lenient(state, p.source,
          "road '" + map.road(at.road).id + "' has no lane " + std::to_string(lane_id) + " (lane " +
              std::to_string(at.lane) + " plus dLane " + std::to_string(p.d_lane) +
              ") at s = " + format_double(at.s),
          "lane " + std::to_string(left) +
              ", esmini's count: dLane lanes toward the reference entity's left, the centre "
              "lane not counted");
  return left;
}

ResolvedPosition relative_lane(const xosc::RelativeLanePosition& p, const SimState& state) {
  const xodr::Map& map = need_map(state, p.source, "RelativeLanePosition");
  const Entity& ref = need_entity(state, p.entity_ref, p.source);
  const RoadCoordinates& rc = need_road_coordinates(ref, p.entity_ref, p.source);
  double ds = p.ds.value_or(0.0);
  int d_lane = p.d_lane;
  double offset = p.offset.value_or(0.0);
  if (p.ds_lane) {
    // dsLane runs along the lane's centre line; on a curve that is longer or shorter than the
    // reference line by the factor (1 - t kappa).
    const auto center = lane_center_t(map, rc.road, rc.s, rc.lane).value_or(rc.t);
    const double kappa = xodr::reference_curvature(map, rc.road, rc.s);
    const double factor = 1.0 - center * kappa;
    ds = factor > 1e-6 ? *p.ds_lane / factor : *p.ds_lane;
    if (esmini_reading(state)) {
      const EsminiAlongLaneSigns signs = esmini_along_lane_signs(map, ref, rc);
      ds *= signs.ds;
      d_lane *= signs.lateral;
      offset *= signs.lateral;
    } else if (!reference_faces_plus_s(map, ref, rc)) {
      // 1.3: "Travel the lane center line difference dsLane from the position of the reference
      // entity in the direction the reference entity is facing". dLane ("adding dLane to that
      // of the reference entity's") and offset ("in the direction of the t-axis") do not turn
      // with the entity.
      ds = -ds;
    }
  }
  const LaneFollow at = walk(map, rc, ds, p.source);
  // 1.3 RelativeLanePosition: "Find the target lane by adding dLane to that of the reference
  // entity", dLane being "The deviation value between the laneId of the lane, where the
  // reference entity is located, and the target laneId": the lane id plus dLane, so that -1 + 1
  // is the centre lane 0, on the reference line. Lanes are not counted. esmini steps lanes across
  // the centre lane without counting it, along ds and dsLane alike (-1 + 1 is lane 1).
  int lane_id = at.lane + at.dir * d_lane;
  if (esmini_reading(state)) {
    lane_id = lane_across_centre(at.lane, at.dir * d_lane);
  } else if (p.ds_lane) {
    lane_id = lane_toward_reference_left(map, ref, rc, at, lane_id, p, state);
  }
  // The centre lane has no width nor direction: on the reference line (as a LanePosition on
  // lane 0), oriented as the reference's lane, in the lane the offset reaches.
  const double t =
      (lane_id == 0 ? 0.0 : need_lane_center(map, at.road, at.s, lane_id, p.source)) + offset;
  // esmini (`--semantics esmini`) turns a relative or missing heading of a position given by ds
  // from the target road's +s, whatever the lane and whichever way the reference entity drives;
  // given by dsLane, from the target lane's direction of travel, as the standard reading does
  // (esmini's Position::EvaluateRelation, direction modes along s and along the lane).
  const bool esmini_road_frame = esmini_reading(state) && !p.ds_lane;
  ResolvedPosition out =
      on_road(map, at.road, at.s, t, lane_id == 0 ? at.lane : lane_id,
              esmini_reading(state) ? missing_as_relative(p.orientation) : p.orientation,
              esmini_road_frame ? OrientationFrame::kRoad : kLanePositionFrame);
  if (lane_id == 0) {
    out.road->lane = map.lane_at(at.road, at.s, t);
  }
  return out;
}

ResolvedPosition geo(const xosc::GeoPosition& p, const SimState& state) {
  const xodr::Map& map = need_map(state, p.source, "GeoPosition");
  if (!p.latitude_deg || !p.longitude_deg) {
    fail(p.source, "GeoPosition needs a latitude and a longitude");
  }
  std::optional<Vec2> xy;
  try {
    xy = geo_to_map(state, map.data().header, *p.latitude_deg, *p.longitude_deg);
  } catch (const InputError& error) {
    fail(p.source, error.diagnostic().message);
  }
  if (!xy) {
    fail(p.source, "latitude " + format_double(*p.latitude_deg) + ", longitude " +
                       format_double(*p.longitude_deg) + " is outside the map's geoReference '" +
                       std::string(trim(map.data().header.geo_reference)) + "'");
  }
  ResolvedPosition out;
  out.pose.x = xy->x;
  out.pose.y = xy->y;
  out.road = locate_point(map, xy->x, xy->y, 0.0);
  if (out.road) {
    const xodr::WorldPose surface = map.world_pose(out.road->road, out.road->s, out.road->t);
    out.pose.z = surface.z;
    out.pose.h = surface.h;
    orient_on_road(
        out.pose, p.orientation,
        out.road->lane && lane_runs_backward(map, out.road->road, out.road->s, *out.road->lane));
  } else if (p.orientation) {
    out.pose.h = p.orientation->h.value_or(0.0);
  }
  if (p.altitude) {
    out.pose.z = *p.altitude;
  }
  return out;
}

}  // namespace

std::optional<RoadPoint> locate_point(const xodr::Map& map, double x, double y,
                                      double max_distance) {
  xodr::LocateOptions options;
  options.max_distance = max_distance;
  return road_point_within(map.locate(x, y, options), max_distance);
}

std::optional<RoadPoint> road_point_within(const std::optional<xodr::LanePosition>& located,
                                           double max_distance) {
  if (!located || located->distance > max_distance) {
    return std::nullopt;
  }
  return RoadPoint{located->road, located->s, located->t,
                   located->distance == 0.0 ? std::optional<int>(located->lane) : std::nullopt};
}

const std::string* referenced_entity(const xosc::Position& position) {
  return std::visit(
      [](const auto& p) -> const std::string* {
        using T = std::decay_t<decltype(p)>;
        if constexpr (std::is_same_v<T, xosc::RelativeWorldPosition> ||
                      std::is_same_v<T, xosc::RelativeObjectPosition> ||
                      std::is_same_v<T, xosc::RelativeRoadPosition> ||
                      std::is_same_v<T, xosc::RelativeLanePosition>) {
          return &p.entity_ref;
        } else {
          return nullptr;
        }
      },
      position.kind);
}

ResolvedPosition resolve_position(const xosc::Position& position, const SimState& state,
                                  std::optional<uint32_t> self) {
  return std::visit(
      [&](const auto& p) -> ResolvedPosition {
        using T = std::decay_t<decltype(p)>;
        if constexpr (std::is_same_v<T, xosc::WorldPosition>) {
          return world(p, state);
        } else if constexpr (std::is_same_v<T, xosc::RelativeWorldPosition>) {
          return relative_world(p, state);
        } else if constexpr (std::is_same_v<T, xosc::RelativeObjectPosition>) {
          return relative_object(p, state);
        } else if constexpr (std::is_same_v<T, xosc::RoadPosition>) {
          return road(p, state);
        } else if constexpr (std::is_same_v<T, xosc::RelativeRoadPosition>) {
          return relative_road(p, state);
        } else if constexpr (std::is_same_v<T, xosc::LanePosition>) {
          return lane(p, state);
        } else if constexpr (std::is_same_v<T, xosc::RelativeLanePosition>) {
          return relative_lane(p, state);
        } else if constexpr (std::is_same_v<T, xosc::RoutePosition>) {
          return resolve_route_position(p, state, self);
        } else if constexpr (std::is_same_v<T, xosc::GeoPosition>) {
          return geo(p, state);
        } else {
          return resolve_trajectory_position(p, state, self);
        }
      },
      position.kind);
}

}  // namespace corsa::engine::detail
