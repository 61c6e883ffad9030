#pragma once

// What car following (the acc controller) and the precautions of generated traffic
// (controllers/npc_caution.h) see of the other entities: each one as it was when the
// controllers' step began, the entities by lane in s order (state/lane_index.h) and, when there
// is generated traffic, their boxes' centres in a grid (state/point_grid.h). Every mover reads
// the same picture whatever the order, or the thread, it is moved in, so a step gives the same
// result on any number of threads; and a mover looks only at the lanes of its path ahead, or at
// the grid cells around it, instead of at every entity.

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "corsa/engine/entity_state.h"
#include "corsa/engine/oriented_box.h"
#include "lanes/lane_follow.h"
#include "state/lane_index.h"
#include "state/packed_point_grid.h"

namespace corsa::engine::detail {

struct SimState;
class GiveWay;

/// The speed (m/s) of an entity heading `h` (rad) along heading `own`: speed x cos(h - own),
/// without the cosine when the two headings are the same (cos 0 is 1 exactly, so the product is
/// `speed` to the bit): vehicles one behind the other on a straight road mostly are.
inline double speed_along(double speed, double h, double own) {
  const double difference = h - own;
  return difference == 0.0 ? speed : speed * std::cos(difference);
}

/// A bounding box as the precautions of generated traffic test it: OrientedBox's centre, half
/// sizes and axes, without the heights, which none of them reads.
struct FlatBox {
  double cx = 0.0, cy = 0.0;  ///< centre, m
  double half_length = 0.0, half_width = 0.0;
  double cos_h = 1.0, sin_h = 0.0;  ///< box axes: (cos, sin) forward, (-sin, cos) left

  static FlatBox of(const OrientedBox& box) {
    return FlatBox{box.cx, box.cy, box.half_length, box.half_width, box.cos_h, box.sin_h};
  }
};

/// One entity as car following sees it: two cache lines. The leader search reads only the
/// first of each entity it meets, the precautions of generated traffic (controllers/npc_caution.h)
/// mostly the second (with hundreds of vehicles these are read from beyond the second-level
/// cache: the 152 bytes this was, with the road's t and the box's heights, straddled three lines
/// and put the leader search's fields on two).
struct alignas(64) FollowTarget {
  double x = 0.0, y = 0.0;  ///< m, reference point
  double h = 0.0;           ///< rad, heading
  double speed = 0.0;       ///< m/s
  double rear = 0.0;        ///< m from the reference point to the rear of the box, along x
  double s = 0.0;           ///< m, road s (RoadCoordinates::s)
  uint32_t road = 0;        ///< RoadCoordinates::road
  uint32_t section = 0;     ///< RoadCoordinates::section
  int lane = 0;             ///< RoadCoordinates::lane
  /// Placed, on a lane and visible to traffic (VisibilityAction): only such an entity leads; the
  /// road fields are set only for such an entity.
  bool usable = false;
  /// Placed and visible to traffic, on a lane or not: what generated traffic keeps clear of.
  /// The fields below (and x, y, h, speed, rear) are set for every present entity.
  bool present = false;
  bool generated = false;  ///< made by traffic, not one of the scenario's own
  bool vehicle = false;    ///< ObjectKind::kVehicle
  double length = 0.0;     ///< m, of the bounding box
  FlatBox shape;           ///< the bounding box at the pose
};
static_assert(sizeof(FollowTarget) == 128, "a FollowTarget is two cache lines");

class FollowView {
 public:
  /// Takes the picture of `state`'s entities now; with `neighbours` also the grid of the present
  /// entities' reference points (near()). The same as begin(), fill() of every entity, finish().
  void build(const SimState& state, bool neighbours);

  /// The picture in three parts, for a caller that shares the entities' own parts out among
  /// threads: begin() sizes the per-entity records; fill(state, i) makes entity i's (its
  /// target, lane node and box reach), reading only that entity and writing only its records,
  /// so fills of different entities may run at once on different threads, in any order; once
  /// every entity is filled, finish() gathers them in index order on one thread (the lane
  /// index, the grids, the bounds), so the picture is the same whoever filled what.
  void begin(const SimState& state, bool neighbours);
  void fill(const SimState& state, uint32_t i);
  void finish();

