// The element list of performed_elements.h. An action or condition belongs here when
// actions/action_factory.cpp or conditions/condition_factory.cpp builds a working instance for
// it (none of them falls back to the unsupported-action warning any more).

#include "corsa/engine/performed_elements.h"

#include <array>

namespace corsa::engine {

std::span<const std::string_view> performed_elements() {
  static constexpr std::array<std::string_view, 68> kElements = {
      "AccelerationCondition",
      "AcquirePositionAction",
      "Act",
      "ActivateControllerAction",
      "AddEntityAction",
      "AngleCondition",
      "AnimationAction",
      "AssignControllerAction",
      "AssignRouteAction",
      "CollisionCondition",
      "ConditionGroup",
      "ConnectTrailerAction",
      "CustomCommandAction",
      "DeleteEntityAction",
      "DisconnectTrailerAction",
      "DistanceCondition",
      "EndOfRoadCondition",
      "EnvironmentAction",
      "Event",
      "FollowTrajectoryAction",
      "Init",
      "LaneChangeAction",
      "LaneOffsetAction",
      "LateralDistanceAction",
      "LightStateAction",
      "LongitudinalDistanceAction",
      "Maneuver",
      "ManeuverGroup",
      "ModifyAction",
      "OffroadCondition",
      "OverrideControllerValueAction",
      "ParameterCondition",
      "RandomRouteAction",
      "ReachPositionCondition",
      "RelativeAngleCondition",
      "RelativeClearanceCondition",
      "RelativeDistanceCondition",
      "RelativeSpeedCondition",
      "SetAction",
      "SetMonitorAction",
      "SimulationTimeCondition",
      "SpeedAction",
      "SpeedCondition",
      "SpeedProfileAction",
      "StandStillCondition",
      "StartTrigger",
      "StopTrigger",
      "Story",
      "Storyboard",
      "StoryboardElementStateCondition",
      "SynchronizeAction",
      "TeleportAction",
      "TimeHeadwayCondition",
      "TimeOfDayCondition",
      "TimeToCollisionCondition",
      "TrafficAreaAction",
      "TrafficSignalCondition",
      "TrafficSignalControllerAction",
      "TrafficSignalControllerCondition",
      "TrafficSignalStateAction",
      "TrafficSinkAction",
      "TrafficSourceAction",
      "TrafficStopAction",
      "TrafficSwarmAction",
      "TraveledDistanceCondition",
      "UserDefinedValueCondition",
      "VariableCondition",
      "VisibilityAction",
  };
  return kElements;
}

}  // namespace corsa::engine
