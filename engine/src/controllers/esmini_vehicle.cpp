// esmini's simple vehicle model and its interactiveDriver and offroadFollower controllers
// (controllers/esmini_vehicle.h).

#include "controllers/esmini_vehicle.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <numbers>
#include <string>

#include "controllers/controllers.h"
#include "controllers/follow_view.h"
#include "corsa/xodr/map.h"
#include "corsa/xodr/map_parts.h"
#include "corsa/xosc/scenario.h"
#include "geometry/angle.h"
#include "motion/pose_command.h"
#include "positions/position_resolver.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

constexpr double kEsminiFullTurn = 2.0 * std::numbers::pi;
// esmini's vehicle.cpp.
constexpr double kEsminiPivotFraction = 0.15;  // the model's reference point, of the length
constexpr double kWheelReturn = 4.0;           // 1/s, the wheel's return toward straight
constexpr double kEngineBrake = 0.001;         // of the speed, every step without throttle
constexpr double kBinarySteerScale = 0.02;     // s^2/m^2, the wheel's range shrinking with speed
constexpr double kAnalogSteerScale = 0.005;    // s^2/m^2, the same under analog control
constexpr double kNoThrottle = 1e-10;          // esmini's SMALL_NUMBER
// esmini's Position::GetSpeedLimit, m/s.
constexpr double kLimitOffRoad = 70.0 / 3.6;
constexpr double kLimitMultiLane = 120.0 / 3.6;
constexpr double kLimitSingleLane = 60.0 / 3.6;
// offroadFollower: the follower may drive this much above the speed limit to catch up.
constexpr double kFollowerLimitFactor = 1.2;

}  // namespace

[[gnu::hot]] void single_track_step(double& x, double& y, double& h, double speed, double wheel,
                                    double length, double dt, CourseTrig* trig) {
  // A straight wheel (exactly 0, as a wheel returning to straight ends up) slips by nothing:
  // kEsminiPivotFraction * wheel is the same signed 0 that atan(k tan(wheel)) gives, and its
  // sine is that 0 again.
  const bool straight = wheel == 0.0;
  const double slip =
      straight ? kEsminiPivotFraction * wheel : std::atan(kEsminiPivotFraction * std::tan(wheel));
  const double course = h + slip;
  const double yaw_rate =
      speed * (straight ? slip : std::sin(slip)) / (length * kEsminiPivotFraction);
  // fmod(a, 2 pi) is a itself for a in [0, 2 pi) (a -0 stays -0 either way).
  const double turned = h + dt * yaw_rate;
  h = turned >= 0.0 && turned < kEsminiFullTurn ? turned : std::fmod(turned, kEsminiFullTurn);
  if (h < 0.0) h += kEsminiFullTurn;
  const uint64_t course_bits = std::bit_cast<uint64_t>(course);
  double cos_course = 0.0;
  double sin_course = 0.0;
  if (trig != nullptr && trig->valid && trig->course_bits == course_bits) {
    cos_course = trig->cos;
    sin_course = trig->sin;
  } else {
    cos_course = std::cos(course);
    sin_course = std::sin(course);
    if (trig != nullptr) {
      *trig = CourseTrig{true, course_bits, cos_course, sin_course};
    }
  }
  x += dt * speed * cos_course;
  y += dt * speed * sin_course;
}

