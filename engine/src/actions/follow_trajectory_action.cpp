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
// time of that point). The actor is on the path in both following modes: how an actor follows a
// path in `follow` mode is the simulator's driver model (1.3 TrajectoryFollowingMode), and esmini's
// FollowTrajectoryAction moves its actor along the path in that mode as in `position` (the mode
// only retimes a timed polyline there: constant acceleration from the current speed over each
// segment, which Corsa does not emulate; it keeps the vertices' times).
// The direction the actor faces along the path, set when it starts moving: the heading the vertex
// it starts from states, if it states one (1.3 §6.9: a trajectory of six dimensions gives the
// entity's orientation too; facing within 90 degrees of the path's direction faces along it, else
// against it); without one, along the path on a timed path, and on an untimed one along it at a
// speed of zero or more, against it (reverse gear) at a negative speed (esmini's reading). The
// stated heading sets the facing whatever the speed's sign. A positive speed drives the way the
// actor faces, a negative one backwards: facing against the path, a positive speed drives toward
// the path's start (esmini's trajectory_heading: a car facing along its path at -10 m/s backs
// toward the path's start). The action ends at the end the actor drives to, timed in the first step
// past its last time (§6.7.3: the actor is at each vertex at its time, so a repeated last vertex
// with a later time is a wait there); that step goes on past the end for its rest, and the actor's
// lane following takes over at the path's own end speed. A timed path driven facing against it is
// driven in reverse gear: the speed is negative. Further on, each vertex stating a heading turns
// the actor to it: on a timed path from that vertex on (a path that doubles back is driven forward
// after reversing), on an untimed one the direction of travel stays as it started and the stated
// headings turn the actor only. The standard reading sets an untimed path's stated headings
// aside, with a warning at the starting vertex's line, when the facing its vertex states would
// drive the actor off the path where it starts at its starting speed (a filler h = 0 on a path
// along -x, driven forward from its start): read so, the action would end before the actor moves.
// esmini honours them (`--semantics esmini`): its FollowTrajectoryAction sets the object to an
// explicitly stated heading and, untimed, moves it by the speed's sign times the side of the path
// that heading faces, so such an action ends at once.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <variant>

#include "actions/action_makers.h"
#include "geometry/angle.h"
#include "positions/trajectory_path.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

class FollowTrajectoryInstance final : public ActionInstance {
 public:
  explicit FollowTrajectoryInstance(const xosc::FollowTrajectoryAction& action)
      : action_(action), timing_(action.time_reference.timing) {}

  // A Timing over a path without times leaves the speed to the longitudinal actions, so such an
  // action takes only the lateral domain (the warning comes when it starts).
  uint8_t domains() const override {
    return timing_ && states_times(action_.trajectory) ? kDomainLongitudinal | kDomainLateral
                                                       : kDomainLateral;
  }

  void start(ActionContext& context) override {
    path_ = build_trajectory_path(action_.trajectory, context.state, context.actor);
    if (timing_ && !path_.timed()) {
      context.state.diagnostics.add_once(
          "follow-trajectory-untimed",
          action_.source.warning("FollowTrajectoryAction has a Timing but trajectory '" +
                                 action_.trajectory.name +
                                 "' has fewer than two times; it is followed at the speed the "
                                 "longitudinal actions give"));
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
    if (first_step_) {
      first_step_ = false;
      facing_ = !timing_ && entity.speed_command < 0.0 ? -1.0 : 1.0;
      if (path_.stated_heading_at(s_)) {
        const double stated = stated_facing(s_);
        if (context.state.options.semantics != Semantics::kEsmini && !timing_ &&
            leaves_no_path(stated, entity.speed_command)) {
          ignore_stated_ = true;
          warn_ignored_headings(context, entity.speed_command);
        } else {
          facing_ = stated;
        }
      }
    }
    // The step that passes the path's end goes on past it along the end's heading for the rest
    // of the step, and a timed path ends in the first step after its last time, as esmini reads
    // it (the standard says where the actor is at each vertex's time, not how the step that ends
    // a path is driven): the speed after a timed path is the path's own, not the share of the
    // step left on it.
    double beyond = 0.0;  // m past the path's end in this step
    double s_next = 0.0;
    double face = facing_;  // the way the actor faces at the step's end
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
      // On a timed path each vertex stating a heading turns the actor to it from there on (a
      // path that doubles back is driven forward again after reversing, as esmini does).
      face = path_.stated_heading_at(s_next) ? stated_facing(s_next) : facing_;
      entity.speed_command = face * (s_next + beyond - s_) / dt;
    } else {
      // A positive speed drives the way the actor faces (toward the path's start when it faces
      // against the path), a negative one backwards (the standard says nothing of the direction
      // of travel along a path nor of a negative speed on it; esmini's reading). A step travels
      // its end speed times dt, as a step on a lane does.
      s_next = s_ + facing_ * entity.speed_command * dt;
      beyond = std::max(0.0, s_next - path_.length());
      const bool toward_start = facing_ * entity.speed_command < 0.0;
      ended_ = toward_start ? s_next <= 1e-9 : s_next >= path_.length() - 1e-9;
      // The direction of travel stays as it started; the stated headings turn the actor only.
      const double clamped = std::clamp(s_next, 0.0, path_.length());
      face = !ignore_stated_ && path_.stated_heading_at(clamped) ? stated_facing(clamped) : facing_;
    }
    s_next = std::clamp(s_next, 0.0, path_.length());
    const double turn = face < 0.0 ? std::numbers::pi : 0.0;
    const PathPoint p = continued(s_next + beyond);
    entity.pose_command = Pose{p.x, p.y, p.z, wrap_angle(p.h + turn), 0.0, 0.0};
    s_ = s_next;
  }

