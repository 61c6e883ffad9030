// esmini's sloppyDriver, emulated (controllers/sloppy_driver.h).

#include "controllers/sloppy_driver.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <numbers>
#include <string>

#include "controllers/controllers.h"
#include "corsa/xosc/scenario.h"
#include "motion/controller.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

// esmini's ControllerSloppyDriver.
constexpr double kSloppySpeedPeriod = 3.0;         // s, mean time between speed targets
constexpr double kSloppyLateralPeriod = 1.5;       // s, mean time between lateral targets
constexpr double kSloppySpeedSpread = 0.35;        // of the reference speed, at sloppiness 1
constexpr double kSloppyLateralScale = 5.0;        // m, the lateral target at sloppiness 1
constexpr double kSloppyOffsetGain = -0.02;        // rad per m of lateral error, per m driven
constexpr double kSloppyHeadingGain = -0.05;       // rad per rad of heading error, per m driven
constexpr double kSloppySpeedChangeSeen = 1e-3;    // m/s: a speed set from elsewhere
constexpr double kSloppyMovingSpeed = 1e-10;       // m/s, esmini's SMALL_NUMBER
constexpr double kEsminiWordRange = 4294967296.0;  // 2^32: the values of one mt19937 word

// The longitudinal domain: a new target at each period's end and the speed blended toward it
// (the entity then moves along its lane at that speed: esmini's additive mode moves the difference
// on top of its default controller's move, so both modes end the step the same distance on).
void sloppy_longitudinal(SloppyDriver& driver, EsminiRandom& random) {
  if (driver.speed_timer.expired(driver.clock)) {
    driver.speed_timer.duration = kSloppySpeedPeriod * random.real_between(0.5, 1.5);
    driver.speed_timer.start = driver.clock;
    driver.initial_speed = driver.reference_speed * driver.target_factor;
    driver.target_factor =
        1.0 + driver.sloppiness * random.real_between(-kSloppySpeedSpread, kSloppySpeedSpread);
  }
  const double weight = driver.speed_timer.elapsed(driver.clock) / driver.speed_timer.duration;
  driver.current_speed = std::max(driver.initial_speed * (1.0 - weight) +
                                      driver.target_factor * driver.reference_speed * weight,
                                  0.0);
}

// The lateral domain: a new target offset at each period's end, then one step of the steering
// law toward it; the entity's lane offset and heading take the change.
void sloppy_lateral(SloppyDriver& driver, EsminiRandom& random, Entity& entity, double speed,
                    double heading_before, double dt) {
  if (driver.lateral_timer.expired(driver.clock)) {
    driver.fuzz_start = driver.fuzz_target;
    driver.fuzz_target = kSloppyLateralScale * driver.sloppiness *
                         std::min(driver.sloppiness, 1.0) * random.real_between(0.5, 1.5);
    driver.lateral_timer.duration = kSloppyLateralPeriod * random.real_between(0.5, 1.5);
    driver.lateral_timer.start = driver.clock;
  }
  // esmini's override mode steers on the entity's own heading, its additive mode on the
  // heading it has made.
  double heading_error = driver.override_mode ? heading_before : driver.heading;
  if (heading_error > std::numbers::pi) heading_error -= 2.0 * std::numbers::pi;
  const double fuzz = driver.fuzz_start + (driver.fuzz_target - driver.fuzz_start) *
                                              driver.lateral_timer.elapsed(driver.clock) /
                                              driver.lateral_timer.duration;
  const double error = driver.offset + fuzz;
  const double turn = (kSloppyOffsetGain * error + kSloppyHeadingGain * heading_error) * dt * speed;
  const double shift = speed * dt * std::sin(driver.heading + turn);
  if (speed <= kSloppyMovingSpeed) {
    return;
  }
  LaneFollow& lane = entity.lane;
  lane.lateral += shift;
  entity.lateral_command += shift;
  lane.heading_offset = driver.override_mode ? driver.heading + turn : heading_before + turn;
  entity.write_state().lateral_speed = shift / dt;
  driver.offset += shift;
  driver.heading += turn;
}

void step_sloppy_driver(SimState& state, uint32_t index, SloppyDriver& driver,
                        const MotionContext& motion) {
  Entity& entity = state.world.entities[index];
  const ControlState& control = state.controls[index];
  driver.clock += motion.dt;
  // A speed set from elsewhere (an action) becomes the reference (esmini: the entity's speed
  // differs from the one it gave).
  const bool command_changed = entity.speed_command != driver.last_command;
  driver.last_command = entity.speed_command;
  const double object_speed =
      (!control.longitudinal || command_changed) ? entity.speed_command : driver.current_speed;
  if (std::abs(object_speed - driver.current_speed) > kSloppySpeedChangeSeen) {
    driver.reference_speed = object_speed;
  }
  driver.current_speed = object_speed;
  const double heading_before = entity.lane.heading_offset;
  double lateral_speed = object_speed;
  if (control.longitudinal) {
    sloppy_longitudinal(driver, *state.esmini_random);
    if (driver.override_mode) lateral_speed = driver.current_speed;
  }
  // The lane move: at the blended speed when it drives the longitudinal domain, else at the
  // actions' speed (esmini's default controller).
  const double commanded = entity.speed_command;
  if (control.longitudinal) {
    entity.speed_command = std::abs(object_speed) > kSloppyMovingSpeed ? driver.current_speed : 0.0;
  }
  DefaultController{}.step(entity, motion);
  if (control.longitudinal) {
    entity.speed_command = commanded;
    entity.write_state().speed = driver.current_speed;
  }
  if (control.lateral && entity.lane.on_road && state.map != nullptr) {
    sloppy_lateral(driver, *state.esmini_random, entity, lateral_speed, heading_before, motion.dt);
    update_pose_from_lane(entity, *state.map, *motion.scratch);
  }
}