[[gnu::hot]] void place_entity_at_model(double x, double y, double h, double speed, Entity& entity,
                                        const MotionContext& motion) {
  // A model that did not move its entity (esmini's at rest, whose speed only nears 0) keeps the
  // pose, lane and road it has, off the road or on its lane: only the speed and what follows
  // from it change.
  constexpr double kSurfaceWithin = 0.5;  // m from a lane, the road's height and pitch are taken
  const double heading = remainder_full_turn(h);
  // (One with a lane at its point is not clear of the lanes: at most one of the two holds.)
  if (entity.lane.on_road && keeps_pose_on_lane(entity, x, y, heading, kSurfaceWithin, motion)) {
    move_at_controller_speed(entity, speed, [&] { hold_pose_on_lane(entity, motion); });
    return;
  }
  if (keeps_pose_off_lanes(entity, x, y, heading, motion)) {
    move_at_controller_speed(entity, speed, [&] { hold_pose_off_lanes(entity, motion); });
    return;
  }
  Pose pose = entity.state().pose;
  pose.x = x;
  pose.y = y;
  pose.h = heading;
  if (motion.map != nullptr) {
    if (const xodr::SurfacePose* surface =
            surface_near(entity, *motion.map, x, y, kSurfaceWithin)) {
      pose.z = surface->z;
      pose.p = surface->p;
    }
  }
  entity.pose_command = pose;
  move_at_controller_speed(entity, speed, [&] { move_to_pose_command(entity, motion); });
}

namespace {

void integrate(EsminiVehicle& car, double dt) {
  single_track_step(car.x, car.y, car.h, car.speed, car.wheel, car.length, dt, &car.course_trig);
}

}  // namespace

[[gnu::hot]] SpeedLimitMemo speed_limit_of(const xodr::Map& map, const RoadCoordinates& at) {
  const xodr::Road& road = map.road(at.road);
  const int side = at.lane < 0 ? -1 : 1;
  SpeedLimitMemo memo{true, at.road, at.section, side};
  // The types from the first up to the first beyond s: any s from the furthest of them to that
  // one takes the same.
  std::optional<double> typed;
  for (const xodr::RoadType& type : road.types) {
    if (type.s > at.s) {
      memo.s_to = type.s;
      break;
    }
    typed = type.max_speed;
    memo.s_from = std::max(memo.s_from, type.s);
  }
  if (typed && *typed > 0.0) {
    memo.limit = *typed;
  } else if (at.section >= road.lane_sections.size()) {
    memo.limit = kLimitSingleLane;
  } else {
    int driving = 0;
    for (const xodr::Lane& lane : road.lane_sections[at.section].lanes) {
      if (lane.id * side > 0 && xodr::is_drivable(lane.type)) ++driving;
    }
    memo.limit = driving > 1 ? kLimitMultiLane : kLimitSingleLane;
  }
  return memo;
}

[[gnu::hot]] double speed_limit_at(const xodr::Map* map, const std::optional<RoadCoordinates>& at,
                                   SpeedLimitMemo& memo) {
  if (map == nullptr || !at) {
    return kLimitOffRoad;
  }
  // A NaN s fails the comparisons: read again.
  if (!(memo.valid && memo.road == at->road && memo.section == at->section &&
        memo.side == (at->lane < 0 ? -1 : 1) && at->s >= memo.s_from && at->s < memo.s_to)) {
    memo = speed_limit_of(*map, *at);
  }
  return memo.limit;
}

