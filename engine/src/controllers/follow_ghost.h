#pragma once

// esmini's followGhost controller (its ControllerFollowGhost and the ghost its ScenarioEngine
// sets up), which esmini's example scenarios name explicitly:
//   - the entity gets a ghost, "<name>_ghost", a copy of it appended after the scenario's
//     entities, which starts the run `headstartTime` seconds earlier: the run begins at
//     simulation time -headstartTime, and until time 0 only the ghost moves (the other
//     entities' actions begin at time 0: storyboard/action_runner.h);
//   - the ghost performs the entity's Init actions (all but the controller ones) and, in the
//     stories, the entity's motion actions (Speed, SpeedProfile, LaneChange, LaneOffset,
//     Synchronize, FollowTrajectory, AssignRoute, Teleport); the SimulationTimeConditions of
//     those events and of every Act's start trigger come headstartTime earlier, and the
//     entity's by-entity conditions there (Collision, ReachPosition, TraveledDistance, Speed,
//     Acceleration, EndOfRoad, Offroad, StandStill) are the ghost's;
//   - the ghost leaves a trail (a sample every 0.2 s); the entity, once its controller is
//     activated, drives a simple vehicle model after it: at time t it steers toward the trail's
//     point of time t - headstart + lookaheadSteering and takes the speed of the point of
//     time t - headstart + lookaheadSpeed.
//   - an event the ghost performs whose start trigger holds a condition the ghost cannot meet
//     ahead of its entity (one on a value other than the simulation time, one on another entity,
//     or a by-entity condition not handed over) restarts the ghost when it starts after time 0:
//     the ghost is put back onto the entity (pose and speed), its trail starts again, the run's
//     time goes back by headstartTime and, as in the head start, only the ghost moves until the
//     time reached before (rows of those times are recorded again); the completed events the
//     ghost performs may start again. At time 0 or before it only puts the ghost onto the entity.
// The ghost is recorded (esmini records it too) but no other entity, sensor or condition sees
// it, and it collides with nothing.

#include <cstdint>

#include "corsa/xosc/conditions.h"
#include "corsa/xosc/private_actions.h"
#include "motion/controller.h"

namespace corsa::engine::detail {

struct SimState;
struct TrailPoint;

/// Makes the ghost of the first entity whose ObjectController is esmini's followGhost
/// (Property esminiController, else the Controller's name, FollowGhostController), unless
/// controllers are disabled or driven from outside, and sets the run's first tick to -headstart.
/// Call after the entities are built and before the controllers are assigned. A second such entity
/// gets none (as in esmini, which sets up the first ghost only; a warning says so).
void setup_ghost(SimState& state);

/// Whether `oc` is esmini's followGhost controller.
bool is_follow_ghost(const xosc::ObjectController& oc);

/// Whether the ghost performs this action of its entity in the stories (the motion actions
/// listed above).
bool ghost_performs(const xosc::PrivateAction& action);

/// Whether `oc` is esmini's followGhost controller.
bool is_follow_ghost(const xosc::ObjectController& oc);

/// Whether the ghost performs this Init action of its entity too (all but the controller ones).
bool ghost_copies_init(const xosc::PrivateAction& action);

/// Whether esmini hands a by-entity condition of this kind over to the ghost when its triggering
/// entity is the ghost's entity (Collision, ReachPosition, TraveledDistance, Speed, Acceleration,
/// EndOfRoad, Offroad, StandStill).
bool ghost_meets(const xosc::EntityCondition& condition);

/// Whether an event the ghost performs restarts the ghost when it starts: its start trigger
/// holds a condition the ghost cannot meet ahead of its entity (above).
bool ghost_restarts_on(const xosc::Trigger& trigger, const SimState& state);

/// esmini's ghost restart, at the start of such an event (above), before its actions start and
/// after the actions running on the ghost were stopped (a teleport takes both domains).
/// Returns whether the run's time went back (the completed ghost events may start again).
bool restart_ghost(SimState& state);

/// Adds the ghost's sample of the current tick to its trail when one is due.
void record_trail(SimState& state);

/// The trail's point at `time` (linear between samples; the first or last sample outside).
/// The trail must not be empty.
TrailPoint trail_at(const SimState& state, double time);

/// One step of the followGhost controller on entity `index` (the ghost's follower).
void step_follow_ghost(SimState& state, uint32_t index, const MotionContext& motion);

}  // namespace corsa::engine::detail
