#include "corsa/engine/simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "controllers/controllers.h"
#include "controllers/external.h"
#include "controllers/follow_ghost.h"
#include "corsa/xodr/map.h"
#include "corsa/xodr/parser.h"
#include "corsa/xosc/scenario.h"
#include "motion/placement.h"
#include "motion/refpoint_trail.h"
#include "motion/route_lanes.h"
#include "motion/trailers.h"
#include "simulation/simulation_impl.h"
#include "state/entity_builder.h"
#include "state/environment_clock.h"
#include "state/world_contacts.h"
#include "state/world_update.h"
#include "traffic/traffic_generators.h"
#include "traffic/traffic_update.h"

namespace corsa::engine {
namespace {

void check_options(const SimulationOptions& options) {
  if (!(options.dt > 0.0) || !std::isfinite(options.dt) || options.dt > 10.0) {
    throw InputError(Diagnostic{Severity::kError, "", 0, -1, "",
                                "the step dt must be a positive number of seconds up to 10"});
  }
  if (!(options.duration >= 0.0) || !std::isfinite(options.duration)) {
    throw InputError(Diagnostic{Severity::kError, "", 0, -1, "",
                                "the duration must be a finite, non-negative number of seconds"});
  }
}

}  // namespace

Simulation::Impl::Impl(const xosc::Scenario& scenario, std::shared_ptr<const xodr::Map> map,
                       const SimulationOptions& options, Diagnostics& diagnostics)
    : state(scenario, std::move(map), options, diagnostics), mover(options.threads) {
  check_options(options);
  if (options.strict && state.map_owner) {
    // A map is read once and may be shared by runs of both kinds (sweeps), so it records its
    // lenient readings and a strict run refuses them here.
    xodr::refuse_lenient_readings(state.map_owner->data());
  }
  contact_sweep.share = [this](size_t count, const std::function<void(size_t, size_t)>& work) {
    mover.share(count, work);
  };
  for (const auto& [name, value] : options.values) state.given_values[name] = value;
  detail::build_entities(state);
  detail::setup_ghost(state);
  detail::read_refpoint_offsets(state);
  detail::assign_initial_controllers(state);
  detail::init_traffic(state);
  for (const xosc::ParameterDeclaration& p : scenario.parameters) {
    state.parameters.declare(p.name, p.value);
  }
  for (const xosc::VariableDeclaration& v : scenario.variables) {
    state.variables.declare(v.name, v.value);
  }
  for (const xosc::MonitorDeclaration& m : scenario.monitors) state.monitors[m.name] = m.value;
  storyboard = std::make_unique<detail::Storyboard>(state);
  init.run(state);
  detail::trail_refpoints(state, 0.0);
  for (detail::Entity& entity : state.world.entities) {
    if (!entity.state().placed) {
      diagnostics.add(entity.object->source.warning(
          "entity '" + entity.info.name +
          "' has no position in Init (no TeleportAction); it waits at the origin"));
    }
  }
  detail::place_npcs(state);
  detail::update_contacts(state, contact_sweep);
  detail::update_timers(state, false);
  detail::record_trail(state);
}

void Simulation::Impl::announce(const Simulation& owner) {
  announced = true;
  init.run_user_defined(state);
  for (SimulationObserver* observer : observers) {
    observer->on_step(owner);
  }
}

[[gnu::hot]] void Simulation::Impl::advance() {
  // With several threads the mover measures whether sharing out a step pays.
  const bool timed = mover.times_steps();
  const auto began =
      timed ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
  init.step_actions(state);
  storyboard->step_actions(state);
  detail::MotionContext motion{state.map, state.time.dt(), &scratch};
  // With no road network an entity no action moves stands, as esmini, which moves entities along
  // roads only, reads it (the standard says nothing of a default controller without lanes).
  motion.stand_without_roads = state.map == nullptr;
  detail::follow_route_lanes(state, motion);
  detail::begin_commands(state);
  mover.move(state, motion);
  detail::end_commands(state);
  detail::trail_refpoints(state, state.time.dt());
  detail::move_trailers(state, state.time.dt());
  if (state.straight_travel_wanted) {
    detail::sum_straight_travel(state);
  }
  ++state.tick;
  detail::record_trail(state);
  detail::update_traffic(state);
  detail::update_contacts(state, contact_sweep);
  detail::update_timers(state, true);
  init.settle(state);
  storyboard->settle(state);
  if (timed) {
    mover.charge_step(std::chrono::steady_clock::now() - began);
  }
}

Simulation::Simulation(const xosc::Scenario& scenario, std::shared_ptr<const xodr::Map> map,
                       const SimulationOptions& options, Diagnostics& diagnostics)
    : impl_(std::make_unique<Impl>(scenario, std::move(map), options, diagnostics)) {
  impl_->state.simulation = this;
}

Simulation::Simulation(Simulation&&) noexcept = default;
Simulation& Simulation::operator=(Simulation&&) noexcept = default;
Simulation::~Simulation() = default;

[[gnu::hot]] bool Simulation::step() {
  Impl& impl = *impl_;
  detail::SimState& state = impl.state;
  state.simulation = this;
  if (!impl.announced) {
    impl.announce(*this);
  }
  if (impl.end != EndReason::kRunning) {
    return false;
  }
  impl.storyboard->update(state);
  if (impl.storyboard->stopped()) {
    impl.end = EndReason::kStopTrigger;
    return false;
  }
  if (impl.storyboard->finished(state)) {
    impl.end = EndReason::kStoriesComplete;
    return false;
  }
  // The cap in whole ticks (half a step of slack against rounding).
  if (static_cast<double>(state.tick) * state.time.dt() >=
      state.options.duration - 0.5 * state.time.dt()) {
    impl.end = EndReason::kDuration;
    return false;
  }
  impl.advance();
  for (SimulationObserver* observer : impl.observers) {
    observer->on_step(*this);
  }
  return true;
}

void Simulation::run() {
  while (step()) {
  }
}

void Simulation::interrupt() {
  if (impl_->end == EndReason::kRunning) {
    impl_->end = EndReason::kInterrupted;
  }
}

bool Simulation::ended() const { return impl_->end != EndReason::kRunning; }
EndReason Simulation::end_reason() const { return impl_->end; }
int64_t Simulation::tick() const { return impl_->state.tick; }
int64_t Simulation::start_tick() const {
  return impl_->state.ghost ? -impl_->state.ghost->headstart_ticks : 0;
}
int64_t Simulation::steps() const {
  // A ghost restart runs ticks a second time (controllers/follow_ghost.h).
  return tick() - start_tick() + (impl_->state.ghost ? impl_->state.ghost->replayed_ticks : 0);
}
bool Simulation::is_ghost(size_t index) const {
  return impl_->state.world.entities.at(index).ghost;
}
double Simulation::time() const { return impl_->state.now(); }
double Simulation::dt() const { return impl_->state.time.dt(); }
double Simulation::time_of(int64_t tick) const { return impl_->state.time.time(tick); }
const SimulationOptions& Simulation::options() const { return impl_->state.options; }

size_t Simulation::entity_count() const { return impl_->state.world.entities.size(); }
const EntityInfo& Simulation::entity(size_t index) const {
  return impl_->state.world.entities[index].info;
}
const EntityState& Simulation::state(size_t index) const {
  return impl_->state.world.entities[index].state();
}
EntityStates Simulation::states() const {
  const auto& entities = impl_->state.world.entities;
  return entities.empty()
             ? EntityStates{}
             : EntityStates{&entities.front().state(), entities.size(), sizeof(entities[0])};
}
EntityStateChanges Simulation::state_changes() const {
  const auto& entities = impl_->state.world.entities;
  return entities.empty() ? EntityStateChanges{}
                          : EntityStateChanges{&entities.front().state_changes(), entities.size(),
                                               sizeof(entities[0])};
}
std::optional<size_t> Simulation::find_entity(std::string_view name) const {
  const auto index = impl_->state.world.find(name);
  return index ? std::optional<size_t>(*index) : std::nullopt;
}

const std::string& Simulation::road_id(uint32_t road) const {
  static const std::string kNone;
  const xodr::Map* map = impl_->state.map;
  return map != nullptr && road < map->road_count() ? map->road(road).id : kNone;
}

std::span<const TransitionRecord> Simulation::transitions() const {
  return impl_->state.elements.log();
}

std::optional<ElementState> Simulation::element_state(std::string_view path) const {
  const auto index = impl_->state.elements.find(path);
  return index ? std::optional<ElementState>(impl_->state.elements[*index].state) : std::nullopt;
}

std::vector<ElementStatusView> Simulation::elements() const {
  const detail::ElementTable& table = impl_->state.elements;
  std::vector<ElementStatusView> out;
  out.reserve(table.size());
  for (uint32_t i = 0; i < table.size(); ++i) {
    out.push_back({table[i].type, table[i].path, table[i].state});
  }
  return out;
}

std::span<const CollisionRecord> Simulation::collisions() const { return impl_->state.collisions; }

std::span<const LightChange> Simulation::light_changes() const {
  return impl_->state.light_changes;
}

std::span<const Lifetime> Simulation::lifetimes(size_t index) const {
  const auto& all = impl_->state.traffic.lifetimes;
  const auto it = all.find(static_cast<uint32_t>(index));
  return it == all.end() ? std::span<const Lifetime>() : std::span<const Lifetime>(it->second);
}

std::vector<std::pair<std::string, bool>> Simulation::monitors() const {
  return {impl_->state.monitors.begin(), impl_->state.monitors.end()};
}

std::string_view Simulation::controller_substitute(size_t index) const {
  const auto& controls = impl_->state.controls;
  return index < controls.size() ? std::string_view(controls[index].substitute_for)
                                 : std::string_view();
}

bool Simulation::colliding(size_t a, size_t b) const {
  return a != b && impl_->state.contacts.get(static_cast<uint32_t>(a), static_cast<uint32_t>(b));
}

std::optional<xosc::Value> Simulation::parameter(std::string_view name) const {
  const xosc::Value* value = impl_->state.parameters.find(name);
  return value ? std::optional<xosc::Value>(*value) : std::nullopt;
}

std::optional<xosc::Value> Simulation::variable(std::string_view name) const {
  const xosc::Value* value = impl_->state.variables.find(name);
  return value ? std::optional<xosc::Value>(*value) : std::nullopt;
}

const EnvironmentState& Simulation::environment() const { return impl_->state.environment; }

namespace {

/// Whether a light set by LightStateAction is lit at `time`.
bool lit(const detail::LightSetting& light, double time) {
  using Mode = detail::LightSetting::Mode;
  if (light.mode != Mode::kFlashing) {
    return light.mode == Mode::kOn;
  }
  const double cycle = light.on_s + light.off_s;
  const double into = std::fmod(std::max(0.0, time - light.since), cycle);
  return into < light.on_s;
}

/// How far the fade of `light` is at `time`: 0 at its start, 1 once over (or without one).
double light_fade_done(const detail::LightSetting& light, double time) {
  if (!(light.transition_s > 0.0)) {
    return 1.0;
  }
  return std::clamp((time - light.since) / light.transition_s, 0.0, 1.0);
}

/// Adds what `light` emits at `time`, weighted by `weight`, to `look`: its fading-out previous
/// state (an unset light counts as off) mixed linearly with its own.
void add_light_look(const detail::LightSetting& light, double time, double weight,
                    LightLook& look) {
  const double done = light_fade_done(light, time);
  if (done < 1.0 && light.previous) {
    add_light_look(*light.previous, time, weight * (1.0 - done), look);
  }
  const double w = weight * done;
  if (w <= 0.0 || !lit(light, time)) {
    return;
  }
  std::array<double, 3> unit{};
  if (light.rgb) {
    const auto& c = *light.rgb;
    const double y = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];  // Rec. 709 luminance
    for (int k = 0; k < 3 && y > 0.0; ++k) {
      unit[k] = c[k] / y;  // a black light emits nothing
    }
  }
  if (light.candela && light.rgb) {
    for (int k = 0; k < 3; ++k) {
      look.fixed_cd[k] += w * *light.candela * unit[k];
    }
  } else if (light.candela) {
    look.lamp_colour_cd += w * *light.candela;
  } else if (light.rgb) {
    for (int k = 0; k < 3; ++k) {
      look.colour_share[k] += w * unit[k];
    }
  } else {
    look.lamp_share += w;
  }
}

bool look_emits(const LightLook& look) {
  const auto any = [](const std::array<double, 3>& v) { return v[0] + v[1] + v[2] > 0.0; };
  return any(look.fixed_cd) || look.lamp_colour_cd > 0.0 || any(look.colour_share) ||
         look.lamp_share > 0.0;
}

/// The lights an entity shows at `time`: the ones LightStateAction set, and otherwise brake
/// lights while it decelerates by more than 0.5 m/s^2 or stands after having moved (held on the
/// brake), and a flashing indicator (1.5 Hz, the middle of UN ECE R48's 90 +- 30 per minute)
/// while it moves sideways across its lane faster than 0.2 m/s.
void entity_lights(const detail::Entity& entity, double time, EntitySnapshot& out) {
  out.lights_on = 0;
  out.lights_set = 0;
  out.lights_flashing = 0;
  out.light_looks.clear();
  out.light_settings.clear();
  const EntityState& state = entity.state();
  const bool braking =
      state.acceleration < -0.5 || (std::abs(state.speed) < 0.05 && state.odometer > 0.0);
  if (braking) {
    out.lights_on |= light_bit(VehicleLight::kBrake);
  }
  const bool flash_phase = std::fmod(time, 2.0 / 3.0) < 1.0 / 3.0;
  if (std::abs(state.lateral_speed) > 0.2) {
    const uint32_t indicator = light_bit(state.lateral_speed > 0.0 ? VehicleLight::kIndicatorLeft
                                                                   : VehicleLight::kIndicatorRight);
    out.lights_flashing |= indicator;
    out.lights_on |= flash_phase ? indicator : 0u;
  }
  if (!entity.lights) {
    return;
  }
  for (size_t i = 0; i < detail::kVehicleLightCount; ++i) {
    const auto& light = (*entity.lights)[i];
    if (!light) {
      continue;
    }
    const uint32_t bit = 1u << i;
    out.lights_set |= bit;
    out.light_settings.push_back(light->view(static_cast<VehicleLight>(i)));
    const bool flashing = light->mode == LightMode::kFlashing;
    out.lights_flashing = flashing ? (out.lights_flashing | bit) : (out.lights_flashing & ~bit);
    bool on = lit(*light, time);
    if (light->candela || light->rgb || light_fade_done(*light, time) < 1.0) {
      LightLook look;
      look.light = static_cast<VehicleLight>(i);
      add_light_look(*light, time, 1.0, look);
      on = look_emits(look);
      out.light_looks.push_back(look);
    }
    out.lights_on = on ? (out.lights_on | bit) : (out.lights_on & ~bit);
  }
}

}  // namespace

