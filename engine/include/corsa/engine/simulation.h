#pragma once

// engine::Simulation: one run of one scenario. The scenario (xosc::Scenario) and the map
// (xodr::Map) are read-only models; everything that changes during the run (entities,
// storyboard states, parameters, variables, environment) lives inside the Simulation, so two
// simulations in one process never see each other (MuJoCo's mjModel / mjData split).
//
// Time advances in integer ticks of the fixed step dt. Each step (DESIGN.md, "Data flow of one
// run"): triggers are evaluated on the state at the current tick and the storyboard transitions;
// running actions step; controllers move the entities to the next tick; collisions and timers
// are updated; observers (recorder, capture timeline) see the new state.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/core/vec.h"
#include "corsa/engine/entity_state.h"
#include "corsa/engine/external_control.h"
#include "corsa/engine/storyboard_state.h"
#include "corsa/engine/world_snapshot.h"

namespace corsa::xosc {
struct Scenario;
struct UserDefinedAction;
struct Value;
}  // namespace corsa::xosc

namespace corsa::xodr {
class Map;
}

namespace corsa::engine {

/// WGS84 latitude and longitude (degrees) to x, y (m) in the map's projected CRS, before the
/// OpenDRIVE header <offset>; nothing where the CRS gives no finite result.
using GeographicToMap =
    std::function<std::optional<Vec2>(double latitude_deg, double longitude_deg)>;
/// Makes the GeographicToMap of a map's geoReference (a PROJ string, WKT or "EPSG:n"); throws
/// corsa::InputError saying why when it cannot.
using GeoProjectionFactory = std::function<GeographicToMap(const std::string& geo_reference)>;

/// How the engine reads where the standard's text and esmini differ (docs/openscenario.md,
/// "Differences from esmini"); what the text leaves open is read as esmini reads it under both.
enum class Semantics : uint8_t {
  kStandard,  ///< the default: e.g. a SpeedAction's TransitionDynamics hold beyond the Performance
  kEsmini,    ///< esmini's choices, to compare trajectories with esmini's (`--semantics esmini`)
};

struct SimulationOptions {
  double dt = 0.01;          ///< fixed step, s (> 0)
  double duration = 3600.0;  ///< cap on simulated time, s: the run ends there at the latest
  uint64_t seed = 0;         ///< run seed for every random draw (per-entity streams)
  /// Controller for every vehicle that names none in the scenario (`corsa run --controller`):
  /// "default", "acc" or "dynamics"; empty: the scenario's choice.
  std::string controller;
  /// Seeded random NPCs added at tick 0 (`corsa run --npc vehicles=N,pedestrians=M`): vehicles
  /// on driving lanes under the car-following controller, pedestrians walking on sidewalks.
  struct Npc {
    uint32_t vehicles = 0;
    uint32_t pedestrians = 0;
  } npc;
  /// Threads the entities of a step may be moved on (`corsa run --threads`), at least 1.
  /// Outputs are byte-identical for any number; only runs with many entities use more than
  /// one, and only while the steps' times show that it pays (now and then both ways timed).
  unsigned threads = 1;
  /// Controllers driven from outside (external_control.h): an entity whose ObjectController, by
  /// its own name or its Controller's (e.g. "ExternalController"), is one of these moves only by
  /// Simulation::command. Empty: none (the command line's choice; the Python module names
  /// "ExternalController").
  std::vector<std::string> external_controllers;
  /// The map-to-Earth transform GeoPositions need (OpenSCENARIO 1.3 §6.4), called once per
  /// simulation, on the first GeoPosition: corsa::geo::geographic_to_projected (PROJ) for
  /// library users; the `corsa` command loads it on demand. Empty: a GeoPosition is an error
  /// that says so.
  GeoProjectionFactory geo_projection;
  /// Lenient readings (a rule of the standard broken in a way whose meaning is clear, run as
  /// its author meant with a `(read as ...)` warning) are errors instead (`--strict`): the
  /// scenario's load (xosc::LoadOptions::strict) and what the engine reads at run time.
  bool strict = false;
  /// Values of UserDefinedValueConditions by name (`corsa run --value NAME=VALUE`); see also
  /// Simulation::set_user_value.
  std::vector<std::pair<std::string, std::string>> values;
  /// Standard or esmini reading where the standard's text and esmini differ (`--semantics`).
  Semantics semantics = Semantics::kStandard;
  /// The scenario's controllers are ignored (`corsa run --disable-controllers`, esmini's
  /// `--disable_controllers`): ObjectControllers and AssignControllerActions choose nothing, so
  /// every entity moves under the default controller (or `controller` for vehicles).
  bool disable_controllers = false;
};

/// One presence of a generated entity (traffic actions, NPCs): when it appeared and, once it
/// has, when it left (s).
struct Lifetime {
  double spawned = 0.0;
  std::optional<double> removed;
};

/// Why a run ended.
enum class EndReason : uint8_t {
  kRunning,          ///< not ended yet
  kStopTrigger,      ///< the Storyboard's stop trigger fired
  kDuration,         ///< the duration cap was reached
  kStoriesComplete,  ///< every story completed and the storyboard has no stop trigger
  kInterrupted,      ///< stopped from outside (Simulation::interrupt, e.g. Ctrl-C)
};
std::string_view to_string(EndReason reason);  ///< "stop trigger", "duration", ...

/// Two entities whose bounding boxes started to overlap at `tick` (one record per contact).
struct CollisionRecord {
  int64_t tick = 0;
  double time = 0.0;
  uint32_t first = 0;  ///< entity indices, first < second
  uint32_t second = 0;
};

/// A light of entity `entity` (index) set by a LightStateAction, at `setting.since`.
struct LightChange {
  uint32_t entity = 0;
  LightSettingView setting;
};

/// One storyboard element and its state now (Simulation::elements).
struct ElementStatusView {
  ElementType type = ElementType::kStory;
  std::string_view path;  ///< "" for the storyboard itself
  ElementState state = ElementState::kStandby;
};

class Simulation;

/// Sees the simulation after the initial actions (tick 0) and after every step.
class SimulationObserver {
 public:
  virtual ~SimulationObserver() = default;
  virtual void on_step(const Simulation& simulation) = 0;
};

/// A CustomCommandAction (UserDefinedAction) reaching the engine. Handlers are registered per
/// `type`; they may throw corsa::InputError (located with action.source) for bad content.
using CustomCommandHandler =
    std::function<void(const xosc::UserDefinedAction& action, const Simulation& simulation)>;

class Simulation {
 public:
  /// Builds the run state and performs the Init actions at tick 0. `scenario` must outlive the
  /// simulation; `map` may be null when the scenario has no road network. Throws InputError
  /// (located in the scenario) for what makes the run impossible: an entity on a missing road
  /// or lane, off the map, references that cannot be resolved, bad options.
  Simulation(const xosc::Scenario& scenario, std::shared_ptr<const xodr::Map> map,
             const SimulationOptions& options, Diagnostics& diagnostics);
  Simulation(Simulation&&) noexcept;
  Simulation& operator=(Simulation&&) noexcept;
  ~Simulation();

