#pragma once

// One factory function per action kind, each defined in the action's own file. The factory
// (action_factory.cpp) dispatches the xosc action variants to them.

#include <memory>
#include <string_view>

#include "actions/action.h"
#include "corsa/xosc/global_actions.h"
#include "corsa/xosc/private_actions.h"

namespace corsa::engine::detail {

std::unique_ptr<ActionInstance> make_teleport_action(const xosc::TeleportAction& action);
std::unique_ptr<ActionInstance> make_speed_action(const xosc::SpeedAction& action);
std::unique_ptr<ActionInstance> make_lane_change_action(const xosc::LaneChangeAction& action);
std::unique_ptr<ActionInstance> make_lane_offset_action(const xosc::LaneOffsetAction& action);
std::unique_ptr<ActionInstance> make_parameter_set_action(const xosc::ParameterSetAction& action);
std::unique_ptr<ActionInstance> make_parameter_modify_action(
    const xosc::ParameterModifyAction& action);
std::unique_ptr<ActionInstance> make_variable_set_action(const xosc::VariableSetAction& action);
std::unique_ptr<ActionInstance> make_variable_modify_action(
    const xosc::VariableModifyAction& action);
std::unique_ptr<ActionInstance> make_environment_action(const xosc::EnvironmentAction& action);
std::unique_ptr<ActionInstance> make_custom_command_action(const xosc::UserDefinedAction& action);
/// An action kind this engine does not perform yet: warns once (located) and completes.
std::unique_ptr<ActionInstance> make_unsupported_action(std::string_view kind,
                                                        const xosc::Source& source);

}  // namespace corsa::engine::detail
