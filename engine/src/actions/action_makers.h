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
std::unique_ptr<ActionInstance> make_set_monitor_action(const xosc::SetMonitorAction& action);
std::unique_ptr<ActionInstance> make_light_state_action(const xosc::LightStateAction& action);
std::unique_ptr<ActionInstance> make_animation_action(const xosc::AnimationAction& action);
std::unique_ptr<ActionInstance> make_random_route_action(const xosc::RandomRouteAction& action);
std::unique_ptr<ActionInstance> make_connect_trailer_action(
    const xosc::ConnectTrailerAction& action);
std::unique_ptr<ActionInstance> make_disconnect_trailer_action(
    const xosc::DisconnectTrailerAction& action);
std::unique_ptr<ActionInstance> make_variable_modify_action(
    const xosc::VariableModifyAction& action);
std::unique_ptr<ActionInstance> make_environment_action(const xosc::EnvironmentAction& action);
std::unique_ptr<ActionInstance> make_custom_command_action(const xosc::UserDefinedAction& action);
// Entities, visibility, controllers, traffic signals and traffic.
std::unique_ptr<ActionInstance> make_add_entity_action(const xosc::AddEntityAction& action);
std::unique_ptr<ActionInstance> make_delete_entity_action(const xosc::DeleteEntityAction& action);
std::unique_ptr<ActionInstance> make_visibility_action(const xosc::VisibilityAction& action);
std::unique_ptr<ActionInstance> make_activate_controller_action(
    const xosc::ActivateControllerAction& action);
std::unique_ptr<ActionInstance> make_assign_controller_action(
    const xosc::AssignControllerAction& action);
std::unique_ptr<ActionInstance> make_override_controller_action(
    const xosc::OverrideControllerValueAction& action);
std::unique_ptr<ActionInstance> make_traffic_signal_state_action(
    const xosc::TrafficSignalStateAction& action);
std::unique_ptr<ActionInstance> make_traffic_signal_controller_action(
    const xosc::TrafficSignalControllerAction& action);
std::unique_ptr<ActionInstance> make_traffic_swarm_action(const xosc::TrafficSwarmAction& action);
std::unique_ptr<ActionInstance> make_traffic_area_action(const xosc::TrafficAreaAction& action);
std::unique_ptr<ActionInstance> make_traffic_source_action(const xosc::TrafficSourceAction& action);
std::unique_ptr<ActionInstance> make_traffic_sink_action(const xosc::TrafficSinkAction& action);
std::unique_ptr<ActionInstance> make_traffic_stop_action(const xosc::TrafficStopAction& action);
std::unique_ptr<ActionInstance> make_assign_route_action(const xosc::AssignRouteAction& action);
std::unique_ptr<ActionInstance> make_acquire_position_action(
    const xosc::AcquirePositionAction& action);
std::unique_ptr<ActionInstance> make_synchronize_action(const xosc::SynchronizeAction& action);
std::unique_ptr<ActionInstance> make_follow_trajectory_action(
    const xosc::FollowTrajectoryAction& action);
std::unique_ptr<ActionInstance> make_longitudinal_distance_action(
    const xosc::LongitudinalDistanceAction& action);
std::unique_ptr<ActionInstance> make_lateral_distance_action(
    const xosc::LateralDistanceAction& action);
std::unique_ptr<ActionInstance> make_speed_profile_action(const xosc::SpeedProfileAction& action);
/// An action kind this engine does not perform yet: warns once (located) and completes.
std::unique_ptr<ActionInstance> make_unsupported_action(std::string_view kind,
                                                        const xosc::Source& source);

}  // namespace corsa::engine::detail
