#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <variant>

#include "corsa/xodr/map_parts.h"
#include "geometry/angle.h"
#include "lanes/lane_follow.h"
#include "motion/controller.h"
#include "motion/pose_command.h"
#include "positions/position_resolver.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {

namespace {

// The inputs of lane_pose (the lane graph node follows from road, section and lane).
bool same_lane_position(const LaneFollow& a, const LaneFollow& b) {
  return a.on_road == b.on_road && a.road == b.road && a.section == b.section && a.lane == b.lane &&
         a.dir == b.dir && same_bits(a.s, b.s) && same_bits(a.lateral, b.lateral) &&
         same_bits(a.heading_offset, b.heading_offset);
}

}  // namespace

void update_pose_from_lane(Entity& entity, const xodr::Map& map,
                           std::vector<xodr::LaneSpan>& scratch) {
  update_pose_from_lane(entity, entity.lane_pose_memo, map, scratch);
}

[[gnu::hot]] void update_pose_from_lane(EntityMotion& entity, LanePoseMemo& memo,
                                        const xodr::Map& map,
                                        std::vector<xodr::LaneSpan>& scratch) {
  // The same lane position gives the same pose (lane_pose is a function of it and the map);
  // the memo counts only while nothing else has moved the entity since.
  if (memo.valid && same_lane_position(memo.from, entity.lane) &&
      same_bits(memo.pose, entity.state().pose) && same_bits(memo.road, entity.state().road)) {
    return;
  }
  const LanePose lp = lane_pose_of(map, entity.lane, scratch);
  entity.write_state().pose = {lp.pose.x, lp.pose.y, lp.pose.z, lp.pose.h, lp.pose.p, lp.pose.r};
  if (lp.lane_at) {
    entity.write_state().road =
        RoadCoordinates{entity.lane.road, entity.lane.section, *lp.lane_at, entity.lane.s, lp.t};
  } else {
    entity.write_state().road.reset();
  }
  memo.valid = true;
  memo.from = entity.lane;
  memo.pose = entity.state().pose;
  memo.road = entity.state().road;
}

void update_road_from_pose(Entity& entity, const xodr::Map* map) {
  update_road_from_pose(entity, entity.point_memo, map);
}

void update_road_from_pose(EntityMotion& entity, PointLocateMemo& memo, const xodr::Map* map) {
  if (map == nullptr) {
    entity.write_state().road.reset();
    return;
  }
  update_road_from_located(entity,
                           locate_near(memo, *map, entity.state().pose.x, entity.state().pose.y));
}

[[gnu::hot]] void update_road_from_located(EntityMotion& entity,
                                           const std::optional<xodr::LanePosition>& located) {
  if (located && located->distance == 0.0) {
    entity.write_state().road =
        RoadCoordinates{located->road, located->section, located->lane, located->s, located->t};
  } else {
    entity.write_state().road.reset();
  }
}

const std::optional<xodr::LanePosition>& locate_near(Entity& entity, const xodr::Map& map, double x,
                                                     double y) {
  return locate_near(entity.point_memo, map, x, y);
}

[[gnu::hot]] const std::optional<xodr::LanePosition>& locate_near(PointLocateMemo& memo,
                                                                  const xodr::Map& map, double x,
                                                                  double y) {
  if (clear_of_lanes_at(memo, x, y)) {
    return memo.located;  // still clear of every lane (a NaN point fails the comparisons)
  }
  if (!memo.valid || !same_bits(memo.x, x) || !same_bits(memo.y, y)) {
    constexpr double kMaxDistance = 0.5;
    // How far an entity off the road may move before it is searched for again: a few steps
    // of a car (the bound costs about one search of a square this much wider).
    constexpr double kClearReach = 2.0;
    xodr::LocateOptions options;
    options.max_distance = kMaxDistance;
    memo.located = map.locate(x, y, options);
    memo.x = x;
    memo.y = y;
    memo.valid = true;
    memo.surface_valid = false;
    memo.clear = memo.located ? 0.0 : map.clear_of_lanes(x, y, kMaxDistance, kClearReach);
  }
  return memo.located;
}

const xodr::SurfacePose* surface_near(Entity& entity, const xodr::Map& map, double x, double y,
                                      double max_distance) {
  PointLocateMemo& memo = entity.point_memo;
  const auto at = road_point_within(locate_near(memo, map, x, y), max_distance);
  if (!at) {
    return nullptr;
  }
  if (!memo.surface_valid) {
    memo.surface = xodr::surface_pose(map, at->road, at->s, at->t);
    memo.surface_valid = true;
  }
  return &memo.surface;
}