  const std::vector<FollowTarget>& targets() const { return targets_; }
  const LaneIndex& lanes() const { return lanes_; }
  /// Usable entities whose lane is not a lane-graph node (looked at by every query).
  const std::vector<uint32_t>& unindexed() const { return unindexed_; }
  /// The least FollowTarget::rear of the usable entities (m; +inf without any): a gap to an
  /// entity `ahead` metres along the path is at least ahead - own front + this.
  double least_rear() const { return least_rear_; }

  /// Appends to `out` every present entity whose box centre (FollowTarget::shape) lies in
  /// [x_min, x_max] x [y_min, y_max] (m), and possibly some beyond, in no particular order (the
  /// view must have been built with `neighbours`).
  void near(double x_min, double y_min, double x_max, double y_max,
            std::vector<uint32_t>& out) const;
  /// The same for the present vehicles of the scenario's own (not generated), kept apart: few or
  /// none among much generated traffic.
  void near_scenario_vehicles(double x_min, double y_min, double x_max, double y_max,
                              std::vector<uint32_t>& out) const;
  /// The present entities (only the scenario's vehicles with `scenario_vehicles`) whose box
  /// centre lies in [along_min, along_max] x [-half, half] of the frame at (x, y) with axis
  /// cosine `c` and sine `s` (PackedPointGrid::query_band; [x_min, x_max] x [y_min, y_max]
  /// bounds that rectangle), and those with non-finite coordinates, appended to `out`.
  void near_band(double x_min, double y_min, double x_max, double y_max, double x, double y,
                 double c, double s, double along_min, double along_max, double half,
                 bool scenario_vehicles, std::vector<uint32_t>& out) const {
    (scenario_vehicles ? scenario_vehicles_ : grid_)
        .query_band(x_min, y_min, x_max, y_max, x, y, c, s, along_min, along_max, half, out);
  }
  /// The entities near_band appends, in the same order, handed to `visit(ids, count)` in runs
  /// (PackedPointGrid::visit_band).
  template <typename Visit>
  void visit_band(double x_min, double y_min, double x_max, double y_max, double x, double y,
                  double c, double s, double along_min, double along_max, double half,
                  bool scenario_vehicles, Visit visit) const {
    (scenario_vehicles ? scenario_vehicles_ : grid_)
        .visit_band(x_min, y_min, x_max, y_max, x, y, c, s, along_min, along_max, half, visit);
  }
  bool has_scenario_vehicles() const { return has_scenario_vehicles_; }
  /// The farthest (m) a present entity's bounding box reaches from its centre (half its
  /// diagonal): how far around a region near() must look for boxes reaching in (the same bound
  /// serves near_scenario_vehicles()). Centres, not reference points, are kept in the grids
  /// because a vehicle's reference point is its rear axle: the box reaches farther from it (a
  /// car's 3.8 m against 2.4 m), and every corridor query would look that much wider.
  double max_reach() const { return max_reach_; }
  /// The farthest (m) a present entity's box centre lies from its reference point: how far
  /// around a region near() must look for reference points in it.
  double max_offset() const { return max_offset_; }
  /// The greatest box length (m).
  double max_length() const { return max_length_; }
  /// Whether the present entities' FollowTarget::shape is that of this picture (built with
  /// `neighbours`).
  bool has_shapes() const { return has_shapes_; }

  /// Generated vehicles' claims in junctions (controllers/give_way.h), settled for this step
  /// before the moves; null without generated traffic or road network. A mover reads where its
  /// own entity must stop and writes only that entity's record.
  GiveWay* give_way() const { return give_way_; }
  void set_give_way(GiveWay* give_way) { give_way_ = give_way; }