void Simulation::fill_snapshot(WorldSnapshot& out) const {
  const detail::SimState& state = impl_->state;
  out.tick = state.tick;
  out.time = state.now();
  out.environment = state.environment;
  const detail::DateTime now = detail::current_date_time(state);
  out.environment.year = now.year;
  out.environment.month = now.month;
  out.environment.day = now.day;
  out.environment.time_of_day = now.seconds_of_day;
  out.entities.resize(state.world.entities.size());
  for (size_t i = 0; i < state.world.entities.size(); ++i) {
    const detail::Entity& entity = state.world.entities[i];
    EntitySnapshot& snap = out.entities[i];
    snap.instance_id = static_cast<uint32_t>(i + 1);
    snap.name = entity.info.name;
    snap.category = entity.info.category;
    snap.model3d = entity.info.model3d;
    snap.pose = entity.state().pose;
    snap.box = entity.info.box;
    snap.speed = entity.state().speed;
    const double c = std::cos(entity.state().pose.h), s = std::sin(entity.state().pose.h);
    snap.vx = entity.state().speed * c - entity.state().lateral_speed * s;
    snap.vy = entity.state().speed * s + entity.state().lateral_speed * c;
    snap.vz = 0.0;
    snap.yaw_rate = entity.state().yaw_rate;
    snap.acceleration = entity.state().acceleration;
    snap.odometer = entity.state().odometer;
    if (entity.info.kind == ObjectKind::kVehicle) {
      entity_lights(entity, out.time, snap);
    }
    snap.visible = entity.state().visible && entity.state().placed;
    snap.sensor_exceptions.clear();
    if (entity.state().placed && i < state.controls.size()) {
      snap.sensor_exceptions = state.controls[i].sensor_exceptions;
    }
    const double now = state.now();
    snap.animations.clear();
    for (const auto& [type, animation] : entity.animations) {
      snap.animations.push_back({type, detail::animation_state(animation, now)});
    }
  }
  out.signals.clear();
  for (const auto& [id, signal_state] : state.traffic.signals) {
    out.signals.push_back({id, signal_state});
  }
  out.overlaps.clear();
  for (const auto& [a, b] : state.contacts.pairs) {
    out.overlaps.emplace_back(a + 1, b + 1);
  }
}