  /// Evaluates the triggers at the current tick and, unless the run ends there, advances one
  /// step. Returns false once the run has ended (then nothing changes any more).
  bool step();
  /// Steps until the run ends.
  void run();
  /// Ends the run here (EndReason::kInterrupted) unless it has ended already: the next step()
  /// returns false and the state stays as it is, so its outputs can still be written.
  void interrupt();

  bool ended() const;
  EndReason end_reason() const;
  int64_t tick() const;
  double time() const;  ///< seconds: tick on the step grid
  /// The tick the run started at: 0, or minus the head start of esmini's followGhost ghost
  /// (the run then begins at negative simulation times).
  int64_t start_tick() const;
  /// Steps taken so far: tick() - start_tick(), plus the ticks esmini's ghost restarts ran a
  /// second time (time() goes back by the ghost's head start at each restart).
  int64_t steps() const;
  /// Whether entity `index` is esmini's followGhost ghost, which nothing else sees: metrics,
  /// like sensors and conditions, leave it out.
  bool is_ghost(size_t index) const;
  double dt() const;
  double time_of(int64_t tick) const;
  const SimulationOptions& options() const;

  size_t entity_count() const;
  const EntityInfo& entity(size_t index) const;
  const EntityState& state(size_t index) const;
  /// Every entity's state where the run keeps it, for readers that visit all of them every tick
  /// (the recorders) without a call per entity: states()[i] is state(i). Valid until the next
  /// step.
  EntityStates states() const;
  /// Every entity's count of its state's writes, as states() (valid until the next step): while
  /// entity i's count is one a reader saw, states()[i] holds the state it saw then, bit for bit
  /// (a write that changed nothing may still move the count). The recorders pass an entity
  /// whose count did not move with one comparison.
  EntityStateChanges state_changes() const;
  std::optional<size_t> find_entity(std::string_view name) const;
  /// The OpenDRIVE id of a road index (for output), "" without a map.
  const std::string& road_id(uint32_t road) const;

