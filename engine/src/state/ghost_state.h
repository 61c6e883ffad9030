#pragma once

// esmini's ghost (its FollowGhostController, controllers/follow_ghost.h): an entity driven by
// the `followGhost` controller gets a second entity, "<name>_ghost", that starts the run a head
// start earlier (negative simulation times), performs the entity's motion actions, and leaves a
// trail; the entity then drives after the ghost along that trail.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace corsa::engine::detail {

/// One sample of the ghost's trail (map frame: m, rad, m/s; time in s of simulation time; s in
/// m, the distance along the trail's polyline from its first sample).
struct TrailPoint {
  double time = 0.0;
  double x = 0.0, y = 0.0, z = 0.0, h = 0.0;
  double speed = 0.0;
  double s = 0.0;
  /// The ghost jumped here from the sample before (a TeleportAction): the follower jumps too
  /// when it reaches this sample, and the jump adds nothing to s.
  bool jump = false;
};

/// The driver model of the entity that follows its ghost: esmini's simple vehicle (a kinematic
/// single-track model with its reference point 15% of the length ahead of the rear axle), its
/// state in the map frame.
struct GhostFollower {
  bool started = false;
  /// The tick of the follower's last step: a step that does not follow it (the controller was
  /// off, or the entity deleted, in between) starts the model again from the entity's pose, as
  /// esmini's controller does when it is activated.
  int64_t last_tick = 0;
  /// Position mode: the trail segment [follow_index, follow_index + 1] nearest the entity last
  /// step, where the search for the nearest point starts.
  size_t follow_index = 0;
  double x = 0.0, y = 0.0, h = 0.0;  ///< m, m, rad in [0, 2 pi)
  double speed = 0.0;                ///< m/s
  double length = 5.0;               ///< m, the entity's bounding box length
};

/// The one ghost of a run and what its follower reads of it.
struct GhostLink {
  uint32_t entity = 0;     ///< the entity the followGhost controller drives
  uint32_t ghost = 0;      ///< "<entity>_ghost", appended after the scenario's entities
  double headstart = 3.0;  ///< s the ghost starts earlier (property headstartTime)
  /// Property followMode: false ("time", the default) looks ahead along the trail by time
  /// behind the ghost; true ("position") by distance from the trail point nearest the entity.
  bool by_position = false;
  int64_t headstart_ticks = 0;
  /// Until this tick only the ghost moves: 0 during its head start; after a restart (esmini's
  /// ghost restart, controllers/follow_ghost.h) the tick the run had reached when the ghost was
  /// put back, which the ghost then runs up to again from headstart_ticks earlier.
  int64_t replay_end_tick = 0;
  /// Ticks run a second time by restarts (the run's step count adds them).
  int64_t replayed_ticks = 0;
  /// Look-ahead along the trail for the speed and the steering target (properties
  /// lookaheadSpeed / minLookaheadSpeed, lookaheadSteering / minLookaheadSteering): in time mode
  /// all four are s; in position mode the look-ahead is max(min, lookahead * speed) in m.
  double lookahead_speed = 0.1;
  double min_lookahead_speed = 0.1;
  double lookahead_steering = 1.0;
  double min_lookahead_steering = 0.1;
  /// Steering damping with speed: the wheel's range is 60 degrees / (1 + k v^2).
  double steering_speed_inertia = 0.01;
  std::vector<TrailPoint> trail;  ///< sampled every kTrailSampleTime, in time order
  GhostFollower follower;
};

/// Seconds between trail samples (esmini's GHOST_TRAIL_SAMPLE_TIME).
inline constexpr double kTrailSampleTime = 0.2;

}  // namespace corsa::engine::detail