void Simulation::add_observer(SimulationObserver& observer) {
  impl_->observers.push_back(&observer);
}

void Simulation::set_custom_command_handler(std::string type, CustomCommandHandler handler) {
  impl_->state.custom_handlers[std::move(type)] = std::move(handler);
}

void Simulation::set_user_value_provider(UserValueProvider provider) {
  impl_->state.user_values = std::move(provider);
}

namespace {

void check_command(const ExternalCommand& command) {
  const auto finite = [](double v) { return std::isfinite(v); };
  if (command.pose && command.controls) {
    throw std::invalid_argument("a command gives either a pose or controls, not both");
  }
  if (command.pose) {
    const Pose& p = *command.pose;
    if (!finite(p.x) || !finite(p.y) || !finite(p.z) || !finite(p.h) || !finite(p.p) ||
        !finite(p.r)) {
      throw std::invalid_argument("the commanded pose must be finite numbers");
    }
  }
  if (command.speed && !finite(*command.speed)) {
    throw std::invalid_argument("the commanded speed must be a finite number of m/s");
  }
  if (command.controls) {
    const VehicleControls& c = *command.controls;
    if (!(c.throttle >= 0.0 && c.throttle <= 1.0) || !(c.brake >= 0.0 && c.brake <= 1.0)) {
      throw std::invalid_argument("throttle and brake must be between 0 and 1");
    }
    if (!finite(c.steering)) {
      throw std::invalid_argument("the steering angle must be a finite number of radians");
    }
  }
}

}  // namespace

