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
#include "controllers/give_way.h"
#include "controllers/lane_path.h"
#include "controllers/npc_caution.h"
#include "lanes/lane_follow.h"
#include "state/lane_index.h"
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

struct Leader {
  double gap = std::numeric_limits<double>::infinity();  ///< m, bumper to bumper
  double speed = 0.0;
  uint32_t entity = kNoHazardEntity;  ///< the view's entity; none for a stop line
};

// The lanes a vehicle held at `lane` will follow, choosing with `chooser`, up to kRange metres
// ahead; the lanes after its own come from `ahead`, which must have been started afresh for
// this lane, direction and chooser (path_ahead).
[[gnu::hot]] LanePath path_from(const xodr::Map& map, const LaneFollow& lane,
                                const LaneChooser* chooser, LanesAhead& ahead) {
  LanePath path;
  LaneEntry at = LaneEntry::of(lane);
  const auto& graph = map.lane_graph();
  // Where the lane of `entry` ends in its direction (road s), and how far that is from its s.
  const auto boundary = [&graph](const LaneEntry& entry) {
    const auto& info = graph.info(entry.node);
    return entry.dir > 0 ? info.s_end : info.s_start;
  };
  const auto span = [&boundary](const LaneEntry& entry) {
    return std::abs(boundary(entry) - entry.s);
  };
  double distance = 0.0;
  for (size_t k = 0; path.count < kMaxPieces; ++k) {
    path.pieces[path.count++] =
        PathPiece{at.road, at.section, at.lane, at.node, at.s, at.dir, distance};
    // The lanes ahead carry their spans: the lane graph is read for the follower's own lane
    // (which the followers moved before it mostly read too) and where the path grows.
    distance += k == 0 ? span(at) : at.span;
    if (distance >= kRange) {
      break;
    }
    if (k < ahead.count) {
      at = ahead.next(static_cast<uint32_t>(k));
      continue;
    }
    const auto ends = graph.ends(at.node, at.dir < 0);
    if (ahead.dead_end || ends.empty()) {
      ahead.dead_end = true;
      break;
    }
    // The next lane from the whole of the last one: the entity's own lane, or the last known.
    LaneFollow follow = k == 0 ? lane : ahead.last;
    follow.s = boundary(at);
    enter_next_lane(map, follow, ends, chooser);
    ahead.push(follow, span(LaneEntry::of(follow)));
    at = ahead.next(static_cast<uint32_t>(k));
  }
  return path;
}

// The lanes the entity will follow from where it is, up to kRange metres ahead; the lanes after
// its own come from `ahead` (extended, or started afresh when the entity's lane, direction or
// chooser changed).
LanePath path_ahead(const xodr::Map& map, const Entity& me, LanesAhead& ahead) {
  if (ahead.node != me.lane.node || ahead.dir != me.lane.dir || ahead.chooser != me.chooser) {
    ahead.node = me.lane.node;
    ahead.dir = me.lane.dir;
    ahead.chooser = me.chooser;
    ahead.route = me.route;
    ahead.clear();
  }
  return path_from(map, me.lane, me.chooser, ahead);
}

