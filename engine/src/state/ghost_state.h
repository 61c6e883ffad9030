#pragma once

// esmini's ghost (its FollowGhostController, controllers/follow_ghost.h): an entity driven by
// the `followGhost` controller gets a second entity, "<name>_ghost", that starts the run a head
// start earlier (negative simulation times), performs the entity's motion actions, and leaves a
// trail; the entity then drives after the ghost along that trail.

#include <cstdint>
#include <vector>

namespace corsa::engine::detail {

/// One sample of the ghost's trail (map frame: m, rad, m/s; time in s of simulation time).
struct TrailPoint {
  double time = 0.0;
  double x = 0.0, y = 0.0, z = 0.0, h = 0.0;
  double speed = 0.0;
};

/// The driver model of the entity that follows its ghost: esmini's simple vehicle (a kinematic
/// single-track model with its reference point 15% of the length ahead of the rear axle), its
/// state in the map frame.
struct GhostFollower {
  bool started = false;
  double x = 0.0, y = 0.0, h = 0.0;  ///< m, m, rad in [0, 2 pi)
  double speed = 0.0;                ///< m/s
  double length = 5.0;               ///< m, the entity's bounding box length
};

/// The one ghost of a run and what its follower reads of it.
struct GhostLink {
  uint32_t entity = 0;     ///< the entity the followGhost controller drives
  uint32_t ghost = 0;      ///< "<entity>_ghost", appended after the scenario's entities
  double headstart = 3.0;  ///< s the ghost starts earlier (property headstartTime)
  int64_t headstart_ticks = 0;
  /// Look-ahead times (s) along the trail for the speed and the steering target (properties
  /// lookaheadSpeed / minLookaheadSpeed, lookaheadSteering / minLookaheadSteering).
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