void Simulation::command(size_t index, const ExternalCommand& command) {
  detail::SimState& state = impl_->state;
  if (index >= state.world.entities.size()) {
    throw std::invalid_argument("no entity with index " + std::to_string(index));
  }
  check_command(command);
  detail::ControlState& control = detail::control_of(state, static_cast<uint32_t>(index));
  if (!control.commanded) {
    state.commanded.push_back(static_cast<uint32_t>(index));
  }
  control.command = command;
  control.commanded = true;
}

bool Simulation::external(size_t index) const {
  const detail::SimState& state = impl_->state;
  return index < state.controls.size() &&
         state.controls[index].kind == detail::ControllerKind::kExternal;
}

void Simulation::set_user_value(std::string name, std::string value) {
  impl_->state.given_values[std::move(name)] = std::move(value);
}

const xosc::Scenario& Simulation::scenario() const { return impl_->state.scenario; }
const xodr::Map* Simulation::map() const { return impl_->state.map; }

std::string_view to_string(EndReason reason) {
  switch (reason) {
    case EndReason::kRunning:
      return "running";
    case EndReason::kStopTrigger:
      return "stop trigger";
    case EndReason::kDuration:
      return "duration";
    case EndReason::kStoriesComplete:
      return "stories complete";
    case EndReason::kInterrupted:
      return "interrupted";
  }
  return "running";
}

}  // namespace corsa::engine