// The lateral domain beside another controller's longitudinal one (ControlState::partner): the
// other has moved the entity along its lane at its speed; the steering law then shifts it with the
// speed and heading the step began with (esmini steps the sloppy driver, assigned first, before
// the other).
void steer_sloppy_partner(SimState& state, uint32_t index, SloppyDriver& driver,
                          const DomainPartner& partner, const MotionContext& motion) {
  Entity& entity = state.world.entities[index];
  driver.clock += motion.dt;
  driver.last_command = entity.speed_command;
  if (entity.lane.on_road && state.map != nullptr) {
    sloppy_lateral(driver, *state.esmini_random, entity, partner.step_start_speed,
                   partner.step_start_heading, motion.dt);
    update_pose_from_lane(entity, *state.map, *motion.scratch);
  }
}

}  // namespace

double EsminiRandom::real_between(double low, double high) {
  // libstdc++'s generate_canonical<double, 53>: two words, the first the low one.
  double sum = static_cast<double>(engine_());
  sum += static_cast<double>(engine_()) * kEsminiWordRange;
  double canonical = sum / (kEsminiWordRange * kEsminiWordRange);
  if (canonical >= 1.0) canonical = std::nextafter(1.0, 0.0);
  return canonical * (high - low) + low;
}

EsminiRandom EsminiRandom::after_entities(uint32_t seed, size_t entities) {
  constexpr size_t kDrawsPerEntity = 2;
  EsminiRandom random(seed);
  for (size_t i = 0; i < kDrawsPerEntity * entities; ++i) random.real_between(0.0, 1.0);
  return random;
}

bool is_sloppy_driver(const xosc::ObjectController& oc) {
  const std::string type =
      oc.controller.properties.get("esminiController").value_or(oc.controller.name);
  return type == "SloppyDriverController" || type == "sloppyDriver";
}

std::shared_ptr<SloppyDriver> make_sloppy_driver(SimState& state,
                                                 const xosc::ObjectController& oc) {
  auto driver = std::make_shared<SloppyDriver>();
  for (const xosc::Property& property : oc.controller.properties.properties) {
    if (property.name == "sloppiness") {
      char* end = nullptr;
      const double value = std::strtod(property.value.c_str(), &end);
      if (end != property.value.c_str() && *end == '\0' && std::isfinite(value)) {
        driver->sloppiness = value;
      } else {
        state.diagnostics.add(
            property.source.warning("sloppyDriver property 'sloppiness' is not a number ('" +
                                    property.value + "'): its default 0.5 is used"));
      }
    } else if (property.name == "mode") {
      driver->override_mode = property.value != "additive";
    }
  }
  if (!state.esmini_random) {
    // esmini's seed is an unsigned int.
    state.esmini_random = std::make_shared<EsminiRandom>(EsminiRandom::after_entities(
        static_cast<uint32_t>(state.options.seed), state.scenario.entities.objects.size()));
  }
  return driver;
}

void activate_sloppy_driver(SloppyDriver& driver, const Entity& entity) {
  driver.speed_timer = SloppyTimer{0.0, kSloppySpeedPeriod};
  driver.target_factor = 1.0;
  driver.current_speed = entity.state().speed;
  driver.initial_speed = entity.state().speed;
  driver.reference_speed = entity.state().speed;
  driver.last_command = entity.speed_command;
  driver.lateral_timer = SloppyTimer{0.0, kSloppyLateralPeriod};
  driver.fuzz_start = 0.0;
  driver.fuzz_target = 0.0;
  driver.offset = 0.0;
  driver.heading = entity.lane.heading_offset;
}

void step_sloppy_drivers(SimState& state, const MotionContext& motion) {
  const auto count = static_cast<uint32_t>(state.world.entities.size());
  for (uint32_t i = 0; i < count && i < state.controls.size(); ++i) {
    ControlState& control = state.controls[i];
    Entity& entity = state.world.entities[i];
    if (!control.sloppy || !entity.state().placed || entity.towed_by || state.frozen(i)) {
      continue;
    }
    if (control.effective() == ControllerKind::kSloppyDriver) {
      step_sloppy_driver(state, i, *control.sloppy, motion);
    } else if (!control.commanded && control.partner &&
               control.partner->kind == ControllerKind::kSloppyDriver && control.partner->lateral) {
      steer_sloppy_partner(state, i, *control.sloppy, *control.partner, motion);
    }
  }
}

}  // namespace corsa::engine::detail
