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
// drives its own heading, as a driver would: it cuts corners a little and lags the path. A point
// behind it (an actor facing away from the path) turns it on its tightest circle through that
// point; past the path's end the point runs on along the end's heading, so that the actor drives
// out along the end instead of circling the end point. Untimed, the progress along the path is
// the path point nearest the actor (not the distance driven, which a detour makes longer), and
// the action ends when that point reaches the path's end.
// A negative speed when the action starts drives the path in reverse gear (the vehicle faces
// against the path); in position mode a speed whose sign differs from that drives back toward
// the path's start (esmini's reading). The action ends at the path's end (or, driven back, its
// start), timed in the first step past its last time (§6.7.3: the actor is at each vertex at its
// time, so a repeated last vertex with a later time is a wait there); that step goes on past the
// end for its rest, and the actor's lane following takes over at the path's own end speed.

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
    const bool follow = action_.following_mode == xosc::FollowingMode::kFollow;
    if (first_step_) {
      first_step_ = false;
      direction_ = entity.speed_command < 0.0 ? -1.0 : 1.0;
    }
    // The step that passes the path's end goes on past it along the end's heading for the rest
    // of the step, and a timed path ends in the first step after its last time, as esmini reads
    // it (the standard says where the actor is at each vertex's time, not how the step that ends
    // a path is driven): the speed after a timed path is the path's own, not the share of the
    // step left on it.
    double beyond = 0.0;  // m past the path's end in this step
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
      // A last segment of zero length between two times (a vertex repeated) holds the actor
      // there until the last time, at speed 0.
      ended_ = trajectory_time >= path_.last_time() && s_next >= path_.last_timed_s() - 1e-9;
      if (ended_) {
        const double late = trajectory_time - path_.last_time();
        ended_ = late > 1e-9;
        beyond = std::max(0.0, late * end_speed());
      }
      entity.speed_command = (s_next + beyond - s_) / dt;
    } else if (follow) {
      // The follow driver drives the path ahead, in reverse gear while the speed is negative.
      s_next = s_ + std::abs(entity.speed_command * dt);
      beyond = std::max(0.0, s_next - path_.length());
    } else {
      // The sign of the speed when the action starts sets the direction of travel along the
      // path (reverse gear, facing against the path, if negative); a speed of the other sign
      // later drives back along the path toward its start, facing as before, as esmini reads it
      // (the standard says nothing of a negative speed along a path). A step travels its end
      // speed times dt, as a step on a lane does.
      s_next = s_ + direction_ * entity.speed_command * dt;
      beyond = std::max(0.0, s_next - path_.length());
      const bool backward = direction_ * entity.speed_command < 0.0;
      ended_ = backward ? s_next <= 1e-9 : s_next >= path_.length() - 1e-9;
    }
    s_next = std::clamp(s_next, 0.0, path_.length());
    if (follow) {
      const double facing = entity.speed_command < 0.0 ? std::numbers::pi : 0.0;
      Pose along = entity.state.pose;
      along.h = wrap_angle(along.h + facing);  // steer the direction of travel
      const double distance = s_next + beyond - s_;
      Pose pose = pursue(along, distance, s_, dt);
      pose.h = wrap_angle(pose.h + facing);
      entity.pose_command = pose;
      if (!timing_) {
        s_next = nearest_ahead(pose, lookahead(distance, dt));
        ended_ = s_next >= path_.length() - 1e-9;
      }
    } else {
      const double facing = direction_ < 0.0 ? std::numbers::pi : 0.0;
      const PathPoint p = continued(s_next + beyond);
      entity.pose_command = Pose{p.x, p.y, p.z, wrap_angle(p.h + facing), 0.0, 0.0};
    }
    s_ = s_next;
  }

  bool finished() const override { return ended_; }

 private:
  static double lookahead(double distance, double dt) {
    return std::max(kMinLookahead, kLookahead * distance / dt);
  }

  // m/s along the path at its last time: the last millisecond's (or whole path's) mean speed.
  double end_speed() const {
    const double h = std::min(1e-3, path_.last_time() - path_.first_time());
    return h > 0.0 ? (path_.last_timed_s() - path_.s_at_time(path_.last_time() - h)) / h : 0.0;
  }

  // The path's point at arc length s, continued straight past the end along the end's heading.
  PathPoint continued(double s) const {
    PathPoint p = path_.at(s);
    const double beyond = s - path_.length();
    if (beyond > 0.0) {
      p.x += std::cos(p.h) * beyond;
      p.y += std::sin(p.h) * beyond;
    }
    return p;
  }

  // Arc length of the path point nearest `pose`, searched from the progress so far up to
  // `reach` metres further: 32 samples, then a ternary search between the best one's neighbours.
  double nearest_ahead(const Pose& pose, double reach) const {
    const auto gap = [&](double s) {
      const PathPoint p = path_.at(s);
      return std::hypot(p.x - pose.x, p.y - pose.y);
    };
    constexpr int kSamples = 32;
    const double end = std::min(s_ + reach, path_.length());
    const double step = (end - s_) / kSamples;
    int best = 0;
    for (int i = 1; i <= kSamples; ++i) {
      if (gap(s_ + step * i) < gap(s_ + step * best)) {
        best = i;
      }
    }
    double lo = s_ + step * std::max(0, best - 1);
    double hi = s_ + step * std::min(kSamples, best + 1);
    for (int i = 0; i < 40; ++i) {
      const double a = lo + (hi - lo) / 3.0;
      const double b = hi - (hi - lo) / 3.0;
      if (gap(a) < gap(b)) {
        hi = b;
      } else {
        lo = a;
      }
    }
    return std::max(s_, 0.5 * (lo + hi));
  }

  // One step of a pure-pursuit driver (Coulter 1992): toward the look-ahead point L metres
  // ahead on the path at bearing alpha from the heading, along the arc of curvature
  // 2 sin(alpha) / L for `distance` metres. A point behind (|alpha| > 90 degrees) gets the
  // tightest circle through it (curvature 2 / chord) on its side: sin(alpha) would fall back to 0
  // and send the driver straight on, away from the path.
  Pose pursue(const Pose& from, double distance, double s, double dt) const {
    const PathPoint target = continued(s + lookahead(distance, dt));
    const double chord = std::max(1e-6, std::hypot(target.x - from.x, target.y - from.y));
    const double alpha = wrap_angle(std::atan2(target.y - from.y, target.x - from.x) - from.h);
    const double sine =
        std::abs(alpha) > 0.5 * std::numbers::pi ? (alpha < 0.0 ? -1.0 : 1.0) : std::sin(alpha);
    const double turn = 2.0 * sine / chord * distance;
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
  bool first_step_ = true;  ///< direction_ is set in the first step, from the speed then
  /// Position mode: +1 if the speed was positive or zero when the action started (a positive
  /// speed drives toward the path's end), -1 if negative (a negative speed drives toward the
  /// end, in reverse gear, facing against the path).
  double direction_ = 1.0;
};

}  // namespace

std::unique_ptr<ActionInstance> make_follow_trajectory_action(
    const xosc::FollowTrajectoryAction& action) {
  return std::make_unique<FollowTrajectoryInstance>(action);
}

}  // namespace corsa::engine::detail
