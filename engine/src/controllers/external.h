#pragma once

// Control from outside the scenario (corsa/engine/external_control.h). A command given with
// Simulation::command takes the place of the entity's controller for the next step: a pose puts
// it there, a speed moves it along its lane as the default controller would, controls drive the
// dynamics controller's vehicle model (controllers/dynamics_controller.cpp). An entity of the
// external controller (ControllerKind::kExternal) moves only by commands: between them it
// repeats the last one's speed or controls, and before the first it keeps its speed.
//
// Within a step: begin_commands, then move_entities (which calls step_commanded for a pose or a
// speed and the vehicle model for controls), then end_commands.

#include <cstdint>

#include "motion/controller.h"

namespace corsa::engine::detail {

struct SimState;

/// Before the entities move: entities of the external controller that got no command repeat
/// their held one; a commanded entity drops the pose an action set for this step (the command
/// takes its place).
void begin_commands(SimState& state);

/// Moves a commanded entity by its command's pose or speed.
void step_commanded(SimState& state, uint32_t index, const DefaultController& ideal,
                    const MotionContext& motion);

/// After the move: what each entity of the external controller holds now; commands cleared.
void end_commands(SimState& state);

}  // namespace corsa::engine::detail