namespace {

// Curvature (1/m) of the reference line at s: read from lines, arcs and spirals directly (the
// common records; cheaper than evaluating the reference point), evaluated for the cubics.
[[gnu::hot]] double curvature_at(const xodr::Map& map, uint32_t road, double s) {
  const xodr::Geometry* record = map.plan_record_at(road, s);
  if (record == nullptr) {
    return map.road(road).plan_view.empty() ? 0.0 : xodr::reference_curvature(map, road, s);
  }
  const xodr::Geometry& g = *record;
  if (std::holds_alternative<xodr::LineGeometry>(g.shape)) {
    return 0.0;
  }
  if (const auto* arc = std::get_if<xodr::ArcGeometry>(&g.shape)) {
    return arc->curvature;
  }
  if (const auto* spiral = std::get_if<xodr::SpiralGeometry>(&g.shape)) {
    const double f = g.length > 0.0 ? std::clamp((s - g.s) / g.length, 0.0, 1.0) : 0.0;
    return spiral->curv_start + f * (spiral->curv_end - spiral->curv_start);
  }
  return xodr::reference_curvature(map, road, s);
}

// Path length per metre of reference s (1 - k t) where the entity is, kept within [0.2, 5] so
// that a point near or beyond the centre of curvature of a tight curve cannot stall or fling it.
// Outside every lane of the road (a lateral offset beyond its outer lane, e.g. a lane change that
// a route carries onto a connecting road with fewer lanes) t comes from the followed lane.
double path_scale(const xodr::Map& map, const EntityMotion& entity, CurvatureMemo* memo) {
  const bool located = entity.state().road && entity.state().road->road == entity.lane.road;
  if (!located && entity.state().road) {
    return 1.0;
  }
  const uint32_t road = entity.lane.road;
  const double s = entity.lane.s;
  const double k = memo != nullptr ? memo->at(road, s, [&] { return curvature_at(map, road, s); })
                                   : curvature_at(map, road, s);
  if (k == 0.0) {
    return 1.0;
  }
  const double t = located ? entity.state().road->t : followed_t(map, entity.lane);
  return std::clamp(1.0 - k * t, 0.2, 5.0);
}

// The step's travel along the lane: what is left of `distance` beside the lateral change, so
// that the path (along and across) is as long as the speed gives. The speed is the entity's
// (1.3 SpeedCondition compares "the total speed" unless a direction is given); the lateral
// actions give the offset over time or distance and leave the travel along the lane open
// (esmini's reading). A lateral change of at least `distance`, a jump rather than a motion at
// the speed, leaves it whole.
double along_lane(const EntityMotion& entity, double distance) {
  const double lateral = entity.lateral_command - entity.lane.lateral;
  if (lateral == 0.0 || std::abs(lateral) >= std::abs(distance)) {
    return distance;
  }
  return std::copysign(std::sqrt(distance * distance - lateral * lateral), distance);
}

// Whether `lane` advanced by along / scale, for any scale path_scale gives ([0.2, 5]), stops at
// once at a lane end with nothing beyond: the advance then leaves the lane where it is and
// travels 0 whatever the scale (advance_along_lanes' first lane end, with no room before it).
// `along` is far enough from 0 that no such quotient rounds to 0.
bool at_dead_end(const xodr::Map& map, const LaneFollow& lane, double along) {
  if (!(std::abs(along) > 1e-300)) {
    return false;
  }
  const int dir = along > 0.0 ? lane.dir : -lane.dir;
  const xodr::LaneGraph& graph = map.lane_graph();
  const auto& info = graph.info(lane.node);
  const double boundary = dir > 0 ? info.s_end : info.s_start;
  return std::abs(boundary - lane.s) == 0.0 && graph.ends(lane.node, dir < 0).empty();
}

// Whether a step of `along` metres (no lateral change asked for) leaves the lane position as it
// is: a travel far below an ulp of s, as of a speed decaying toward 0 that some action keeps
// setting (a continuous relative SpeedAction behind a slowing entity), which advance_along_lanes
// would add to s without changing it. `reach`, 8 |along|, bounds that travel (|along| / scale
// for any scale path_scale gives, [0.2, 5]) and what it is scaled back to; where s, the
// distance driven and the odometer absorb the reach, they absorb the travel (rounding is
// monotonic), and the heading keeps its offset (below 1e-9 m). |along| above 1e-300 keeps the
// travel from rounding to 0, so the step is no stand (it is not at a lane end either, the room
// before it being at least the reach). Such a step changes nothing but what follows from the
// speed, so the lane and the scale need no asking.
bool creeps_in_place(const xodr::Map& map, const EntityMotion& entity, double along) {
  const LaneFollow& lane = entity.lane;
  const double reach = 8.0 * std::abs(along);
  if (!(std::abs(along) > 1e-300 && reach <= 1e-9) ||
      entity.lateral_command - lane.lateral != 0.0) {
    return false;
  }
  const double toward = along > 0.0 ? lane.dir : -lane.dir;
  if (lane.s + toward * reach != lane.s ||
      entity.longitudinal_distance + reach != entity.longitudinal_distance ||
      entity.state().odometer + reach != entity.state().odometer) {
    return false;
  }
  const auto& info = map.lane_graph().info(lane.node);
  return reach <= std::abs((toward > 0.0 ? info.s_end : info.s_start) - lane.s);
}

// The still step memo (Entity::still_step): the entity's motion, copied by its fields
// (assignment through the base, so nothing of Entity placed in EntityMotion's tail is copied)
// and compared field by field.
void take_still_step(EntityMotion& memo, const EntityMotion& motion) { memo = motion; }

// same_bits_beside_state (state/sim_state.h) in one test of the bits, without a branch per
// field: the lane position, the four doubles from speed_command to lateral_acceleration,
// end_of_road and the chooser, as 14 words of 8 bytes whose padding bytes (never written, never
// the same) and the count of the state's writes are masked off.
bool same_bits_beside_state_masked(const EntityMotion& a, const EntityMotion& b) {
  static_assert(sizeof(EntityMotion) == 248, "add the new field to the masks");
  // The masks read the layout little-endian, a bool as one byte of 0 or 1.
  static_assert(std::endian::native == std::endian::little && sizeof(bool) == 1);
  static_assert(sizeof(LaneFollow) == 64 && offsetof(LaneFollow, road) == 4 &&
                    offsetof(LaneFollow, section) == 8 && offsetof(LaneFollow, lane) == 12 &&
                    offsetof(LaneFollow, node) == 16 && sizeof(xodr::LaneNode) == 4 &&
                    offsetof(LaneFollow, s) == 24 && offsetof(LaneFollow, dir) == 32 &&
                    offsetof(LaneFollow, lateral) == 40 &&
                    offsetof(LaneFollow, heading_offset) == 48 &&
                    offsetof(LaneFollow, frame_shift) == 56,
                "the masks follow LaneFollow's layout");
  // (offsetof of a type with private members, which GCC gives as for any other.)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Winvalid-offsetof"
  constexpr size_t kLane = offsetof(EntityMotion, lane);
  static_assert(kLane % 8 == 0 && offsetof(EntityMotion, speed_command) == kLane + 64 &&
                    offsetof(EntityMotion, lateral_acceleration) == kLane + 88 &&
                    offsetof(EntityMotion, end_of_road) == kLane + 96 &&
                    offsetof(EntityMotion, chooser) == kLane + 104 &&
                    kLane + 112 == sizeof(EntityMotion),
                "the masks follow EntityMotion's layout");
#pragma GCC diagnostic pop
  constexpr uint64_t kAll = ~uint64_t{0};
  constexpr uint64_t kMasks[14] = {
      0xFFFFFFFF000000FFull,  // on_road, (padding), road
      kAll,                   // section, lane
      0x00000000FFFFFFFFull,  // node, (padding)
      kAll,                   // s
      0x00000000FFFFFFFFull,  // dir, (padding)
      kAll,                   // lateral
      kAll,                   // heading_offset
      kAll,                   // frame_shift
      kAll,                   // speed_command
      kAll,                   // lateral_command
      kAll,                   // longitudinal_distance
      kAll,                   // lateral_acceleration
      0x00000000000000FFull,  // end_of_road, (padding, the count of the state's writes)
      kAll,                   // chooser
  };
  const auto* pa = reinterpret_cast<const unsigned char*>(&a) + kLane;
  const auto* pb = reinterpret_cast<const unsigned char*>(&b) + kLane;
  uint64_t diff = 0;
  for (size_t i = 0; i < 14; ++i) {
    uint64_t wa = 0, wb = 0;
    std::memcpy(&wa, pa + 8 * i, 8);
    std::memcpy(&wb, pb + 8 * i, 8);
    diff |= (wa ^ wb) & kMasks[i];
  }
  return diff == 0;
}

// Whether the entity holds the memo again: its state is the memo's while the state's count of
// writes is the one the memo was confirmed at (Entity::still_step_changes), and is compared
// otherwise (a write that changed nothing); the rest of the motion is compared.
bool holds_still_step(const Entity& entity) {
  const EntityMotion& memo = entity.still_step;
  return (entity.state_changes() == entity.still_step_changes ||
          same_bits(memo.state(), entity.state())) &&
         same_bits_beside_state_masked(memo, entity);
}

}  // namespace

