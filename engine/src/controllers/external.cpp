// Commands from outside and the external controller (controllers/external.h).

#include "controllers/external.h"

#include "controllers/controllers.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {

[[gnu::hot]] void begin_commands(SimState& state) {
  const auto count = static_cast<uint32_t>(state.world.entities.size());
  if (count == 0) {
    return;
  }
  control_of(state, count - 1);
  // An active external controller without a command from outside for this step repeats what
  // it held. A pass over the control records alone: most entities have no such controller.
  for (uint32_t i = 0; i < count; ++i) {
    ControlState& control = state.controls[i];
    if (control.kind != ControllerKind::kExternal || control.commanded ||
        !(control.longitudinal || control.lateral)) {
      continue;
    }
    if (control.held) {
      control.command = *control.held;
    } else {
      control.command = ExternalCommand{};
      control.command.speed = state.world.entities[i].state().speed;
    }
    control.commanded = true;
    state.commanded.push_back(i);
  }
  // A commanded entity goes where its command puts it, not where an action asked for: every
  // commanded entity is listed in state.commanded (Simulation::command and the pass above).
  for (const uint32_t i : state.commanded) {
    if (i < count && state.controls[i].commanded) {
      state.world.entities[i].pose_command.reset();
    }
  }
}

void step_commanded(SimState& state, uint32_t index, const DefaultController& ideal,
                    const MotionContext& motion) {
  Entity& entity = state.world.entities[index];
  const ControlState& control = state.controls[index];
  const ExternalCommand& command = control.command;
  const bool external = control.kind == ControllerKind::kExternal;
  // A one-step command leaves the actions' speed command alone: the controller resumes from it.
  const double speed_command = entity.speed_command;
  entity.speed_command = command.speed.value_or(entity.state().speed);
  if (command.pose) {
    entity.pose_command = *command.pose;  // consumed by the move (motion/pose_command.h)
  } else if (external) {
    entity.lateral_command = entity.lane.lateral;  // no action steers it: hold the offset
  }
  ideal.step(entity, motion);
  if (!external) {
    entity.speed_command = speed_command;
  }
}

[[gnu::hot]] void end_commands(SimState& state) {
  for (const uint32_t i : state.commanded) {
    if (i >= state.controls.size()) {
      continue;
    }
    ControlState& control = state.controls[i];
    if (control.commanded && control.kind == ControllerKind::kExternal) {
      ExternalCommand held;
      if (control.command.controls) {
        held.controls = control.command.controls;  // the pedals and the wheel stay where they are
      } else {
        // After a speed or a pose: roll on at the speed it has.
        held.speed = state.world.entities[i].state().speed;
      }
      control.held = held;
    }
    control.commanded = false;
    control.command = ExternalCommand{};
  }
  state.commanded.clear();
}

}  // namespace corsa::engine::detail
