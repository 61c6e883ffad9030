#pragma once

// Generated vehicles giving way to each other in junctions (docs/engine.md, "How generated
// traffic gives way"). The conflict zones of the junction lanes are the map's
// (controllers/junction_conflicts.h). Each step:
//   1. before the moves, one pass settles the claims the vehicles near a junction recorded in
//      the last step: in one order (inside a zone or unable to stop before the next one first,
//      then by the lane's right of way, then first come first served, then entity index), each
//      vehicle takes the zones ahead of it unless a vehicle earlier in the order holds the other
//      side of one; then it stops before that zone and takes only the zones before it. Every
//      wait is for a vehicle earlier in the order, so there is no circular wait: the first one
//      always goes. One that can stop there only at its own maximum deceleration is told to
//      brake so (an emergency stop); only one that cannot even so goes on;
//   2. during its move each such vehicle (acc controller) stops before the zone it was told to
//      (a standing leader there, braking within the controller's limits, or at its maximum
//      deceleration in an emergency), and records the zones its path enters within its horizon
//      for the next pass. Only its own record is written, so the moves stay independent of each
//      other and of the threads.
// Vehicles farther than their horizon from every zone do nothing but look up the lanes of
// their path; nothing is allocated per step once the records have their size.

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "controllers/junction_conflicts.h"
#include "controllers/lane_path.h"

namespace corsa::engine::detail {

struct SimState;
struct Entity;

/// A vehicle's claim on a conflict zone ahead of (or under) it.
struct Claim {
  uint32_t conflict = 0;
  uint32_t side = 0;
  double to_enter = 0.0;  ///< m from its front to where its path enters the zone (< 0: in it)
  xodr::LaneNode node = xodr::kNoLane;  ///< the zone's lane
  double s_enter = 0.0;                 ///< road s where the path enters the zone
};

/// m/s^2: braking a vehicle is asked for without an emergency; one that cannot stop before a
/// zone at this is committed to it, and goes first.
inline constexpr double kFirm = 5.0;
/// m/s^2: the braking the horizon holds the stop at, and that a placed vehicle must be able to
/// stop at before a crossing another placed vehicle claims too (traffic/npc_traffic.cpp).
inline constexpr double kComfort = 2.0;

/// Zones one vehicle records at most (the nearest; Town04's busiest lane has fewer).
inline constexpr size_t kMaxClaims = 24;

/// What a vehicle near a junction tells the claims pass about itself.
struct Approach {
  uint32_t count = 0;                      ///< claims set, in path order
  RightOfWay right = RightOfWay::kNormal;  ///< of the lane of its first claim
  int64_t arrived = 0;                     ///< tick since which it has been approaching
  double stopping = 0.0;                   ///< m it needs to stop from its speed, braking firmly
  /// m it needs to stop at its own maximum deceleration (kFirm when that is less; `stopping`
  /// for the scenario's own traffic, see GiveWay::npc_vehicle): nearer a zone than this it can
  /// no longer stop before it, and holds it whatever the order.
  double emergency = 0.0;
  std::array<Claim, kMaxClaims> claims;
};

/// Where a vehicle must stop: its front kept before road s `s` of lane `node`.
struct YieldPoint {
  xodr::LaneNode node = xodr::kNoLane;
  double s = 0.0;
  bool emergency = false;  ///< it can stop there only braking at its maximum deceleration
};

/// m: the least distance between a vehicle's front and a zone it stops before (the acc
/// controller keeps its standstill gap to the point it stops at, kStopMargin before the zone).
inline constexpr double kStopMargin = 0.5;

/// The pass that settles the claims (1. above), with its scratch kept between steps.
class ClaimSettler {
 public:
  /// Settles the claims of the entities `who` (their approaches by entity index) on
  /// `conflict_count` conflicts: yields[i] for each i of `who` (sized by the caller).
  void settle(std::span<const Approach> approaches, std::span<const uint32_t> who,
              size_t conflict_count, std::span<YieldPoint> yields);

