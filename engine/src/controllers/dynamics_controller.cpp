// The `dynamics` controller: the vehicle is the single-track model of dynamics_model.h and a
// driver model steers and drives it toward what the actions ask for: pure pursuit (Coulter,
// "Implementation of the Pure Pursuit Path Tracking Algorithm", CMU-RI-TR-92-01) toward a point
// on the commanded path (the followed lane at the commanded lateral offset) a speed-dependent
// distance ahead, and a PI loop with feed-forward on the commanded speed. Acceleration,
// deceleration and speed stay within the vehicle's Performance; steering within its front
// axle's maxSteering. OverrideControllerValueActions replace the driver's throttle, brake and
// steering while active; a command with controls from outside (external_control.h) replaces the
// driver for its step.

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <utility>

#include "controllers/controllers.h"
#include "controllers/dynamics_fleet.h"
#include "controllers/dynamics_model.h"
#include "corsa/xosc/scenario.h"
#include "geometry/angle.h"
#include "lanes/lane_follow.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {

struct DynamicsVehicle {
  explicit DynamicsVehicle(const VehicleParams& params) : model(params) {}
  DynamicsIntegrator model;
  double integral = 0.0;      ///< m, integral of the speed error
  double last_command = 0.0;  ///< m/s, the speed command of the previous step
  Pose pose;                  ///< where the model left the entity (to detect teleports)
  VehicleState before;        ///< the model state at the start of the step under way
  // Override values as applied (rate-limited), throttle/brake 0..1, steering wheel rad.
  double throttle = 0.0, brake = 0.0, steering_wheel = 0.0;
  // The lane centre under the vehicle at the end of the last step (sync_lane).
  LaneFollow foot_lane;
  LanePose foot;
  bool foot_valid = false;
  /// The system the models of all dynamics vehicles of the simulation are integrated in: held
  /// by each of them, so that it lives as long as any does (one per simulation, no global).
  std::shared_ptr<DynamicsFleet> fleet;
};

