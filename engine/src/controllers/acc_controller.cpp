// The `acc` controller: adaptive cruise control on top of the default controller. The set speed
// is what the actions command; when a vehicle drives ahead on the lane path the follower will
// take, the speed is held below that so as to keep a time gap (constant time-gap policy, e.g.
// Rajamani, Vehicle Dynamics and Control, §5.3), within the vehicle's Performance limits.
//
// "Ahead" is along the lanes the default controller will drive next (OpenDRIVE 1.8 §9.4 lane
// linkage, §10 junction connections), chosen at each lane end as the controller will choose
// (the entity's route, else the straightest successor), up to the sensor range: a vehicle just
// across a road link or inside the junction's connecting lane is a leader too.
//
// The others are seen as they were when the step began (controllers/follow_view.h): every
// follower of a step reads the same world, whatever the order it is moved in.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "controllers/controllers.h"
#include "controllers/follow_view.h"
#include "lanes/lane_follow.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

constexpr double kTimeGap = 1.5;         // s
constexpr double kStandstill = 3.0;      // m, bumper to bumper at rest
constexpr double kRange = 200.0;         // m, sensor range
constexpr double kReach = 1.5 * kRange;  // m, straight-line bound of what may be within range
constexpr double kGapGain = 0.25;        // 1/s^2
constexpr double kSpeedGain = 0.8;       // 1/s
constexpr double kDefaultLimit = 6.0;    // m/s^2 when the Performance gives none
constexpr size_t kMaxPieces = 16;        // lane pieces looked along (zero-length lanes included)

struct Leader {
  double gap = std::numeric_limits<double>::infinity();  ///< m, bumper to bumper
  double speed = 0.0;
};

// One lane (of one lane section) on the path ahead: road coordinates of where the path enters
// it, the direction it is driven in, and the path distance (m, along s) at the entry.
struct PathPiece {
  uint32_t road = 0;
  uint32_t section = 0;
  int lane = 0;
  xodr::LaneNode node = xodr::kNoLane;
  double s_entry = 0.0;
  int dir = 1;
  double distance = 0.0;
};

struct LanePath {
  std::array<PathPiece, kMaxPieces> pieces;  // the first `count` are set
  size_t count = 0;
};

// The lanes the entity will follow from where it is, up to kRange metres ahead; the lanes after
// its own come from `ahead` (extended, or started afresh when the entity's lane, direction or
// chooser changed).
LanePath path_ahead(const xodr::Map& map, const Entity& me, LanesAhead& ahead) {
  if (ahead.node != me.lane.node || ahead.dir != me.lane.dir || ahead.chooser != me.chooser) {
    ahead.node = me.lane.node;
    ahead.dir = me.lane.dir;
    ahead.chooser = me.chooser;
    ahead.route = me.route;
    ahead.next.clear();
    ahead.dead_end = false;
  }
  LanePath path;
  LaneFollow follow = me.lane;
  const auto& graph = map.lane_graph();
  double distance = 0.0;
  for (size_t k = 0; path.count < kMaxPieces; ++k) {
    path.pieces[path.count++] = PathPiece{follow.road, follow.section, follow.lane, follow.node,
                                          follow.s,    follow.dir,     distance};
    const auto& info = graph.info(follow.node);
    const double boundary = follow.dir > 0 ? info.s_end : info.s_start;
    distance += std::abs(boundary - follow.s);
    if (distance >= kRange) {
      break;
    }
    if (k < ahead.next.size()) {
      follow = ahead.next[k];
      continue;
    }
    const auto ends = graph.ends(follow.node, follow.dir < 0);
    if (ahead.dead_end || ends.empty()) {
      ahead.dead_end = true;
      break;
    }
    follow.s = boundary;
    enter_next_lane(map, follow, ends, me.chooser);
    ahead.next.push_back(follow);
  }
  return path;
}

// Path distance (m) of road coordinates `theirs` ahead of the follower, or nothing when they
// are not on the path. `containing` also matches the lane the follower is in now (during a
// lane change the followed lane is already the target lane; the old one still counts).
std::optional<double> distance_on_path(const LanePath& path, const RoadCoordinates& theirs,
                                       int containing) {
  for (size_t i = 0; i < path.count; ++i) {
    const PathPiece& piece = path.pieces[i];
    // Lane first: within one road most others are in another lane.
    if ((theirs.lane != piece.lane && !(i == 0 && theirs.lane == containing)) ||
        theirs.road != piece.road || theirs.section != piece.section) {
      continue;
    }
    const double ahead = piece.distance + (theirs.s - piece.s_entry) * piece.dir;
    // On the first piece only what is in front; later pieces hold only what is ahead.
    if (ahead > 0.0 || (i > 0 && ahead >= 0.0)) {
      return ahead;
    }
  }
  return std::nullopt;
}

