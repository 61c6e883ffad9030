#pragma once

// The controllers and how entities get them (OpenSCENARIO 1.3 §7.5): the default
// controller (ideal lane following, motion/controller.h), `acc` (car following on top of it)
// and `dynamics` (a single-track vehicle model driven by pure pursuit and a speed PI loop).
//
// An entity's controller comes from its ObjectController: a Controller whose Properties have
// `corsa:controller` = default | acc | dynamics; otherwise from `corsa run --controller NAME`
// (SimulationOptions::controller) for vehicles; otherwise the default controller.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "corsa/engine/simulation.h"
#include "motion/controller.h"
#include "state/control_state.h"

namespace corsa::xosc {
struct Controller;
struct ObjectController;
struct Source;
}  // namespace corsa::xosc

namespace corsa::engine::detail {

struct SimState;

/// The corsa controller a scenario Controller asks for (its `corsa:controller` property, or
/// esmini's `esminiController` = DefaultController, which is the default controller), or
/// nothing. An unknown value warns once (located) and means the default controller.
bool controller_kind_of(const xosc::Controller& controller, Diagnostics& diagnostics,
                        ControllerKind& out);

/// Whether SimulationOptions::external_controllers names this ObjectController (its name, its
/// Controller's name, or esmini's `esminiController` property): its entity is driven from outside.
bool names_external(const SimulationOptions& options, const xosc::ObjectController& oc);

/// A controller this engine does not have (an external driver model, esmini's ALKSController):
/// the acc controller stands in for it on entity `index` (a driver that does not run into the
/// vehicle ahead). Recorded in ControlState::substitute_for (the run summary lists it) and
/// warned once per entity and controller, located at the ObjectController.
void substitute_controller(SimState& state, uint32_t index, const xosc::ObjectController& oc);

/// Whether an entity's controller of kind `a` and its controller of kind `b` may each move it in
/// one motion domain: the pairs whose steps are defined (docs/engine.md, "Controllers per motion
/// domain"), esmini's sloppyDriver with its interactiveDriver.
bool may_share_domains(const ControlState& control, ControllerKind a, ControllerKind b);

/// Exchanges the roles of the entity's controller and its DomainPartner (kind, name, domains).
void swap_with_partner(ControlState& control);

/// After an assignment or activation: the controller active in the longitudinal domain becomes
/// `kind` (the one the dispatch steps) when two share the motion domains, the active one when
/// only one is. Returns false, and forgets the partner, when the two active ones are not a pair
/// whose step is defined (the caller warns): `kind`, the controller assigned or activated last,
/// then moves the entity in its domains.
bool settle_domains(ControlState& control);

/// settle_domains for entity `index`, warning at `source` (an assignment or activation) when the
/// two active controllers are not such a pair.
void settle_domains_at(SimState& state, uint32_t index, const xosc::Source& source);

/// esmini's type of a scenario Controller: its `esminiController` property, else its name.
std::string esmini_type(const xosc::Controller& controller);

/// Runs `move` (one step of the entity's motion) with the entity's speed command set to a
/// controller's `speed`, then gives the actions' command back unless the step changed it.
template <class Move>
void move_at_controller_speed(Entity& entity, double speed, Move&& move) {
  const double asked = entity.speed_command;
  entity.speed_command = speed;
  std::forward<Move>(move)();
  if (entity.speed_command == speed) entity.speed_command = asked;
}

/// The Property `name` of a scenario Controller as a non-negative number (esmini's controllers
/// take their parameters so: `timeGap`, `headstartTime`, ...), or nothing when it is absent. A
/// value that is no finite non-negative number warns (once per property), located at the
/// property, naming `controller_label`, and counts as absent (the caller's default is used).
std::optional<double> nonnegative_property(const SimState& state,
                                           const xosc::Controller& controller, const char* name,
                                           const char* controller_label);

/// Gives every entity its controller from the scenario and the options (state.controls sized
/// to the entities). Throws InputError for an unknown --controller name.
void assign_initial_controllers(SimState& state);

/// The control state of entity `index`, created (default controller) for entities added during
/// the run (traffic).
ControlState& control_of(SimState& state, uint32_t index);

/// Moves every present entity over one step with its controller, on up to `threads` threads.
/// Each entity's move reads and writes only that entity, the map and a picture of the others
/// taken before the moves (controllers/follow_view.h, for car following), so the result is the
/// same whatever the number of threads. Keeps its buffers and threads between steps.
class EntityMover {
 public:
  explicit EntityMover(unsigned threads = 1);
  ~EntityMover();
  EntityMover(EntityMover&&) noexcept;
  EntityMover& operator=(EntityMover&&) noexcept;

  void move(SimState& state, const MotionContext& motion);

  /// Whether the mover wants each step's wall time (charge_step): with more than one thread it
  /// measures whether sharing a step out pays (controllers/thread_choice.h).
  bool times_steps() const;
  /// The wall time of the step whose moves the last move() made, all of the step's phases.
  void charge_step(std::chrono::steady_clock::duration step);

  /// Calls work(begin, end) for ranges covering [0, count), each once: on the mover's threads
  /// when it has several and `count` is large enough to be worth sharing (thousands: light
  /// work), else here in one call.
  /// For per-entity work whose result does not depend on the thread (e.g. the contacts' boxes).
  void share(size_t count, const std::function<void(size_t, size_t)>& work);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

class FollowView;
struct LanesAhead;

/// The car-following controller: the commanded speed, limited so as to keep a time gap to the
/// vehicle ahead on the lane path it will drive (through links and junctions, within 200 m), as
/// `view` shows the others; then the default controller's motion. `ahead` is the entity's own,
/// kept between steps.
void step_acc(SimState& state, uint32_t index, const MotionContext& motion, const FollowView& view,
              LanesAhead& ahead);

/// The dynamics controller (controllers/dynamics_controller.cpp), in two halves.
/// begin_dynamics: for each entity of `indices`, the driver model's inputs from the entity's own
/// state and commands; then all their vehicle models integrated over the step as one system.
/// It changes nothing other entities see, so it runs ahead of the moves of EntityMover::move,
/// where finish_dynamics moves each entity to its model's new state and updates its lane
/// position.
void begin_dynamics(SimState& state, std::span<const uint32_t> indices,
                    const MotionContext& motion);
void finish_dynamics(SimState& state, uint32_t index, const MotionContext& motion);

}  // namespace corsa::engine::detail
