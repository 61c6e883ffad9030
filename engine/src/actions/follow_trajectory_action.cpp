// FollowTrajectoryAction (OpenSCENARIO 1.3 §7.4.2.4, trajectories §6.7): the actor drives along
// a Polyline, Clothoid, ClothoidSpline or Nurbs (inline or from a catalog, expanded by the
// loader; positions resolved when the action starts).
//
// Progress along the path: with TimeReference/Timing the trajectory times say where the actor
// is: simulation time t maps to trajectory time (t - offset) / scale (§6.7.3: t_sim = t_traj *
// scale + offset), t measured from the action start in the `relative` domain; the speed is what
// that progress takes. With <None/> the times are ignored and the actor keeps the speed its
// longitudinal actions give it (this action then takes only the lateral domain).
// initialDistanceOffset starts that many metres along the path (relative timing starts at the
// time of that point). Following mode `position`: the actor is exactly on the path. `follow`: it
// steers toward a point kLookahead seconds (at least kMinLookahead m) ahead on the path and
// drives its own heading, as a driver would: it cuts corners a little and lags the path.
// A negative speed drives the path in reverse gear (the vehicle faces against the path). The
// action ends at the path's end, timed at its last time (§6.7.3: the actor is at each vertex at
// its time, so a repeated last vertex with a later time is a wait there); the actor's lane
// following takes over from there, at the speed the last step of the path gave it.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "actions/action_makers.h"
#include "geometry/angle.h"
#include "positions/trajectory_path.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

constexpr double kLookahead = 1.0;     // s
constexpr double kMinLookahead = 3.0;  // m

class FollowTrajectoryInstance final : public ActionInstance {
 public:
  explicit FollowTrajectoryInstance(const xosc::FollowTrajectoryAction& action)
      : action_(action), timing_(action.time_reference.timing) {}

  uint8_t domains() const override {
    return timing_ ? kDomainLongitudinal | kDomainLateral : kDomainLateral;
  }

  void start(ActionContext& context) override {
    path_ = build_trajectory_path(action_.trajectory, context.state, context.actor);
    if (timing_ && !path_.timed()) {
      context.state.diagnostics.add_once(
          "follow-trajectory-untimed",
          action_.source.warning("FollowTrajectoryAction has a Timing but trajectory '" +
                                 action_.trajectory.name +
                                 "' has fewer than two times; it is followed at the current "
                                 "speed"));
      timing_.reset();
    }
    s_ = std::clamp(action_.initial_distance_offset.value_or(0.0), 0.0, path_.length());
    start_time_ = context.state.now();
    if (timing_ && timing_->domain_absolute_relative == xosc::ReferenceContext::kRelative) {
      time_shift_ = path_.time_at_s(s_) - path_.first_time();
    }
  }

  void step(ActionContext& context) override {
    Entity& entity = context.entity();
    const double dt = context.state.time.dt();
    double s_next = 0.0;
    if (timing_) {
      double t = context.state.time.time(context.state.tick + 1);
      if (timing_->domain_absolute_relative == xosc::ReferenceContext::kRelative) {
        t -= start_time_;
      }
      const double scale = timing_->scale > 0.0 ? timing_->scale : 1.0;
      const double trajectory_time =
          path_.first_time() + (t - timing_->offset) / scale + time_shift_;
      s_next = std::max(s_, path_.s_at_time(trajectory_time));
      ended_ = trajectory_time >= path_.last_time() && s_next >= path_.last_timed_s() - 1e-9;
      entity.speed_command = (s_next - s_) / dt;
    } else {
      // Reversing (a negative speed) also runs along the path: the path gives the direction
      // of travel, the vehicle then faces against it.
      s_next = s_ + std::abs(0.5 * (entity.state.speed + entity.speed_command) * dt);
    }
    const double facing = entity.speed_command < 0.0 ? std::numbers::pi : 0.0;
    s_next = std::min(s_next, path_.length());
    // With a Timing the times say when the action ends: a last segment of zero length between
    // two times (a vertex repeated) holds the actor there until the last time, at speed 0.
    ended_ = timing_ ? ended_ : s_next >= path_.length() - 1e-9;
    if (action_.following_mode == xosc::FollowingMode::kFollow) {
      Pose along = entity.state.pose;
      along.h = wrap_angle(along.h + facing);  // steer the direction of travel
      Pose pose = pursue(along, s_next - s_, s_, dt);
      pose.h = wrap_angle(pose.h + facing);
      entity.pose_command = pose;
    } else {
      const PathPoint p = path_.at(s_next);
      entity.pose_command = Pose{p.x, p.y, p.z, wrap_angle(p.h + facing), 0.0, 0.0};
    }
    s_ = s_next;
  }

  bool finished() const override { return ended_; }

 private:
  // One step of a pure-pursuit driver (Coulter 1992): toward the look-ahead point L metres
  // ahead on the path at bearing alpha from the heading, along the arc of curvature
  // 2 sin(alpha) / L for `distance` metres.
  Pose pursue(const Pose& from, double distance, double s, double dt) const {
    const double lookahead = std::max(kMinLookahead, kLookahead * distance / dt);
    const PathPoint target = path_.at(s + lookahead);
    const double chord = std::max(1e-6, std::hypot(target.x - from.x, target.y - from.y));
    const double alpha = wrap_angle(std::atan2(target.y - from.y, target.x - from.x) - from.h);
    const double turn = 2.0 * std::sin(alpha) / chord * distance;
    const double mid = from.h + 0.5 * turn;
    return Pose{from.x + std::cos(mid) * distance,
                from.y + std::sin(mid) * distance,
                path_.at(s).z,
                wrap_angle(from.h + turn),
                from.p,
                from.r};
  }

  const xosc::FollowTrajectoryAction& action_;
  std::optional<xosc::Timing> timing_;
  TrajectoryPath path_;
  double s_ = 0.0;           ///< m along the path
  double start_time_ = 0.0;  ///< s
  double time_shift_ = 0.0;  ///< s of trajectory time skipped by initialDistanceOffset
  bool ended_ = false;
};

}  // namespace

std::unique_ptr<ActionInstance> make_follow_trajectory_action(
    const xosc::FollowTrajectoryAction& action) {
  return std::make_unique<FollowTrajectoryInstance>(action);
}

}  // namespace corsa::engine::detail