[[gnu::hot]] void DefaultController::step(Entity& entity, const MotionContext& context) const {
  if (entity.pose_command) {
    move_to_pose_command(entity, context);
    return;
  }
  // A step that would change nothing: the last one changed nothing, and nothing has changed
  // the entity since.
  if (entity.still_step_valid && holds_still_step(entity)) {
    return;
  }
  // Only an entity already standing on its lane can take a step that changes nothing.
  const bool may_stand =
      entity.state().speed == 0.0 && entity.lane.on_road && context.map != nullptr;
  entity.still_step_valid = false;
  if (may_stand) {
    take_still_step(entity.still_step, entity);
  }
  bool stood = false;
  step_entity(entity, MapMemos{entity.lane_pose_memo, entity.point_memo}, context, stood);
  entity.still_step_valid = may_stand && stood && same_bits(entity.still_step, entity);
  entity.still_step_changes = entity.state_changes();
}

[[gnu::hot]] void DefaultController::step_entity(EntityMotion& entity, MapMemos memos,
                                                 const MotionContext& context, bool& stood) const {
  EntityState& state = entity.write_state();
  const double dt = context.dt;
  const double v0 = state.speed;
  double v1 = entity.speed_command;
  // A step travels its end speed times dt (semi-implicit Euler, as esmini and most players
  // integrate). The standard gives the speed over time (TransitionDynamics) and leaves how a
  // simulator turns it into positions to the simulator; the trapezoid rule would be the exact
  // integral of the speed's linear change within a step, dt / 2 per m/s gained shorter.
  const double distance = v1 * dt;
  const double h0 = state.pose.h;
  double path = std::abs(distance);
  double lateral_change = 0.0;
  if (entity.lane.on_road && context.map != nullptr) {
    LaneFollow& lane = entity.lane;
    // The speed is along the entity's own path, s along the reference line: at t metres from a
    // reference line of curvature k the path is (1 - k t) times as long as s (OpenDRIVE 1.8
    // §9.3, lanes run parallel to the reference line), so a car in the outer lane of a turn does
    // not drive faster than its speed.
    // Standing still needs no scale (and on a cubic reference line it costs an evaluation), nor
    // does a step that cannot leave a lane end it stands at (the speed asked for stays asked
    // for there: such an entity tries every step).
    const double along = along_lane(entity, distance);
    // Creeping in place, the step travels `along` as far as anything it writes can tell.
    const bool creeps = creeps_in_place(*context.map, entity, along);
    const double scale = creeps || distance == 0.0 || at_dead_end(*context.map, lane, along)
                             ? 1.0
                             : path_scale(*context.map, entity, context.curvatures);
    const double shift_before = lane.frame_shift;
    const AdvanceResult moved =
        creeps ? AdvanceResult{along}
               : advance_along_lanes(*context.map, lane, along / scale, entity.chooser);
    // Carried on from a neighbouring lane's end: the offset asked for moves with the lane frame.
    entity.lateral_command += lane.frame_shift - shift_before;
    const double travelled = moved.travelled * scale;
    lateral_change = entity.lateral_command - lane.lateral;
    if (std::abs(travelled) > 1e-9) {
      // The heading turns away from the lane by the angle of the path the lateral motion draws;
      // standing entities keep theirs (a car parked at an angle stays so). Without a lateral
      // motion the angle is the quotient's +-0 (atan(+-0) = +-0), which skips the library call.
      const double slope = lateral_change / travelled;
      lane.heading_offset = slope == 0.0 ? slope : std::atan(slope);
    }
    lane.lateral = entity.lateral_command;
    // At a lane end without successor the entity stops; it stays "at the end of the road"
    // until it moves away from it. The speed it was asked for stays asked for (no action changed
    // it): put elsewhere (a TeleportAction), it drives on at that speed, as esmini's
    // lane_change_simple expects of its car after each teleport back from the road's end.
    entity.end_of_road = moved.hit_end || (entity.end_of_road && moved.travelled == 0.0);
    if (moved.hit_end) {
      v1 = 0.0;
    }
    // Moved neither along the lane (asked for no speed, or stopped at a lane end) nor across.
    stood = moved.travelled == 0.0 && lateral_change == 0.0;
    // hypot(x, +-0) is |x| exactly: the library call only for a lateral motion.
    path = lateral_change == 0.0 ? std::abs(travelled) : std::hypot(travelled, lateral_change);
    entity.longitudinal_distance += std::abs(travelled);
    update_pose_from_lane(entity, memos.lane_pose, *context.map, *context.scratch);
  } else if (context.stand_without_roads) {
    v1 = 0.0;
  } else {
    state.pose.x += std::cos(state.pose.h) * distance;
    state.pose.y += std::sin(state.pose.h) * distance;
    entity.longitudinal_distance += std::abs(distance);
    if (distance != 0.0) {
      update_road_from_pose(entity, memos.point, context.map);
    }
  }
  state.acceleration = (v1 - v0) / dt;
  state.speed = v1;
  const double lateral_speed = lateral_change / dt;
  entity.lateral_acceleration = (lateral_speed - state.lateral_speed) / dt;
  state.lateral_speed = lateral_speed;
  state.yaw_rate = remainder_full_turn(state.pose.h - h0) / dt;
  state.odometer += path;
}

}  // namespace corsa::engine::detail
