#pragma once

// Which controller moves an entity and what it keeps between steps (OpenSCENARIO 1.3 §7.5
// "Controllers": ObjectController, ActivateControllerAction, AssignControllerAction,
// OverrideControllerValueAction). Kept on the Entity; the dynamics integrator lives behind a
// pointer so that entities stay movable.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "corsa/engine/external_control.h"
#include "state/out_of_line.h"

namespace corsa::engine::detail {

/// The controllers this engine has. kDefault is the ideal lane follower (motion/controller.h);
/// kExternal moves the entity only by commands from outside (controllers/external.h).
/// kFollowGhost drives after the entity's ghost (controllers/follow_ghost.h); kEsminiVehicle
/// is one of esmini's drivers of its simple vehicle model (controllers/esmini_vehicle.h);
/// kNaturalDriver is esmini's NaturalDriver (controllers/natural_driver.h); kAlksR157 is
/// esmini's ALKS_R157SM_Controller (controllers/alks_r157.h); kSloppyDriver is esmini's
/// sloppyDriver (controllers/sloppy_driver.h).
enum class ControllerKind : uint8_t {
  kDefault,
  kAcc,
  kDynamics,
  kExternal,
  kFollowGhost,
  kEsminiVehicle,
  kNaturalDriver,
  kAlksR157,
  kSloppyDriver
};

/// Parses a controller name as `corsa:controller` and `corsa run --controller` spell it
/// ("default", "acc", "dynamics", "external"); nothing for an unknown name.
bool parse_controller_kind(const std::string& name, ControllerKind& out);

/// One OverrideControllerValueAction value (§7.5.3): while `active`, `value` replaces what the
/// driver model would do. Throttle, brake and clutch 0..1; steering wheel in rad; brake as a
/// force in N when `force`.
struct OverrideSlot {
  bool active = false;
  double value = 0.0;
  bool force = false;
  double max_rate = 0.0;  ///< per second; 0: unlimited
};

struct ControllerOverrides {
  OverrideSlot throttle;
  OverrideSlot brake;
  OverrideSlot clutch;
  OverrideSlot parking_brake;
  OverrideSlot steering_wheel;
  bool gear_active = false;
  int gear = 1;  ///< manual gear number; automatic: -1 R, 0 N or P, 1 D