// Path distance (m) of road coordinates `theirs` ahead of the follower, or nothing when they
// are not on the path. `containing` also matches the lane the follower is in now (during a
// lane change the followed lane is already the target lane; the old one still counts).
std::optional<double> distance_on_path(const LanePath& path, const FollowTarget& theirs,
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

// A traffic light on the path ahead that says stop, as a standing leader at its stop line: red,
// or yellow while the vehicle can still stop comfortably (OpenDRIVE 1.8 §14 signals: a dynamic
// signal at s on its road, for traffic in the direction of its orientation).
Leader signal_ahead(const SimState& state, const Entity& me, const LanePath& path) {
  constexpr double kComfort = 3.0;  // m/s^2, the deceleration a yellow light is stopped with
  Leader stop;
  if (state.traffic.signals.empty()) {
    return stop;
  }
  const double my_front = me.info.box.center_x + 0.5 * me.info.box.length;
  for (size_t i = 0; i < path.count; ++i) {
    const PathPiece& piece = path.pieces[i];
    for (const xodr::Signal& signal : state.map->road(piece.road).signals) {
      const bool facing = signal.orientation == "none" || signal.orientation.empty() ||
                          (signal.orientation == "+") == (piece.dir > 0);
      const auto found = state.traffic.signals.find(signal.id);
      if (!signal.dynamic || !facing || found == state.traffic.signals.end()) {
        continue;
      }
      const double ahead = piece.distance + (signal.s - piece.s_entry) * piece.dir;
      // On the first piece only what is in front of the vehicle's front.
      const double gap = ahead - my_front - 1.0;  // stop a metre before the line
      if (ahead < 0.0 || (i == 0 && gap < -0.5) || gap >= stop.gap) {
        continue;
      }
      const SignalAspect aspect = signal_aspect(found->second);
      const double v = std::max(me.state().speed, 0.0);
      if (aspect == SignalAspect::kStop ||
          (aspect == SignalAspect::kCaution && gap > v * v / (2.0 * kComfort))) {
        stop.gap = std::max(gap, 0.0);
        stop.speed = 0.0;
      }
    }
  }
  return stop;
}

// The search for the leader: the nearest usable entity ahead on the lane path, as the view
// shows it; of equal gaps the lowest entity index (what a scan of every entity in index order
// keeps).
class LeaderSearch {
 public:
  LeaderSearch(const Entity& me, uint32_t self, const LanePath& path, const FollowView& view)
      : me_(me),
        self_(self),
        path_(path),
        view_(view),
        containing_(me.state().road->lane),
        my_front_(me.info.box.center_x + 0.5 * me.info.box.length) {}

  // Every entity that can be the leader is considered: those in lanes the index does not hold,
  // then, piece by piece along the path, those in its lane from where the path enters it, in the
  // order the path meets them, until no entity further on can be nearer than the leader so far:
  // an entity first met on piece i, `local` metres along the path, is `local` metres ahead, so
  // its gap is at least local - front + least rear (IEEE addition is monotonic, so also as
  // computed). Entities met on an earlier piece have been considered there.
  Leader find(const xodr::Map& map) {
    for (const uint32_t i : view_.unindexed()) {
      consider(i);
    }
    for (size_t k = 0; k < path_.count; ++k) {
      const PathPiece& piece = path_.pieces[k];
      if (beyond(piece.distance)) {
        break;
      }
      walk(piece, piece.node);
      if (k == 0 && containing_ != piece.lane) {
        const auto node =
            map.lane_graph().find(xodr::LaneRef{piece.road, piece.section, containing_});
        if (node) {
          walk(piece, *node);
        }
      }
    }
    return leader_;
  }

 private:
  // Whether an entity `local` metres along the path cannot be nearer than the leader so far.
  bool beyond(double local) const {
    return local >= kRange + kSlack || (local - my_front_) + view_.least_rear() > leader_.gap;
  }

  // The first entry of `lane` (sorted by s) whose s is not below `s`: std::lower_bound's, found
  // without a branch on the comparisons (a conditional move halves the range), which follow no
  // pattern a branch predictor learns.
  static const LaneIndex::Entry* first_from(std::span<const LaneIndex::Entry> lane, double s) {
    const LaneIndex::Entry* base = lane.data();
    size_t n = lane.size();
    if (n == 0) {
      return base;
    }
    while (n > 1) {
      const size_t half = n / 2;
      base = base[half].s < s ? base + half : base;
      n -= half;
    }
    return base + (base->s < s ? 1 : 0);
  }

  // The entities of lane `node` from the piece's entry on, in the direction of travel.
  void walk(const PathPiece& piece, xodr::LaneNode node) {
    const auto lane = view_.lanes().lane(node);
    const LaneIndex::Entry* const end = lane.data() + lane.size();
    if (piece.dir > 0) {
      for (const LaneIndex::Entry* it = first_from(lane, piece.s_entry - kSlack); it != end; ++it) {
        if (beyond(piece.distance + (it->s - piece.s_entry))) {
          break;
        }
        consider(it->entity);
      }
      return;
    }
    const LaneIndex::Entry* it = first_from(lane, piece.s_entry + kSlack);
    // Entries before `it` have s < entry + slack: walk them backwards (toward -s).
    while (it != lane.data()) {
      --it;
      if (it->s > piece.s_entry + kSlack) {
        continue;
      }
      if (beyond(piece.distance + (it->s - piece.s_entry) * -1)) {
        break;
      }
      consider(it->entity);
    }
  }

  void consider(uint32_t i) {
    const FollowTarget& other = view_.targets()[i];
    if (i == self_ || !other.usable) {
      return;
    }
    // What is farther in a straight line than kReach cannot be within kRange along the path
    // (s runs along the reference line; outer lanes of bends are longer).
    const double dx = other.x - me_.state().pose.x, dy = other.y - me_.state().pose.y;
    if (dx * dx + dy * dy > kReach * kReach) {
      return;
    }
    const auto ahead = distance_on_path(path_, other, containing_);
    if (!ahead || *ahead >= kRange) {
      return;
    }
    const double gap = *ahead - my_front_ + other.rear;
    if (gap < leader_.gap || (gap == leader_.gap && i < leader_.entity)) {
      leader_.entity = i;
      leader_.gap = gap;
      leader_.speed = speed_along(other.speed, other.h, me_.state().pose.h);
    }
  }

  static constexpr double kSlack = 1e-3;  // m, against the rounding of the path distances

  const Entity& me_;
  uint32_t self_;
  const LanePath& path_;
  const FollowView& view_;
  int containing_;
  double my_front_;
  Leader leader_;
};

// The leader as the view shows it along `path`; for generated traffic also a traffic light that
// says stop (the light when it is as near).
[[gnu::hot]] Leader find_leader(const SimState& state, uint32_t self, const FollowView& view,
                                const LanePath& path, bool obey_signals) {
  const Entity& me = state.world.entities[self];
  const Leader leader = LeaderSearch(me, self, path, view).find(*state.map);
  if (obey_signals) {
    const Leader stop = signal_ahead(state, me, path);
    if (stop.gap <= leader.gap) {
      return stop;
    }
  }
  return leader;
}

// The gap (m) between two boxes along the axis (ax, ay), measured from `from`: positive when
// `to` lies beyond it along the axis, negative when behind, 0 when their shadows overlap.
double gap_along(const OrientedBox& from, const OrientedBox& to, double ax, double ay) {
  const auto shadow = [ax, ay](const OrientedBox& b) {
    const double c = b.cx * ax + b.cy * ay;
    const double r = b.half_length * std::abs(b.cos_h * ax + b.sin_h * ay) +
                     b.half_width * std::abs(b.cos_h * ay - b.sin_h * ax);
    return std::array<double, 2>{c - r, c + r};
  };
  const auto [min0, max0] = shadow(from);
  const auto [min1, max1] = shadow(to);
  if (max0 < min1) return min1 - max0;
  if (min0 > max1) return max1 - min0;
  return 0.0;
}

// esmini's ACCController also takes as its leader an entity very close in front wherever it
// is (ControllerACC::Step, "really close entities in front"): the gap between the boxes along
// the follower's heading above 0 and below 1 m + the entity's length + half the closing speed,
// and across it between 0.5 m to the right and 0.2 m to the left (0 where the boxes overlap
// across). Such an entity replaces the leader along the lanes, as esmini's does (the last one
// in entity order); it is what makes esmini's ALKS ego brake for a car cutting in before the
// car's reference point is in its lane.
Leader close_in_front(const SimState& state, uint32_t self, const FollowView& view, Leader leader) {
  const Entity& me = state.world.entities[self];
  const OrientedBox mine = box_of(me.info.box, me.state().pose);
  const double v = me.state().speed;
  const auto& targets = view.targets();
  for (uint32_t i = 0; i < targets.size(); ++i) {
    const FollowTarget& other = targets[i];
    if (i == self || !other.present || i == leader.entity) continue;
    // Where the view shows it (the step's start; only position and heading count here).
    const Pose pose{.x = other.x, .y = other.y, .h = other.h};
    const OrientedBox box = box_of(state.world.entities[i].info.box, pose);
    const double along = gap_along(mine, box, mine.cos_h, mine.sin_h);
    if (along <= 0.0 || along >= 1.0 + other.length + 0.5 * std::max(0.0, v - other.speed)) {
      continue;
    }
    const double across = gap_along(mine, box, -mine.sin_h, mine.cos_h);
    if (across < 0.2 && across > -0.5) {
      leader = Leader{along, other.speed, i};
    }
  }
  return leader;
}

// Whether the entity has a lane path to look along.
bool has_path(const SimState& state, const Entity& me) {
  return me.state().road && me.lane.on_road && state.map != nullptr;
}

// esmini's ACCController (its ControllerACC::Step): the speed after this step. Without a leader
// it approaches the set speed at 0.7 x maxAcceleration per m/s of difference (at most 0.7 x
// maxAcceleration, at least -maxDeceleration) and stops at it. With one, it keeps 3 m plus
// timeGap x the faster one's speed: the acceleration 2.5 f - f (v - set) - (1 - f) (v -
// min(set, lead)), f = min(1, (gap - follow) / follow), within the Performance, and never past
// the set speed (newer esmini's cap: a leader far ahead no longer lifts it 2.5 m/s over); a gap
// under 1 m stops it. It sees leaders no further than max(50 m, 6 m + v^2 / maxDeceleration).
double esmini_acc_speed(const Entity& entity, const EsminiAcc& acc, double set_speed,
                        const Leader& leader, double dt) {
  constexpr double kMinDist = 3.0;  // m
  constexpr double kSetSpeedGain = 0.7;
  const double max_acc =
      entity.info.max_acceleration > 0.0 ? entity.info.max_acceleration : kDefaultLimit;
  const double max_dec =
      entity.info.max_deceleration > 0.0 ? entity.info.max_deceleration : kDefaultLimit;
  const double v = entity.state().speed;
  const double lookahead = std::max(50.0, 2.0 * kMinDist + v * v / max_dec);
  if (std::isfinite(leader.gap) && leader.gap <= lookahead) {
    if (leader.gap < 1.0) return 0.0;
    const double follow = kMinDist + acc.time_gap * std::abs(std::max(v, leader.speed));
    const double f = std::min(1.0, (leader.gap - follow) / follow);
    const double dv_min = v - std::min(set_speed, leader.speed);
    const double dv_set = v - set_speed;
    const double a = std::clamp(2.5 * f - f * dv_set - (1.0 - f) * dv_min, -max_dec, max_acc);
    return std::min(set_speed, std::max(0.0, v + a * dt));
  }
  const double a =
      std::clamp((set_speed - v) * kSetSpeedGain * max_acc, -max_dec, kSetSpeedGain * max_acc);
  const double next = v + a * dt;
  return std::abs(next - set_speed) > std::abs(v - set_speed) ? set_speed : next;
}

// A generated vehicle near a junction: the point it was told to stop before, as a standing
// leader when nearer than `leader`; and its claims for the next step's pass. Returns whether it
// must stop there at its maximum deceleration (an emergency stop).
bool give_way(GiveWay& claims, uint32_t index, const Entity& me, const LanePath& path, int64_t tick,
              Leader& leader) {
  const YieldPoint& point = claims.yield_of(index);
  bool emergency = false;
  if (point.node != xodr::kNoLane) {
    const double front = me.info.box.center_x + 0.5 * me.info.box.length;
    const double gap = gap_to_yield_point(path, point, front);
    if (gap < leader.gap) {
      leader = Leader{gap, 0.0};
    }
    emergency = point.emergency && std::isfinite(gap);
  }
  claims.record(index, me, path, tick);
  return emergency;
}

}  // namespace