 private:
  std::vector<FollowTarget> targets_;
  std::vector<xodr::LaneNode> nodes_;  ///< by entity: its lane's node, kNoLane when not indexed
  std::vector<double> reach_;          ///< by entity: its box's half diagonal (m), with neighbours
  std::vector<double> offset_;    ///< by entity: its box centre's distance from the reference (m)
  std::vector<Box> reach_boxes_;  ///< by entity: the box reach_ and offset_ were made from
  LaneIndex lanes_;
  std::vector<uint32_t> lane_order_;  ///< the last index's entities, lane after lane (in s order)
  std::vector<char> in_index_;        ///< by entity: added to the index from lane_order_
  std::vector<uint32_t> unindexed_;
  double least_rear_ = 0.0;
  PackedPointGrid grid_{kGridCell};
  PackedPointGrid scenario_vehicles_{kGridCell};
  bool has_scenario_vehicles_ = false;
  std::vector<char> generated_;  ///< by entity: made by traffic
  size_t generated_seen_ = 0;    ///< TrafficState::lifetimes.size() generated_ was made from
  double max_reach_ = 0.0;
  double max_offset_ = 0.0;
  double max_length_ = 0.0;
  bool has_shapes_ = false;
  GiveWay* give_way_ = nullptr;

  // m: about two car lengths (the grid makes its cells larger when the points are sparse); a
  // corridor query reads the cells of its bounding box a column at a time, each column's cells
  // one run of memory, so empty cells cost nothing.
  static constexpr double kGridCell = 8.0;
};

/// Where a follower's path enters one of its following lanes: what a piece of the path needs of
/// the LaneFollow that enter_next_lane made (32 bytes of its 64), and the piece's length.
struct LaneEntry {
  uint32_t road = 0;
  uint32_t section = 0;
  int lane = 0;
  xodr::LaneNode node = xodr::kNoLane;
  double s = 0.0;  ///< m, where the path enters the lane
  int dir = 1;     ///< LaneFollow::dir
  /// m along s from `s` to the lane's end in `dir` (|s_end - s| toward +s, |s_start - s| toward
  /// -s, of the lane graph's record): kept with the entry, so that a follower's path does not
  /// read the lane graph's record of every lane ahead at every step.
  double span = 0.0;

  static LaneEntry of(const LaneFollow& follow) {
    return LaneEntry{follow.road, follow.section, follow.lane, follow.node, follow.s, follow.dir};
  }
};

/// The lanes a follower will drive after the one it is in, as enter_next_lane chooses them at
/// each lane end. They depend only on that lane, the direction and the chooser, so a follower
/// keeps them from step to step while those stay the same, and looks them up instead of choosing
/// again (the choice evaluates the road headings of every successor).
///
/// The first lanes are held inline, beside the rest, and the movers keep these records in the
/// order they move the entities (controllers/controllers.cpp): a follower's look-up then reads
/// memory next to the last follower's instead of a heap block of its own (with hundreds of
/// vehicles, the cache misses of those reads were a large part of car following). The lanes
/// are held as LaneEntry (40 bytes); only the last one is kept whole (`last`), which is where
/// a longer path continues from (enter_next_lane reads and moves its lateral offset).
struct LanesAhead {
  xodr::LaneNode node = xodr::kNoLane;
  int dir = 0;
  const LaneChooser* chooser = nullptr;
  bool dead_end = false;  ///< the lane after the last of next (or the first) has no successor
  uint32_t count = 0;     ///< following lanes known
  /// Holds the route `chooser` belongs to, so that its address is not reused by another.
  std::shared_ptr<const LaneChooser> route;
  static constexpr uint32_t kInline = 4;
  /// Where the path enters each following lane: the first kInline here, the others in `more`.
  std::array<LaneEntry, kInline> first;
  std::vector<LaneEntry> more;
  /// The last following lane as enter_next_lane left it (valid while count > 0).
  LaneFollow last;

  const LaneEntry& next(uint32_t k) const { return k < kInline ? first[k] : more[k - kInline]; }
  /// Adds the lane `follow` entered, `span` metres long along the path (LaneEntry::span).
  void push(const LaneFollow& follow, double span) {
    LaneEntry entry = LaneEntry::of(follow);
    entry.span = span;
    if (count < kInline) {
      first[count] = entry;
    } else {
      more.push_back(entry);
    }
    last = follow;
    ++count;
  }
  void clear() {
    count = 0;
    more.clear();
    dead_end = false;
  }
};

}  // namespace corsa::engine::detail