namespace {

// The model started from the entity: on the first step, after a step it did not drive, and
// after something else moved the entity (a TeleportAction): esmini's model would otherwise put
// it back where the model was.
void start_model(EsminiDriver& driver, const Entity& entity, int64_t tick) {
  if (driver.started && driver.last_tick + 1 == tick && entity.state().pose.x == driver.car.x &&
      entity.state().pose.y == driver.car.y) {
    driver.last_tick = tick;
    return;
  }
  EsminiVehicle& car = driver.car;
  const double steering_rate = car.steering_rate;
  car = EsminiVehicle{};
  car.steering_rate = steering_rate;
  car.x = entity.state().pose.x;
  car.y = entity.state().pose.y;
  car.h =
      entity.state().pose.h - kEsminiFullTurn * std::floor(entity.state().pose.h / kEsminiFullTurn);
  car.speed = entity.state().speed;
  if (entity.info.box.length > 0.0) car.length = entity.info.box.length;
  if (entity.info.max_acceleration > 0.0) car.max_acceleration = entity.info.max_acceleration;
  if (entity.info.max_deceleration > 0.0) car.max_deceleration = entity.info.max_deceleration;
  driver.started = true;
  driver.last_tick = tick;
}

void place_at_model(const EsminiVehicle& car, double speed, Entity& entity,
                    const MotionContext& motion) {
  place_entity_at_model(car.x, car.y, car.h, speed, entity, motion);
}

void step_interactive(SimState& state, uint32_t index, EsminiDriver& driver,
                      const MotionContext& motion) {
  Entity& entity = state.world.entities[index];
  const ControlState& control = state.controls[index];
  EsminiVehicle& car = driver.car;
  const double limit =
      driver.speed_factor * speed_limit_at(state.map, entity.state().road, driver.speed_limit);
  car.max_speed = entity.info.max_speed > 0.0 ? std::min(limit, entity.info.max_speed) : limit;
  if (control.longitudinal && control.lateral) {
    roll_neutral(car, motion.dt);
    place_at_model(car, car.speed, entity, motion);
    return;
  }
  if (control.longitudinal) {
    // Along its lane at the model's speed (engine brake, top speed), as the default controller
    // moves it.
    car.speed = std::clamp(car.speed * (1.0 - kEngineBrake), -car.max_speed, car.max_speed);
    move_at_controller_speed(entity, car.speed, [&] { DefaultController{}.step(entity, motion); });
    car.x = entity.state().pose.x;
    car.y = entity.state().pose.y;
    car.h = entity.state().pose.h -
            kEsminiFullTurn * std::floor(entity.state().pose.h / kEsminiFullTurn);
    return;
  }
  // The lateral domain alone: the wheel returns to straight, the speed is the actions' (esmini:
  // its default controller's).
  car.speed = entity.speed_command;
  const double scale = 1.0 / (1.0 + kBinarySteerScale * car.speed * car.speed);
  car.wheel *= 1.0 - kWheelReturn * motion.dt;
  car.wheel = std::clamp(car.wheel, -scale * kEsminiMaxWheelAngle, scale * kEsminiMaxWheelAngle);
  integrate(car, motion.dt);
  place_at_model(car, car.speed, entity, motion);
}

void step_offroad_follower(SimState& state, uint32_t index, EsminiDriver& driver,
                           const MotionContext& motion, const FollowView& view) {
  Entity& entity = state.world.entities[index];
  if (!driver.follow || *driver.follow >= view.targets().size() ||
      !view.targets()[*driver.follow].present) {
    return;  // nothing to follow: esmini's controller leaves the car where it is
  }
  const FollowTarget& lead = view.targets()[*driver.follow];
  EsminiVehicle& car = driver.car;
  const double limit =
      kFollowerLimitFactor * speed_limit_at(state.map, entity.state().road, driver.speed_limit);
  car.max_speed = entity.info.max_speed > 0.0 ? std::min(limit, entity.info.max_speed) : limit;
  const double dx = lead.x - entity.state().pose.x;
  const double dy = lead.y - entity.state().pose.y;
  const double direction = remainder_full_turn(std::atan2(dy, dx) - entity.state().pose.h);
  const double distance = std::hypot(dx, dy);
  const double steering = std::clamp(direction, -1.0, 1.0);
  const double throttle = std::clamp(
      0.5 * (distance - driver.target_distance) - 0.5 * (entity.state().speed - lead.speed), -1.0,
      1.0);
  drive_analog(car, motion.dt, throttle, steering);
  place_at_model(car, car.speed, entity, motion);
}

// A property of an esmini driver as a number; absent or not a number (warned): `fallback`.
double number_property(SimState& state, const xosc::Controller& controller, const char* name,
                       double fallback) {
  return nonnegative_property(state, controller, name, controller.name.c_str()).value_or(fallback);
}

}  // namespace