 private:
  std::vector<std::pair<uint64_t, uint32_t>> order_;
  std::vector<uint32_t> held_stamp_;  ///< by conflict: the pass that last took it
  std::vector<uint32_t> held_side_;   ///< by conflict: the side that took it then
  uint32_t stamp_ = 0;
};

/// What `--npc` leaves for giving way: its generator (traffic/npc_traffic.cpp), kept in the
/// traffic state with the others, is one. Which entities are the vehicles it placed, flagged as
/// it placed them and never told by a name (the scenario's own entities and its traffic
/// actions' objects may be called npc_vehicle_<k> too), and the conflict map it placed them
/// by, which giving way then shares instead of building it again (32 M instructions on Town04).
class NpcPlacement {
 public:
  virtual ~NpcPlacement() = default;
  /// By entity index: 1 for a vehicle `--npc` placed (none past the last).
  const std::vector<uint8_t>& vehicle_flags() const { return vehicle_flags_; }
  /// The conflicts of the map the vehicles were placed by (null before any were placed).
  const std::shared_ptr<const JunctionConflicts>& conflicts() const { return conflicts_; }

 protected:
  std::vector<uint8_t> vehicle_flags_;
  std::shared_ptr<const JunctionConflicts> conflicts_;
};

/// The run's state of giving way, kept by the entity mover.
class GiveWay {
 public:
  /// Before the moves of a step: at the first, the map's conflicts (those `--npc` placed its
  /// vehicles by, else built) and which entities `--npc` placed (NpcPlacement, found among the
  /// traffic state's generators); the records sized to the entities, and the claims recorded in
  /// the last step settled.
  void begin_step(const SimState& state);
  bool ready() const { return conflicts_ != nullptr; }
  const JunctionConflicts& conflicts() const { return *conflicts_; }

  /// Whether entity `index` is one of the vehicles `--npc` placed (NpcPlacement). They, not the
  /// objects of the scenario's traffic actions, brake at their maximum deceleration in an
  /// emergency and speed up within their acceleration (the acc controller): the scenario's
  /// traffic keeps its bytes.
  bool npc_vehicle(uint32_t index) const {
    return index < npc_vehicles_.size() && npc_vehicles_[index] != 0;
  }

  /// Where entity `index` must stop this step (node kNoLane: nowhere).
  const YieldPoint& yield_of(uint32_t index) const { return yields_[index]; }

  /// During entity `index`'s move: records the zones its path ahead enters within its horizon
  /// (or it is still in) for the next pass. Writes only entity `index`'s record.
  void record(uint32_t index, const Entity& me, const LanePath& path, int64_t tick);

 private:
  void start(const SimState& state);

  std::shared_ptr<const JunctionConflicts> conflicts_;
  std::vector<uint8_t> npc_vehicles_;  ///< NpcPlacement::vehicle_flags
  std::vector<Approach> approaches_;   ///< by entity
  std::vector<uint8_t> approaching_;   ///< by entity: its record holds claims
  std::vector<YieldPoint> yields_;     ///< by entity
  std::vector<uint32_t> who_;          ///< scratch: the entities approaching
  std::vector<uint32_t> stopped_;      ///< the entities told to stop by the last pass
  ClaimSettler settler_;
};

/// The claims of a vehicle whose front is `front` and rear `rear` metres ahead of its
/// reference point (rear < 0), at speed `speed`, along `path`: the zones whose far end its rear
/// has not passed, nearer than its horizon, in path order, written to out.claims (and the right
/// of way of the first to out.right); returns how many. Nothing is written without any.
uint32_t collect_claims(const JunctionConflicts& conflicts, const LanePath& path, double front,
                        double rear, double speed, Approach& out);

/// Whether a vehicle that needs `stopping` metres to stop (at some deceleration) can stop
/// before a zone `to_enter` metres ahead of its front, as the claims pass counts it.
bool can_stop(double to_enter, double stopping);

/// A standing leader's gap (m) for a vehicle with front `front` along `path` that must stop
/// before `point`; +inf when the point is not ahead on the path.
double gap_to_yield_point(const LanePath& path, const YieldPoint& point, double front);

}  // namespace corsa::engine::detail