namespace {

constexpr double kProportionalGain = 1.5;   // 1/s
constexpr double kIntegralGain = 0.4;       // 1/s^2
constexpr double kSteeringRatio = 15.0;     // steering wheel angle / front wheel angle
constexpr double kDefaultAccelLimit = 6.0;  // m/s^2 when the Performance gives none
constexpr double kLookaheadTime = 0.8;      // s
constexpr double kMinLookahead = 4.0;       // m

VehicleParams params_of(const SimState& state, const Entity& entity) {
  VehicleParams p;
  const Box& box = entity.info.box;
  p.wheelbase = box.length > 0.0 ? 0.6 * box.length : 2.8;
  if (entity.object != nullptr) {
    if (const auto* vehicle = std::get_if<xosc::Vehicle>(&entity.object->object)) {
      if (vehicle->axles.front_axle) {
        const double base =
            vehicle->axles.front_axle->position_x - vehicle->axles.rear_axle.position_x;
        if (base > 0.5) {
          p.wheelbase = base;
        }
        if (vehicle->axles.front_axle->max_steering > 0.0) {
          p.max_steering = vehicle->axles.front_axle->max_steering;
        }
      }
      if (vehicle->mass && *vehicle->mass > 0.0) {
        p.mass = *vehicle->mass;
      } else if (box.length > 0.0) {
        // About 330 kg per metre of car; a truck's box gives a heavier vehicle.
        p.mass = std::max(800.0, 330.0 * box.length * std::max(1.0, box.width / 1.8));
      }
    }
  }
  p.cg_to_rear = 0.5 * p.wheelbase;
  // A box of uniform density: Iz = m (l^2 + w^2) / 12.
  const double l = box.length > 0.0 ? box.length : p.wheelbase / 0.6;
  const double w = box.width > 0.0 ? box.width : 1.8;
  p.yaw_inertia = p.mass * (l * l + w * w) / 12.0;
  p.friction = std::max(0.05, state.environment.road_friction_scale);
  return p;
}

double limit_rate(double current, double target, double max_rate, double dt) {
  if (max_rate <= 0.0) {
    return target;
  }
  return current + std::clamp(target - current, -max_rate * dt, max_rate * dt);
}

double max_acceleration(const Entity& entity) {
  return entity.info.max_acceleration > 0.0 ? entity.info.max_acceleration : kDefaultAccelLimit;
}
double max_deceleration(const Entity& entity) {
  return entity.info.max_deceleration > 0.0 ? entity.info.max_deceleration : kDefaultAccelLimit;
}

// The inputs of a command from outside (external_control.h): throttle and brake as shares of the
// Performance limits, the front wheel angle as given; nothing drives beyond maxSpeed.
VehicleInputs commanded_inputs(const Entity& entity, DynamicsVehicle& vehicle,
                               const VehicleControls& controls) {
  VehicleInputs inputs;
  inputs.accel =
      controls.throttle * max_acceleration(entity) - controls.brake * max_deceleration(entity);
  if (entity.info.max_speed > 0.0 && entity.state().speed >= entity.info.max_speed) {
    inputs.accel = std::min(inputs.accel, 0.0);
  }
  inputs.steer = controls.steering;
  vehicle.throttle = controls.throttle;
  vehicle.brake = controls.brake;
  vehicle.steering_wheel = controls.steering * kSteeringRatio;
  // The driver model takes over afresh after the command (no integral or feed-forward jump).
  vehicle.integral = 0.0;
  vehicle.last_command = std::max(0.0, entity.speed_command);
  return inputs;
}

// Longitudinal demand (m/s^2): the PI loop on the commanded speed, or the overrides.
double longitudinal_demand(Entity& entity, DynamicsVehicle& vehicle, const ControlState& control,
                           double dt, bool& reverse) {
  const double max_acc = max_acceleration(entity);
  const double max_dec = max_deceleration(entity);
  const ControllerOverrides& o = control.overrides;
  const double mass = vehicle.model.params().mass;
  reverse = false;
  if (o.throttle.active || o.brake.active || o.parking_brake.active) {
    vehicle.throttle = limit_rate(vehicle.throttle, o.throttle.active ? o.throttle.value : 0.0,
                                  o.throttle.max_rate, dt);
    const auto brake_share = [&](const OverrideSlot& slot) {
      return !slot.active ? 0.0 : slot.force ? slot.value / (mass * max_dec) : slot.value;
    };
    vehicle.brake = limit_rate(
        vehicle.brake, std::clamp(brake_share(o.brake) + brake_share(o.parking_brake), 0.0, 1.0),
        o.brake.max_rate, dt);
    const bool declutched = o.clutch.active && o.clutch.value > 0.5;
    const bool neutral = o.gear_active && o.gear == 0;
    reverse = o.gear_active && o.gear < 0;
    const double drive = declutched || neutral ? 0.0 : vehicle.throttle * max_acc;
    // The speed loop takes over afresh when the overrides end (no feed-forward jump).
    vehicle.integral = 0.0;
    vehicle.last_command = std::max(0.0, entity.speed_command);
    return (reverse ? -drive : drive) - vehicle.brake * max_dec;
  }
  double command = std::max(0.0, entity.speed_command);
  if (entity.info.max_speed > 0.0) {
    command = std::min(command, entity.info.max_speed);
  }
  const double error = command - entity.state().speed;
  const double feed_forward = std::clamp((command - vehicle.last_command) / dt, -max_dec, max_acc);
  vehicle.last_command = command;
  const double raw = feed_forward + kProportionalGain * error + kIntegralGain * vehicle.integral;
  const double demand = std::clamp(raw, -max_dec, max_acc);
  if (demand == raw) {
    vehicle.integral += error * dt;  // no wind-up while saturated
  }
  // At the top speed nothing pushes beyond it.
  if (entity.info.max_speed > 0.0 && entity.state().speed >= entity.info.max_speed) {
    return std::min(demand, 0.0);
  }
  return demand;
}

// The world point (x, y) of a followed lane position, as lane_pose places it (Map::world_pose
// at h = 0), without the z, pitch, roll and containing lane that pure pursuit does not need.
std::pair<double, double> lane_point(const xodr::Map& map, const LaneFollow& follow) {
  const double t = followed_t(map, follow);
  const xodr::RefPoint ref = map.reference(follow.road, follow.s);
  // OpenDRIVE 1.8 §8.4.2: t runs along the normal tilted by the superelevation roll.
  const double horizontal = t * std::cos(map.superelevation(follow.road, follow.s));
  return {ref.x - std::sin(ref.hdg) * horizontal, ref.y + std::cos(ref.hdg) * horizontal};
}

// Front wheel angle (rad) toward the commanded path, by pure pursuit from the rear axle.
double steering_demand(const SimState& state, Entity& entity, const VehicleState& now,
                       double vehicle_wheelbase) {
  if (!entity.lane.on_road || state.map == nullptr) {
    return 0.0;  // off the lanes: hold the heading
  }
  LaneFollow probe = entity.lane;
  probe.lateral = entity.lateral_command;
  probe.heading_offset = 0.0;
  const double lookahead = std::max(kMinLookahead, kLookaheadTime * std::abs(now.vx));
  advance_along_lanes(*state.map, probe, lookahead, entity.chooser);
  const auto [target_x, target_y] = lane_point(*state.map, probe);
  const double dx = target_x - now.x, dy = target_y - now.y;
  const double distance = std::hypot(dx, dy);
  if (distance < 1e-6) {
    return 0.0;
  }
  const double alpha = wrap_angle(std::atan2(dy, dx) - now.yaw);
  // Curvature of the arc through the target: 2 sin(alpha) / distance; wheel angle atan(L k).
  const double wheelbase = vehicle_wheelbase;
  return std::atan(wheelbase * 2.0 * std::sin(alpha) / distance);
}

// The entity's own point beside the lane centre `foot` (same road, section and s; `spans` those
// of that section at s): t, the lane containing it, and its z as Map::world_pose gives it at
// h = 0 (pitch and roll do not depend on t). Cheaper than a second lane_pose: no lane spans and
// no reference line evaluation.
LanePose beside_foot(const xodr::Map& map, const LaneFollow& follow, const LanePose& foot,
                     const std::vector<xodr::LaneSpan>& spans) {
  LanePose out;
  out.t = foot.t + follow.dir * follow.lateral;
  // The lane containing t: borders belong to the inner lane, as Map::lane_at decides.
  for (const auto& span : spans) {
    if (span.width() > 0.0 && out.t >= span.t_min() && out.t <= span.t_max() &&
        (!out.lane_at || std::abs(span.id) < std::abs(*out.lane_at))) {
      out.lane_at = span.id;
    }
  }
  out.pose = foot.pose;
  const double roll = follow.dir < 0 ? -foot.pose.r : foot.pose.r;  // the road's own
  out.pose.z = map.elevation(follow.road, follow.s) + out.t * std::sin(roll) +
               0.0 * std::cos(roll) + map.shape_height(follow.road, follow.s, out.t);
  return out;
}

// Puts the followed lane position under the vehicle: s advanced by the motion along the lane
// (a Newton step on the foot point), lateral offset and heading relative to the lane. The foot
// of the previous step is reused when the followed lane position has not changed since (it has
// when an action moved it to another lane).
void sync_lane(const SimState& state, Entity& entity, DynamicsVehicle& vehicle,
               std::vector<xodr::LaneSpan>& spans) {
  const xodr::Map& map = *state.map;
  LaneFollow centre = entity.lane;
  centre.lateral = 0.0;
  centre.heading_offset = 0.0;
  double moved = 0.0;
  bool hit_end = false;
  const LaneFollow& last = vehicle.foot_lane;
  const bool reuse = vehicle.foot_valid && last.node == centre.node && last.road == centre.road &&
                     last.section == centre.section && last.lane == centre.lane &&
                     last.dir == centre.dir && last.s == centre.s;
  LanePose foot = reuse ? vehicle.foot : lane_pose(map, centre, spans);
  bool spans_current = !reuse;
  {
    // One Newton step on the foot point: exact on lines; on curves the small residual does not
    // accumulate, since every step measures from the vehicle's true position.
    const double c = std::cos(foot.pose.h), s = std::sin(foot.pose.h);
    const double along =
        (entity.state().pose.x - foot.pose.x) * c + (entity.state().pose.y - foot.pose.y) * s;
    if (along != 0.0) {
      const AdvanceResult result = advance_along_lanes(map, centre, along, entity.chooser);
      moved = result.travelled;
      hit_end = result.hit_end;
      foot = lane_pose(map, centre, spans);
      spans_current = true;
    }
  }
  if (!spans_current) {
    map.lane_spans_in_section(centre.road, centre.section, centre.s, spans);
  }
  vehicle.foot_lane = centre;
  vehicle.foot = foot;
  vehicle.foot_valid = true;
  const double c = std::cos(foot.pose.h), s = std::sin(foot.pose.h);
  const double dx = entity.state().pose.x - foot.pose.x, dy = entity.state().pose.y - foot.pose.y;
  centre.lateral = c * dy - s * dx;
  centre.heading_offset = wrap_angle(entity.state().pose.h - foot.pose.h);
  // Carried on from a neighbouring lane's end: the offset asked for moves with the lane frame.
  entity.lateral_command += centre.frame_shift - entity.lane.frame_shift;
  entity.lane = centre;
  entity.longitudinal_distance += std::abs(moved);
  entity.end_of_road = hit_end || (entity.end_of_road && moved == 0.0);
  const LanePose at = beside_foot(map, entity.lane, foot, spans);
  entity.write_state().pose.z = at.pose.z;
  entity.write_state().pose.p = at.pose.p;
  entity.write_state().pose.r = at.pose.r;
  if (at.lane_at) {
    entity.write_state().road =
        RoadCoordinates{entity.lane.road, entity.lane.section, *at.lane_at, entity.lane.s, at.t};
  } else {
    entity.write_state().road.reset();
  }
}

bool same_pose(const Pose& a, const Pose& b) { return a.x == b.x && a.y == b.y && a.h == b.h; }

// The driver model's inputs for entity `index`, and its model's step begun on `fleet`.
void begin_vehicle(SimState& state, uint32_t index, const MotionContext& motion,
                   DynamicsFleet& fleet) {
  Entity& entity = state.world.entities[index];
  ControlState& control = control_of(state, index);
  const double dt = motion.dt;
  if (!control.dynamics) {
    control.dynamics = std::make_shared<DynamicsVehicle>(params_of(state, entity));
    control.dynamics->pose = Pose{std::nan(""), 0.0, 0.0, 0.0, 0.0, 0.0};
  }
  DynamicsVehicle& vehicle = *control.dynamics;
  const EntityState& es = entity.state();
  if (!same_pose(vehicle.pose, es.pose) || vehicle.model.state().vx != es.speed) {
    // New, teleported, or its speed set from outside (a step SpeedAction in Init): start the
    // model there, moving straight.
    VehicleState start;
    start.x = es.pose.x;
    start.y = es.pose.y;
    start.yaw = es.pose.h;
    start.vx = es.speed;
    vehicle.model.reset(start);
    vehicle.last_command = es.speed;
    vehicle.integral = 0.0;
  }
  vehicle.before = vehicle.model.state();
  if (control.commanded && control.command.controls) {
    vehicle.model.begin_step(commanded_inputs(entity, vehicle, *control.command.controls), dt,
                             fleet);
    return;
  }
  VehicleInputs inputs;
  inputs.accel = longitudinal_demand(entity, vehicle, control, dt, inputs.reverse);
  if (control.overrides.steering_wheel.active) {
    vehicle.steering_wheel =
        limit_rate(vehicle.steering_wheel, control.overrides.steering_wheel.value,
                   control.overrides.steering_wheel.max_rate, dt);
    inputs.steer = vehicle.steering_wheel / kSteeringRatio;
  } else {
    inputs.steer = steering_demand(state, entity, vehicle.before, vehicle.model.params().wheelbase);
    vehicle.steering_wheel = inputs.steer * kSteeringRatio;
  }
  vehicle.model.begin_step(inputs, dt, fleet);
}

}  // namespace

