#pragma once

// What car following (the acc controller) sees of the other entities: each one as it was when
// the controllers' step began, and the entities by lane in s order (state/lane_index.h). Every
// follower reads the same picture whatever the order, or the thread, it is moved in, so a step
// gives the same result on any number of threads; and a follower looks only at the lanes of its
// path ahead instead of at every entity.

#include <cstdint>
#include <memory>
#include <vector>

#include "corsa/engine/entity_state.h"
#include "lanes/lane_follow.h"
#include "state/lane_index.h"

namespace corsa::engine::detail {

struct SimState;

/// One entity as car following sees it.
struct FollowTarget {
  double x = 0.0, y = 0.0;  ///< m, reference point
  double h = 0.0;           ///< rad, heading
  double speed = 0.0;       ///< m/s
  double rear = 0.0;        ///< m from the reference point to the rear of the box, along x
  RoadCoordinates road;
  /// Placed, on a lane and visible to traffic (VisibilityAction): only such an entity leads.
  bool usable = false;
};

class FollowView {
 public:
  /// Takes the picture of `state`'s entities now.
  void build(const SimState& state);

  const std::vector<FollowTarget>& targets() const { return targets_; }
  const LaneIndex& lanes() const { return lanes_; }
  /// Usable entities whose lane is not a lane-graph node (looked at by every query).
  const std::vector<uint32_t>& unindexed() const { return unindexed_; }
  /// The least FollowTarget::rear of the usable entities (m; +inf without any): a gap to an
  /// entity `ahead` metres along the path is at least ahead - own front + this.
  double least_rear() const { return least_rear_; }

 private:
  std::vector<FollowTarget> targets_;
  LaneIndex lanes_;
  std::vector<uint32_t> unindexed_;
  double least_rear_ = 0.0;
};

/// The lanes a follower will drive after the one it is in, as enter_next_lane chooses them at
/// each lane end. They depend only on that lane, the direction and the chooser, so a follower
/// keeps them from step to step while those stay the same, and looks them up instead of choosing
/// again (the choice evaluates the road headings of every successor).
struct LanesAhead {
  xodr::LaneNode node = xodr::kNoLane;
  int dir = 0;
  const LaneChooser* chooser = nullptr;
  /// Holds the route `chooser` belongs to, so that its address is not reused by another.
  std::shared_ptr<const LaneChooser> route;
  /// Where the path enters each following lane (road, section, lane, node, s, dir).
  std::vector<LaneFollow> next;
  bool dead_end = false;  ///< the lane after next.back() (or the first) has no successor
};

}  // namespace corsa::engine::detail