  bool any() const {
    return throttle.active || brake.active || parking_brake.active || steering_wheel.active ||
           clutch.active || gear_active;
  }
};

/// A generated walker's last look for a road a metre ahead of it (controllers.cpp,
/// waits_at_kerb): whether the point (x, y) lies on a lane vehicles drive on and, when it does
/// not, a radius (m) about it within which no point does. Points are compared to the bit; NaN
/// until the first look.
struct KerbLook {
  double x = std::numeric_limits<double>::quiet_NaN();
  double y = std::numeric_limits<double>::quiet_NaN();
  double clear = 0.0;
  bool on_road = false;
};

struct DynamicsVehicle;
struct EsminiDriver;
struct NaturalDriverState;
struct AlksR157;
struct SloppyDriver;

/// esmini's ACCController (its Properties), which the acc controller then follows instead of its
/// own car-following law (controllers/acc_controller.cpp).
struct EsminiAcc {
  double time_gap = 1.5;  ///< s (property timeGap)
  /// Property setSpeed in mode "override" (m/s); otherwise the actions' speed is the set speed.
  std::optional<double> set_speed;
};

/// An earlier assigned controller that keeps the motion domain the controller assigned after it
/// left to it (docs/engine.md, "Controllers per motion domain"): esmini keeps every assigned
/// controller, each active on its own domains. Its run state stays in ControlState's pointer for
/// its kind (a pair is always of two kinds).
struct DomainPartner {
  ControllerKind kind = ControllerKind::kDefault;
  std::string assigned;  ///< its ObjectController's name
  bool longitudinal = false;
  bool lateral = false;
  /// Whether it was assigned after `kind` (an ActivateControllerAction without objectControllerRef
  /// is for the controller assigned last).
  bool assigned_last = false;
  /// The entity's speed (m/s) and heading relative to its lane (rad) when the step under way
  /// began: the lateral controller steers with them.
  double step_start_speed = 0.0;
  double step_start_heading = 0.0;
};

/// The flags every step reads of every entity (the controller, whether it is commanded or seen
/// by traffic) come first, in one cache line (64 bytes) with the three fields the moves test
/// next to them; the rest is read only by the entities it concerns.
struct ControlState {
  ControllerKind kind = ControllerKind::kDefault;
  /// A command from outside (Simulation::command, `command` below) for the step under way.
  bool commanded = false;
  /// Domains the assigned controller is active in (ActivateControllerAction); when none is, the
  /// default controller moves the entity.
  bool longitudinal = true;
  bool lateral = true;
  bool animation = false;
  bool lighting = false;
  /// VisibilityAction (§7.4.5): whether other traffic (car following, collisions) and the
  /// image generator see the entity; the sensors flag is EntityState::visible.
  bool traffic_visible = true;
  bool graphics_visible = true;
  /// A pedestrian crossing the road (controllers.cpp), and whether it has passed a lane
  /// vehicles drive on.
  bool crossing = false;
  bool crossed_roadway = false;
  /// The controller of the other motion domain while two controllers share the entity's motion
  /// (`kind` then is active only in the domain the partner is not); none otherwise. This and
  /// `natural` follow the flags because every step tests both of every entity (EntityMover's
  /// scan before the moves), out of line so that the scan reads the record's first line alone.
  OutOfLine<DomainPartner> partner;
  /// esmini's NaturalDriver and what it keeps between steps, while it is the controller.
  std::shared_ptr<NaturalDriverState> natural;
  /// Set when the acc controller emulates esmini's ACCController. In the first cache line too:
  /// every car-following step tests it.
  OutOfLine<EsminiAcc> esmini_acc;
  /// A generated walker's own pace (m/s), taken at its first step; it slows for others and
  /// comes back to it (controllers/npc_caution.h). Negative until known.
  double pace = -1.0;
  /// VisibilityAction's SensorReferenceSet: the sensors for which the opposite of
  /// EntityState::visible holds (EntitySnapshot::sensor_exceptions).
  std::vector<std::string> sensor_exceptions;
  /// Name of the assigned ObjectController (for ActivateControllerAction's reference).
  std::string assigned;
  /// The scenario's controller that `kind` stands in for ("" when the scenario's own runs).
  std::string substitute_for;
  ControllerOverrides overrides;
  /// The dynamics controller's vehicle model (created on its first step).
  std::shared_ptr<DynamicsVehicle> dynamics;
  /// esmini's driver and its vehicle model, for ControllerKind::kEsminiVehicle.
  std::shared_ptr<EsminiDriver> esmini_driver;
  /// esmini's ALKS_R157SM_Controller: its settings and run state, while it is the kind.
  std::shared_ptr<AlksR157> alks;
  /// esmini's sloppyDriver: its properties and run state, while it is the kind.
  std::shared_ptr<SloppyDriver> sloppy;
  /// A command from outside (Simulation::command) for the step under way, while `commanded`; it
  /// takes the place of the controller. `held`: what an entity of the external controller
  /// repeats between commands.
  ExternalCommand command;
  std::optional<ExternalCommand> held;
  /// A generated walker's last kerb look (read only by its own moves).
  KerbLook kerb;

  /// The controller that moves the entity this step: a command's controls go through the
  /// dynamics controller's vehicle model, its pose or speed through the external controller.
  ControllerKind effective() const {
    if (commanded) {
      return command.controls ? ControllerKind::kDynamics : ControllerKind::kExternal;
    }
    return (longitudinal || lateral) ? kind : ControllerKind::kDefault;
  }
};
// (offsetof of a type with members of library types, which GCC gives as for any other.)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Winvalid-offsetof"
static_assert(offsetof(ControlState, pace) == 64, "the first line holds what every step tests");
#pragma GCC diagnostic pop

}  // namespace corsa::engine::detail