void begin_dynamics(SimState& state, std::span<const uint32_t> indices,
                    const MotionContext& motion) {
  std::shared_ptr<DynamicsFleet> fleet;
  for (const ControlState& control : state.controls) {
    if (control.dynamics && control.dynamics->fleet) {
      fleet = control.dynamics->fleet;
      break;
    }
  }
  if (!fleet) {
    fleet = std::make_shared<DynamicsFleet>();
  }
  for (const uint32_t index : indices) {
    begin_vehicle(state, index, motion, *fleet);
    state.controls[index].dynamics->fleet = fleet;
  }
  fleet->integrate(motion.dt);
}

void finish_dynamics(SimState& state, uint32_t index, const MotionContext& motion) {
  Entity& entity = state.world.entities[index];
  DynamicsVehicle& vehicle = *state.controls[index].dynamics;
  const double dt = motion.dt;
  EntityState& es = entity.write_state();
  const VehicleState& before = vehicle.before;
  const VehicleState after = vehicle.model.state();
  const double h0 = es.pose.h;
  const double path = std::hypot(after.x - before.x, after.y - before.y);
  es.pose.x = after.x;
  es.pose.y = after.y;
  es.pose.h = wrap_angle(after.yaw);
  if (entity.lane.on_road && state.map != nullptr) {
    sync_lane(state, entity, vehicle, *motion.scratch);
  } else {
    entity.longitudinal_distance += path;
    update_road_from_pose(entity, state.map);
  }
  double speed = after.vx;
  if (entity.end_of_road && speed > 0.0) {
    // A lane end without successor stops the vehicle as it does under the default controller.
    speed = 0.0;
    VehicleState stopped = after;
    stopped.vx = 0.0;
    stopped.vy = 0.0;
    stopped.yaw_rate = 0.0;
    vehicle.model.reset(stopped);
  }
  es.acceleration = (speed - before.vx) / dt;
  es.speed = speed;
  // The reference point (rear axle) moves sideways at vy - lr r.
  es.lateral_speed = after.vy - vehicle.model.params().cg_to_rear * after.yaw_rate;
  entity.lateral_acceleration = vehicle.model.lateral_acceleration();
  es.yaw_rate = remainder_full_turn(es.pose.h - h0) / dt;
  es.odometer += path;
  vehicle.pose = es.pose;
}

}  // namespace corsa::engine::detail