LanePath lane_path_of(const xodr::Map& map, const LaneFollow& lane) {
  LanesAhead ahead;
  return path_from(map, lane, nullptr, ahead);
}

[[gnu::hot]] void step_acc(SimState& state, uint32_t index, const MotionContext& motion,
                           const FollowView& view, LanesAhead& ahead) {
  Entity& entity = state.world.entities[index];
  const double set_speed = entity.speed_command;
  const bool on_path = has_path(state, entity);
  const LanePath path = on_path ? path_ahead(*state.map, entity, ahead) : LanePath{};
  if (const auto& esmini = state.controls[index].esmini_acc) {
    const Leader leader = close_in_front(
        state, index, view, on_path ? find_leader(state, index, view, path, false) : Leader{});
    const double command =
        esmini_acc_speed(entity, *esmini, esmini->set_speed.value_or(set_speed), leader, motion.dt);
    entity.speed_command = command;
    DefaultController().step(entity, motion);
    if (entity.speed_command == command) {
      entity.speed_command = set_speed;
    }
    return;
  }
  // Generated traffic also minds traffic lights, whatever reaches into its way, the scenario's
  // vehicles coming up from behind (controllers/npc_caution.h), and gives way in junctions
  // (controllers/give_way.h).
  const bool generated = view.targets()[index].generated;
  Leader leader = on_path ? find_leader(state, index, view, path, generated) : Leader{};
  double target = set_speed;
  bool emergency = false;
  if (generated) {
    if (on_path && view.give_way() != nullptr && view.give_way()->ready()) {
      emergency = give_way(*view.give_way(), index, entity, path, state.tick, leader);
    }
    std::vector<uint32_t>& near = *motion.nearby;
    const double v = std::max(entity.state().speed, 0.0);
    // Only what is nearer than the leader already found can take its place (a hazard wins with
    // a smaller gap, and a hazard's gap is where its box enters the corridor): the corridor ends
    // there, a metre on against rounding. In dense traffic the leader is close, and the
    // corridor then covers a few cars' lengths instead of up to a hundred metres.
    const double reach = std::max(15.0, 3.0 * v + 10.0);
    const double within = leader.gap < reach ? std::max(0.0, leader.gap + 1.0) : reach;
    const Hazard hazard = corridor_hazard(entity, index, view, within, leader.gap, near,
                                          Hazard{leader.gap, leader.speed, leader.entity});
    if (hazard.gap < leader.gap) {
      leader = {hazard.gap, hazard.speed, hazard.entity};
    }
    const double ahead_of = keep_ahead_speed(entity, index, view, near);
    if (ahead_of > target) {
      target = entity.info.max_speed > 0.0 ? std::min(ahead_of, entity.info.max_speed) : ahead_of;
    }
  }
  const double v = entity.state().speed;
  const double max_acc =
      entity.info.max_acceleration > 0.0 ? entity.info.max_acceleration : kDefaultLimit;
  const double max_dec =
      entity.info.max_deceleration > 0.0 ? entity.info.max_deceleration : kDefaultLimit;
  double command = target;
  if (target > set_speed) {
    // Speeding up to keep ahead: within the vehicle's acceleration.
    command = std::min(target, std::max(v, set_speed) + max_acc * motion.dt);
  }
  if (generated && command > v + max_acc * motion.dt && view.give_way() != nullptr &&
      view.give_way()->npc_vehicle(index)) {
    // NPCs gain speed within their acceleration, also up to their set speed: let go at a
    // junction or rid of their leader, they do not take the set speed at once (the scenario's
    // vehicles, and its traffic actions' objects, keep the speed their actions give).
    command = std::min(command, std::max(v, 0.0) + max_acc * motion.dt);
  }
  if (std::isfinite(leader.gap)) {
    const double desired = kStandstill + kTimeGap * std::max(v, 0.0);
    const double a = std::clamp(kGapGain * (leader.gap - desired) + kSpeedGain * (leader.speed - v),
                                -max_dec, max_acc);
    command = std::min(command, std::max(0.0, v + a * motion.dt));
  }
  if (emergency) {
    // Told to stop where it can stop only at its maximum deceleration: full braking.
    command = std::min(command, std::max(0.0, v - max_dec * motion.dt));
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