  bool finished() const override { return ended_; }

 private:
  // +1 if the heading stated at s (there must be one) is within 90 degrees of the path's
  // direction there, -1 if it faces against the path.
  double stated_facing(double s) const {
    return std::cos(*path_.stated_heading_at(s) - path_.at(s).h) < 0.0 ? -1.0 : 1.0;
  }

  // True if an untimed actor facing `facing` (+1 along the path, -1 against it) at `speed` m/s
  // would drive off the path where it starts: toward the start from the start, or toward the
  // end from the end. At a speed of 0 there is no direction of travel yet.
  bool leaves_no_path(double facing, double speed) const {
    const double direction = facing * speed;
    if (direction == 0.0) {
      return false;
    }
    return direction < 0.0 ? s_ <= 1e-9 : s_ >= path_.length() - 1e-9;
  }

  // The warning for stated headings set aside, at the starting vertex's line.
  void warn_ignored_headings(ActionContext& context, double speed) const {
    const auto* polyline = std::get_if<xosc::Polyline>(&action_.trajectory.shape);
    const size_t index = path_.vertex_index_at(s_);
    const xosc::Source& source = polyline && index < polyline->vertices.size()
                                     ? polyline->vertices[index].source
                                     : action_.source;
    const bool against = stated_facing(s_) < 0.0;
    context.state.diagnostics.add_once(
        "follow-trajectory-heading-ignored:" + source.file_name() + ":" +
            std::to_string(source.line),
        source.warning("trajectory '" + action_.trajectory.name + "': the vertex's heading faces " +
                       (against ? "against" : "along") + " the path, which at a " +
                       (speed < 0.0 ? "negative" : "positive") +
                       " speed drives off the path where the actor starts; the trajectory's "
                       "stated headings are ignored and the actor faces " +
                       (facing_ < 0.0 ? "against" : "along") + " the path"));
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

  const xosc::FollowTrajectoryAction& action_;
  std::optional<xosc::Timing> timing_;
  TrajectoryPath path_;
  double s_ = 0.0;           ///< m along the path
  double start_time_ = 0.0;  ///< s
  double time_shift_ = 0.0;  ///< s of trajectory time skipped by initialDistanceOffset
  bool ended_ = false;
  bool first_step_ = true;  ///< facing_ is set in the first step
  /// The starting vertex's stated heading would drive an untimed actor off the path at once: the
  /// stated headings are set aside (standard reading).
  bool ignore_stated_ = false;
  /// +1 if the actor faces along the path (a positive speed drives toward its end), -1 if it
  /// faces against it (a positive speed drives toward its start).
  double facing_ = 1.0;
};

}  // namespace

std::unique_ptr<ActionInstance> make_follow_trajectory_action(
    const xosc::FollowTrajectoryAction& action) {
  return std::make_unique<FollowTrajectoryInstance>(action);
}

}  // namespace corsa::engine::detail