// Every entity that distance_on_path can place within kRange ahead (and a few more, some
// twice): those in the lanes of the path, from where the path enters each lane to where kRange
// ends, plus those in lanes the index does not hold.
void candidates_on_path(const xodr::Map& map, const LanePath& path, int containing,
                        const FollowView& view, std::vector<uint32_t>& out) {
  constexpr double kSlack = 1e-3;  // m: a superset, whatever the rounding of `ahead`
  out.assign(view.unindexed().begin(), view.unindexed().end());
  for (size_t i = 0; i < path.count; ++i) {
    const PathPiece& piece = path.pieces[i];
    const double reach = kRange - piece.distance + kSlack;
    const double low = piece.dir > 0 ? piece.s_entry - kSlack : piece.s_entry - reach;
    const double high = piece.dir > 0 ? piece.s_entry + reach : piece.s_entry + kSlack;
    view.lanes().query(piece.node, low, high, out);
    if (i == 0 && containing != piece.lane) {
      const auto node = map.lane_graph().find(xodr::LaneRef{piece.road, piece.section, containing});
      if (node) {
        view.lanes().query(*node, low, high, out);
      }
    }
  }
}

// The nearest usable entity ahead on the lane path, as the view shows it; of equal gaps the
// lowest entity index (what a scan of every entity in index order keeps).
Leader find_leader(const SimState& state, uint32_t self, const FollowView& view, LanesAhead& ahead,
                   std::vector<uint32_t>& candidates) {
  const Entity& me = state.world.entities[self];
  Leader leader;
  if (!me.state.road || !me.lane.on_road || state.map == nullptr) {
    return leader;
  }
  const LanePath path = path_ahead(*state.map, me, ahead);
  const int containing = me.state.road->lane;
  candidates_on_path(*state.map, path, containing, view, candidates);
  const double my_front = me.info.box.center_x + 0.5 * me.info.box.length;
  const double x = me.state.pose.x, y = me.state.pose.y;
  uint32_t chosen = UINT32_MAX;
  for (const uint32_t i : candidates) {
    const FollowTarget& other = view.targets()[i];
    if (i == self || !other.usable) {
      continue;
    }
    // What is farther in a straight line than kReach cannot be within kRange along the path
    // (s runs along the reference line; outer lanes of bends are longer).
    const double dx = other.x - x, dy = other.y - y;
    if (dx * dx + dy * dy > kReach * kReach) {
      continue;
    }
    const auto ahead = distance_on_path(path, other.road, containing);
    if (!ahead || *ahead >= kRange) {
      continue;
    }
    const double gap = *ahead - my_front + other.rear;
    if (gap < leader.gap || (gap == leader.gap && i < chosen)) {
      chosen = i;
      leader.gap = gap;
      leader.speed = other.speed * std::cos(other.h - me.state.pose.h);
    }
  }
  return leader;
}

}  // namespace

void step_acc(SimState& state, uint32_t index, const MotionContext& motion, const FollowView& view,
              LanesAhead& ahead, std::vector<uint32_t>& candidates) {
  Entity& entity = state.world.entities[index];
  const double set_speed = entity.speed_command;
  const Leader leader = find_leader(state, index, view, ahead, candidates);
  double command = set_speed;
  if (std::isfinite(leader.gap)) {
    const double v = entity.state.speed;
    const double desired = kStandstill + kTimeGap * std::max(v, 0.0);
    const double max_acc =
        entity.info.max_acceleration > 0.0 ? entity.info.max_acceleration : kDefaultLimit;
    const double max_dec =
        entity.info.max_deceleration > 0.0 ? entity.info.max_deceleration : kDefaultLimit;
    const double a = std::clamp(kGapGain * (leader.gap - desired) + kSpeedGain * (leader.speed - v),
                                -max_dec, max_acc);
    command = std::min(set_speed, std::max(0.0, v + a * motion.dt));
  }
  entity.speed_command = command;
  DefaultController().step(entity, motion);
  // The actions' set speed stays what they asked for (the default controller zeroes it at a
  // road end, which stands).
  if (entity.speed_command == command) {
    entity.speed_command = set_speed;
  }
}

}  // namespace corsa::engine::detail