  /// Every storyboard transition so far, in order.
  std::span<const TransitionRecord> transitions() const;
  /// State of the storyboard element with this `::` path; nothing for an unknown path.
  std::optional<ElementState> element_state(std::string_view path) const;
  /// Every storyboard element in document order (the storyboard first), with its state now.
  std::vector<ElementStatusView> elements() const;
  std::span<const CollisionRecord> collisions() const;
  /// Every light a LightStateAction set so far, in the order they were set (user-defined light
  /// types, which only warn, are not among them).
  std::span<const LightChange> light_changes() const;
  /// When a generated entity (traffic, NPCs) appeared and left, in order; empty for the
  /// scenario's own entities.
  std::span<const Lifetime> lifetimes(size_t index) const;
  /// The scenario's controller of entity `index` that this engine does not have and for which
  /// the acc controller stands in (e.g. "ALKSController"); "" when none.
  std::string_view controller_substitute(size_t index) const;
  /// Pairs of entities overlapping at the current tick.
  bool colliding(size_t a, size_t b) const;

  /// The monitors (MonitorDeclarations, set by SetMonitorAction) and their current values, by
  /// name: the scenario's own verdicts.
  std::vector<std::pair<std::string, bool>> monitors() const;
  /// Current value of a global parameter / variable (after ParameterSet/VariableSet actions).
  std::optional<xosc::Value> parameter(std::string_view name) const;
  std::optional<xosc::Value> variable(std::string_view name) const;
  const EnvironmentState& environment() const;

  /// The world as the sensors see it now.
  void fill_snapshot(WorldSnapshot& out) const;

  /// Observers are called after tick 0 is set up... and after every later step; register them
  /// before the first step() (the tick-0 call happens at the first step() or run()).
  void add_observer(SimulationObserver& observer);
  void set_custom_command_handler(std::string type, CustomCommandHandler handler);
  /// Where UserDefinedValueConditions get their values (none set: they never hold, with a
  /// located warning once per name).
  void set_user_value_provider(UserValueProvider provider);

  /// Moves entity `index` over the next step as `command` says, in place of its controller
  /// (external_control.h); a later command for the same step replaces this one. An entity that is
  /// not present (absent, deleted) ignores it. Throws std::invalid_argument for an index out of
  /// range, a command with both a pose and controls, or a value that is not a finite number
  /// (throttle and brake outside 0..1 included).
  void command(size_t index, const ExternalCommand& command);
  /// Whether entity `index` is driven from outside (SimulationOptions::external_controllers, or
  /// `corsa:controller` = `external`): it moves only by commands. Between commands it repeats the
  /// last one's speed or controls (after a pose: rolls on at its speed); before the first it keeps
  /// the speed it has.
  bool external(size_t index) const;
  /// Sets (or changes) the value UserDefinedValueConditions named `name` compare with, e.g.
  /// from a driver model or the Python module between steps. Wins over the value provider.
  void set_user_value(std::string name, std::string value);

  const xosc::Scenario& scenario() const;
  const xodr::Map* map() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace corsa::engine
