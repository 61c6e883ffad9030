#pragma once

// esmini's simple vehicle model (its vehicle.cpp) and two of esmini's controllers that drive it,
// which esmini's example scenarios name:
//   - interactiveDriver (esminiController InteractiveController): a person drives with the
//     arrow keys. A run without a window (headless, as a regression run is) presses no key, so
//     the throttle and the wheel stay neutral: the car rolls on from the pose and speed it had
//     when the controller was activated, its speed shrinking by esmini's engine brake (a factor
//     1 - 0.001 every step) and held within min(speedFactor x speed limit, maxSpeed), its wheel
//     straight. Active in both domains it drives straight along its heading (it does not follow
//     the road); in the longitudinal domain alone it moves along its lane at that speed; in the
//     lateral domain alone it drives straight at the speed the actions give. In esmini's
//     default mode (override) the storyboard's speed and lane actions do not move it while it
//     is active, as here.
//   - offroadFollower (esminiController OffroadFollower): drives after the entity its property
//     `followEntity` names, over the ground and not along lanes: it steers toward the other's
//     reference point (wheel rate: steeringRate x the angle to it, within +-1) and works the
//     throttle by 0.5 (distance - targetDistance) - 0.5 (own speed - its speed), within +-1,
//     between reference points; its top speed is 1.2 x the speed limit where it is, or its
//     Performance maxSpeed if less. The others are seen as at the beginning of the step
//     (controllers/follow_view.h).
//
// The model (esmini's vehicle.cpp): a kinematic single-track model about a point 15% of the
// length ahead of the rear axle; the wheel returns to straight by the factor 1 - 4 dt a step,
// turns at most 60 degrees, less with speed; the throttle adds maxAcceleration x throttle
// (maxDeceleration when braking) and rolling back through zero stops the car until the throttle
// is released. The speed limit is esmini's: the road type's speed at the entity's s, or without
// one 120 km/h where its side of the road has more than one lane for driving and 60 km/h where
// not; 70 km/h off every road.
//
// Both controllers start their model from the entity's pose and speed when they first move it,
// again after a step in which they did not (esmini resets its model on activation), and after
// something else moved the entity (a TeleportAction).

#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>

#include "motion/controller.h"

namespace corsa::xosc {
struct ObjectController;
}  // namespace corsa::xosc

namespace corsa::engine::detail {

struct SimState;
class FollowView;

/// The cosine and sine of the course a single-track step last moved along: a model whose wheel
/// stands straight keeps its heading, and moves along the same course step after step (esmini's
/// interactiveDriver with no key pressed). The same bits give the same values.
struct CourseTrig {
  bool valid = false;
  uint64_t course_bits = 0;
  double cos = 0.0;
  double sin = 0.0;
};

/// esmini's vehicle model: state and parameters (SI units, heading in [0, 2 pi)).
struct EsminiVehicle {
  double x = 0.0, y = 0.0, h = 0.0;  ///< m, m, rad
  double speed = 0.0;                ///< m/s
  double wheel = 0.0;                ///< rad, the front wheels' angle
  bool handbrake = false;            ///< stopped after rolling back through zero
  double length = 5.0;               ///< m, the bounding box's
  double max_speed = 70.0;           ///< m/s
  double max_acceleration = 20.0;    ///< m/s^2
  double max_deceleration = 20.0;    ///< m/s^2
  double steering_rate = 5.0;        ///< rad/s at full wheel input
  CourseTrig course_trig;            ///< of the last step (single_track_step)
};

/// esmini's vehicle model: the front wheels' largest angle (rad), less with speed.
inline constexpr double kEsminiMaxWheelAngle = 60.0 * std::numbers::pi / 180.0;

/// One kinematic single-track step of esmini's vehicle model about a point 15% of `length`
/// ahead of the rear axle, with the front wheels at `wheel`: (x, y) moves along the heading of
/// the step's start plus the slip angle, h (rad, kept in [0, 2 pi)) turns. `trig`, when given,
/// keeps the course's cosine and sine for the next step along the same course.
void single_track_step(double& x, double& y, double& h, double speed, double wheel, double length,
                       double dt, CourseTrig* trig = nullptr);

/// Puts `entity` at a vehicle model's pose (x, y, h; the height and pitch of the road surface
/// there) with `speed`, as a pose command (move_at_controller_speed, controllers.h).
void place_entity_at_model(double x, double y, double h, double speed, Entity& entity,
                           const MotionContext& motion);

/// One step of esmini's analog control: throttle and steering in [-1, 1].
void drive_analog(EsminiVehicle& car, double dt, double throttle, double steering);

/// One step of esmini's binary control with no key pressed: the engine brake slows the car, the
/// wheel returns toward straight.
void roll_neutral(EsminiVehicle& car, double dt);

/// Which of esmini's controllers an EsminiDriver is.
enum class EsminiDriverKind : uint8_t { kInteractive, kOffroadFollower };

/// The speed limit esmini's driver read last (m/s), and where it holds: on `road`, lane section
/// `section`, the side of the lanes of sign `side`, for s in [s_from, s_to).
struct SpeedLimitMemo {
  bool valid = false;
  uint32_t road = 0;
  uint32_t section = 0;
  int side = 0;
  double s_from = -std::numeric_limits<double>::infinity();
  double s_to = std::numeric_limits<double>::infinity();
  double limit = 0.0;
};

/// esmini's speed limit (m/s) at road coordinates `at` (its Position::GetSpeedLimit): the road
/// type's speed at s, else by the number of drivable lanes on the side of `at.lane`; with the
/// stretch of the road over which it is the same.
SpeedLimitMemo speed_limit_of(const xodr::Map& map, const RoadCoordinates& at);

/// esmini's speed limit (m/s) at `at`, off the road (no `at`, or no map) 70 km/h: `memo`'s
/// while `at` lies in the stretch it holds for, else read again (speed_limit_of) into `memo`.
double speed_limit_at(const xodr::Map* map, const std::optional<RoadCoordinates>& at,
                      SpeedLimitMemo& memo);

/// An entity's esmini driver: its properties and its vehicle model between steps.
struct EsminiDriver {
  EsminiDriverKind kind = EsminiDriverKind::kInteractive;
  double speed_factor = 1.0;  ///< interactiveDriver: property speedFactor
  /// offroadFollower: the entity followed (property followEntity; none: the car stands).
  std::optional<uint32_t> follow;
  double target_distance = 20.0;  ///< m, offroadFollower: property targetDistance
  EsminiVehicle car;
  bool started = false;
  int64_t last_tick = 0;  ///< the tick of the model's last step
  SpeedLimitMemo speed_limit;
};

/// Gives entity `index` esmini's driver when `oc` is interactiveDriver or offroadFollower
/// (its Property esminiController, else the Controller's name), with its properties; returns
/// false for any other controller. A property that is not a number, or a followEntity that
/// names no entity, warns located at the property.
bool assign_esmini_driver(SimState& state, uint32_t index, const xosc::ObjectController& oc);

/// Whether `driver` reads the picture of the others (FollowView) in its step: offroadFollower
/// does (the entity it follows); interactiveDriver, and an entity without a driver (the default
/// controller), do not.
bool esmini_driver_reads_view(const EsminiDriver* driver);

/// One step of entity `index`'s esmini driver.
void step_esmini_driver(SimState& state, uint32_t index, const MotionContext& motion,
                        const FollowView& view);

}  // namespace corsa::engine::detail
