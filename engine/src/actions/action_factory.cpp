#include "actions/action_factory.h"

#include <type_traits>

#include "actions/action_makers.h"

namespace corsa::engine::detail {
namespace {

// The name of an action kind as it appears in OpenSCENARIO, for the unsupported warning.
template <typename T>
constexpr std::string_view kind_name() {
  if constexpr (std::is_same_v<T, xosc::LongitudinalDistanceAction>)
    return "LongitudinalDistanceAction";
  else if constexpr (std::is_same_v<T, xosc::SpeedProfileAction>)
    return "SpeedProfileAction";
  else if constexpr (std::is_same_v<T, xosc::LateralDistanceAction>)
    return "LateralDistanceAction";
  else if constexpr (std::is_same_v<T, xosc::VisibilityAction>)
    return "VisibilityAction";
  else if constexpr (std::is_same_v<T, xosc::SynchronizeAction>)
    return "SynchronizeAction";
  else if constexpr (std::is_same_v<T, xosc::ActivateControllerAction>)
    return "ActivateControllerAction";
  else if constexpr (std::is_same_v<T, xosc::AssignControllerAction>)
    return "AssignControllerAction";
  else if constexpr (std::is_same_v<T, xosc::OverrideControllerValueAction>)
    return "OverrideControllerValueAction";
  else if constexpr (std::is_same_v<T, xosc::AssignRouteAction>)
    return "AssignRouteAction";
  else if constexpr (std::is_same_v<T, xosc::FollowTrajectoryAction>)
    return "FollowTrajectoryAction";
  else if constexpr (std::is_same_v<T, xosc::AcquirePositionAction>)
    return "AcquirePositionAction";
  else if constexpr (std::is_same_v<T, xosc::AddEntityAction>)
    return "AddEntityAction";
  else if constexpr (std::is_same_v<T, xosc::DeleteEntityAction>)
    return "DeleteEntityAction";
  else if constexpr (std::is_same_v<T, xosc::TrafficSignalControllerAction>)
    return "TrafficSignalControllerAction";
  else if constexpr (std::is_same_v<T, xosc::TrafficSignalStateAction>)
    return "TrafficSignalStateAction";
  else if constexpr (std::is_same_v<T, xosc::TrafficSourceAction>)
    return "TrafficSourceAction";
  else if constexpr (std::is_same_v<T, xosc::TrafficSinkAction>)
    return "TrafficSinkAction";
  else if constexpr (std::is_same_v<T, xosc::TrafficSwarmAction>)
    return "TrafficSwarmAction";
  else if constexpr (std::is_same_v<T, xosc::TrafficAreaAction>)
    return "TrafficAreaAction";
  else if constexpr (std::is_same_v<T, xosc::TrafficStopAction>)
    return "TrafficStopAction";
  else
    return "this action";
}

}  // namespace

std::unique_ptr<ActionInstance> make_private_action(const xosc::PrivateAction& action) {
  return std::visit(
      [](const auto& a) -> std::unique_ptr<ActionInstance> {
        using T = std::decay_t<decltype(a)>;
        if constexpr (std::is_same_v<T, xosc::TeleportAction>) {
          return make_teleport_action(a);
        } else if constexpr (std::is_same_v<T, xosc::SpeedAction>) {
          return make_speed_action(a);
        } else if constexpr (std::is_same_v<T, xosc::LaneChangeAction>) {
          return make_lane_change_action(a);
        } else if constexpr (std::is_same_v<T, xosc::LaneOffsetAction>) {
          return make_lane_offset_action(a);
        } else if constexpr (std::is_same_v<T, xosc::VisibilityAction>) {
          return make_visibility_action(a);
        } else if constexpr (std::is_same_v<T, xosc::LightStateAction>) {
          return make_light_state_action(a);
        } else if constexpr (std::is_same_v<T, xosc::ActivateControllerAction>) {
          return make_activate_controller_action(a);
        } else if constexpr (std::is_same_v<T, xosc::AssignControllerAction>) {
          return make_assign_controller_action(a);
        } else if constexpr (std::is_same_v<T, xosc::OverrideControllerValueAction>) {
          return make_override_controller_action(a);
        } else if constexpr (std::is_same_v<T, xosc::AssignRouteAction>) {
          return make_assign_route_action(a);
        } else if constexpr (std::is_same_v<T, xosc::AcquirePositionAction>) {
          return make_acquire_position_action(a);
        } else if constexpr (std::is_same_v<T, xosc::SynchronizeAction>) {
          return make_synchronize_action(a);
        } else if constexpr (std::is_same_v<T, xosc::FollowTrajectoryAction>) {
          return make_follow_trajectory_action(a);
        } else if constexpr (std::is_same_v<T, xosc::LongitudinalDistanceAction>) {
          return make_longitudinal_distance_action(a);
        } else if constexpr (std::is_same_v<T, xosc::LateralDistanceAction>) {
          return make_lateral_distance_action(a);
        } else if constexpr (std::is_same_v<T, xosc::SpeedProfileAction>) {
          return make_speed_profile_action(a);
        } else if constexpr (std::is_same_v<T, xosc::ConnectTrailerAction>) {
          return make_connect_trailer_action(a);
        } else if constexpr (std::is_same_v<T, xosc::DisconnectTrailerAction>) {
          return make_disconnect_trailer_action(a);
        } else if constexpr (std::is_same_v<T, xosc::RandomRouteAction>) {
          return make_random_route_action(a);
        } else if constexpr (std::is_same_v<T, xosc::AnimationAction>) {
          return make_animation_action(a);
        } else {
          return make_unsupported_action(kind_name<T>(), a.source);
        }
      },
      action);
}

std::unique_ptr<ActionInstance> make_global_action(const xosc::GlobalAction& action) {
  return std::visit(
      [](const auto& a) -> std::unique_ptr<ActionInstance> {
        using T = std::decay_t<decltype(a)>;
        if constexpr (std::is_same_v<T, xosc::EnvironmentAction>) {
          return make_environment_action(a);
        } else if constexpr (std::is_same_v<T, xosc::ParameterSetAction>) {
          return make_parameter_set_action(a);
        } else if constexpr (std::is_same_v<T, xosc::ParameterModifyAction>) {
          return make_parameter_modify_action(a);
        } else if constexpr (std::is_same_v<T, xosc::VariableSetAction>) {
          return make_variable_set_action(a);
        } else if constexpr (std::is_same_v<T, xosc::VariableModifyAction>) {
          return make_variable_modify_action(a);
        } else if constexpr (std::is_same_v<T, xosc::AddEntityAction>) {
          return make_add_entity_action(a);
        } else if constexpr (std::is_same_v<T, xosc::DeleteEntityAction>) {
          return make_delete_entity_action(a);
        } else if constexpr (std::is_same_v<T, xosc::TrafficSignalStateAction>) {
          return make_traffic_signal_state_action(a);
        } else if constexpr (std::is_same_v<T, xosc::TrafficSignalControllerAction>) {
          return make_traffic_signal_controller_action(a);
        } else if constexpr (std::is_same_v<T, xosc::TrafficSwarmAction>) {
          return make_traffic_swarm_action(a);
        } else if constexpr (std::is_same_v<T, xosc::TrafficAreaAction>) {
          return make_traffic_area_action(a);
        } else if constexpr (std::is_same_v<T, xosc::TrafficSourceAction>) {
          return make_traffic_source_action(a);
        } else if constexpr (std::is_same_v<T, xosc::TrafficSinkAction>) {
          return make_traffic_sink_action(a);
        } else if constexpr (std::is_same_v<T, xosc::TrafficStopAction>) {
          return make_traffic_stop_action(a);
        } else if constexpr (std::is_same_v<T, xosc::SetMonitorAction>) {
          return make_set_monitor_action(a);
        } else {
          return make_unsupported_action(kind_name<T>(), a.source);
        }
      },
      action);
}

std::unique_ptr<ActionInstance> make_user_defined_action(const xosc::UserDefinedAction& action) {
  return make_custom_command_action(action);
}

std::unique_ptr<ActionInstance> make_action(const xosc::Action& action) {
  return std::visit(
      [](const auto& a) -> std::unique_ptr<ActionInstance> {
        using T = std::decay_t<decltype(a)>;
        if constexpr (std::is_same_v<T, xosc::PrivateAction>) {
          return make_private_action(a);
        } else if constexpr (std::is_same_v<T, xosc::GlobalAction>) {
          return make_global_action(a);
        } else {
          return make_user_defined_action(a);
        }
      },
      action.action);
}

}  // namespace corsa::engine::detail