void drive_analog(EsminiVehicle& car, double dt, double throttle, double steering) {
  const double before = car.speed;
  if (car.handbrake) {
    // Released once the throttle is let go or pressed forward.
    if (std::abs(throttle) < kNoThrottle || throttle > kNoThrottle) car.handbrake = false;
  } else {
    car.speed += (throttle < 0.0 ? car.max_deceleration : car.max_acceleration) * throttle * dt;
    if (before > 0.0 && car.speed < 0.0) {
      car.speed = 0.0;
      car.handbrake = true;
    } else {
      if (std::abs(throttle) < kNoThrottle) car.speed *= 1.0 - kEngineBrake;
      car.speed = std::clamp(car.speed, -car.max_speed, car.max_speed);
    }
  }
  const double scale = 1.0 / (1.0 + kAnalogSteerScale * car.speed * car.speed);
  car.wheel += scale * car.steering_rate * steering * dt;
  car.wheel *= 1.0 - kWheelReturn * dt;
  car.wheel = std::clamp(car.wheel, -scale * kEsminiMaxWheelAngle, scale * kEsminiMaxWheelAngle);
  integrate(car, dt);
}

[[gnu::hot]] void roll_neutral(EsminiVehicle& car, double dt) {
  if (!car.handbrake) {
    car.speed = std::clamp(car.speed * (1.0 - kEngineBrake), -car.max_speed, car.max_speed);
  }
  const double scale = 1.0 / (1.0 + kBinarySteerScale * car.speed * car.speed);
  car.wheel *= 1.0 - kWheelReturn * dt;
  car.wheel = std::clamp(car.wheel, -scale * kEsminiMaxWheelAngle, scale * kEsminiMaxWheelAngle);
  integrate(car, dt);
}

bool assign_esmini_driver(SimState& state, uint32_t index, const xosc::ObjectController& oc) {
  const xosc::Controller& c = oc.controller;
  const std::string type = esmini_type(c);
  auto driver = std::make_shared<EsminiDriver>();
  if (type == "InteractiveController" || type == "interactiveDriver") {
    driver->kind = EsminiDriverKind::kInteractive;
    driver->speed_factor = number_property(state, c, "speedFactor", driver->speed_factor);
  } else if (type == "OffroadFollower" || type == "offroadFollower") {
    driver->kind = EsminiDriverKind::kOffroadFollower;
    driver->target_distance = number_property(state, c, "targetDistance", 20.0);
    for (const xosc::Property& property : c.properties.properties) {
      if (property.name != "followEntity") continue;
      driver->follow = state.world.find(property.value);
      if (!driver->follow) {
        state.diagnostics.add(property.source.warning(
            "offroadFollower followEntity '" + property.value +
            "' names no entity: the car stands, as esmini's controller leaves it"));
      }
    }
  } else {
    return false;
  }
  // esmini's default wheel rate is its vehicle's (5 rad/s); both controllers set 4 by default.
  driver->car.steering_rate = number_property(state, c, "steeringRate", 4.0);
  ControlState& control = control_of(state, index);
  control.kind = ControllerKind::kEsminiVehicle;
  control.substitute_for.clear();
  control.esmini_driver = std::move(driver);
  return true;
}

bool esmini_driver_reads_view(const EsminiDriver* driver) {
  return driver != nullptr && driver->kind == EsminiDriverKind::kOffroadFollower;
}

[[gnu::hot]] void step_esmini_driver(SimState& state, uint32_t index, const MotionContext& motion,
                                     const FollowView& view) {
  ControlState& control = state.controls[index];
  if (!control.esmini_driver) {
    DefaultController{}.step(state.world.entities[index], motion);
    return;
  }
  EsminiDriver& driver = *control.esmini_driver;
  start_model(driver, state.world.entities[index], state.tick);
  if (driver.kind == EsminiDriverKind::kInteractive) {
    step_interactive(state, index, driver, motion);
  } else {
    step_offroad_follower(state, index, driver, motion, view);
  }
}

}  // namespace corsa::engine::detail
