#pragma once

// Private actions (§7.4): everything that acts on one entity. The grouping elements of the XSD
// (LongitudinalAction, LateralAction, ControllerAction, RoutingAction, AppearanceAction,
// TrailerAction) are flattened: PrivateAction is one variant of the concrete actions.

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "corsa/xosc/common.h"
#include "corsa/xosc/entities.h"
#include "corsa/xosc/enums.h"
#include "corsa/xosc/positions.h"
#include "corsa/xosc/trajectories.h"

namespace corsa::xosc {

/// TransitionDynamics: how a value changes to its target. `value` is a time (s), distance (m) or
/// rate (unit/s) depending on dimension.
struct TransitionDynamics {
  DynamicsDimension dimension = DynamicsDimension::kTime;
  DynamicsShape shape = DynamicsShape::kStep;
  double value = 0.0;
  std::optional<FollowingMode> following_mode;
  Source source;
};

/// DynamicConstraints: limits for distance-keeping actions (m/s, m/s^2, m/s^3).
struct DynamicConstraints {
  std::optional<double> max_acceleration;
  std::optional<double> max_acceleration_rate;
  std::optional<double> max_deceleration;
  std::optional<double> max_deceleration_rate;
  std::optional<double> max_speed;
  Source source;
};

struct AbsoluteTargetSpeed {
  double value = 0.0;  ///< m/s
  Source source;
};
struct RelativeTargetSpeed {
  std::string entity_ref;
  double value = 0.0;  ///< m/s (delta) or factor
  SpeedTargetValueType value_type = SpeedTargetValueType::kDelta;
  bool continuous = false;
  Source source;
};
struct SpeedAction {
  TransitionDynamics dynamics;
  std::variant<AbsoluteTargetSpeed, RelativeTargetSpeed> target;
  Source source;
};

struct LongitudinalDistanceAction {
  std::string entity_ref;
  bool continuous = false;
  bool freespace = false;
  std::optional<double> distance;  ///< m
  std::optional<double> time_gap;  ///< s
  std::optional<LongitudinalDisplacement> displacement;
  std::optional<CoordinateSystem> coordinate_system;
  std::optional<DynamicConstraints> constraints;
  Source source;
};

struct SpeedProfileEntry {
  double speed = 0.0;          ///< m/s
  std::optional<double> time;  ///< s to reach it
  Source source;
};
struct SpeedProfileAction {
  std::optional<std::string> entity_ref;
  FollowingMode following_mode = FollowingMode::kFollow;
  std::optional<DynamicConstraints> constraints;
  std::vector<SpeedProfileEntry> entries;
  Source source;
};

struct RelativeTargetLane {
  std::string entity_ref;
  int value = 0;  ///< lanes to the left (positive) or right (negative)
  Source source;
};
struct AbsoluteTargetLane {
  std::string value;  ///< OpenDRIVE lane id
  Source source;
};
struct LaneChangeAction {
  std::optional<double> target_lane_offset;  ///< m
  TransitionDynamics dynamics;
  std::variant<RelativeTargetLane, AbsoluteTargetLane> target;
  Source source;
};

struct RelativeTargetLaneOffset {
  std::string entity_ref;
  double value = 0.0;  ///< m
  Source source;
};
struct AbsoluteTargetLaneOffset {
  double value = 0.0;  ///< m
  Source source;
};
struct LaneOffsetAction {
  bool continuous = false;
  DynamicsShape shape = DynamicsShape::kLinear;
  std::optional<double> max_lateral_acc;  ///< m/s^2
  std::variant<RelativeTargetLaneOffset, AbsoluteTargetLaneOffset> target;
  Source source;
};

struct LateralDistanceAction {
  std::string entity_ref;
  bool continuous = false;
  bool freespace = false;
  std::optional<double> distance;  ///< m
  std::optional<LateralDisplacement> displacement;
  std::optional<CoordinateSystem> coordinate_system;
  std::optional<DynamicConstraints> constraints;
  Source source;
};

/// A SensorReferenceSet's SensorReference: a sensor's name (the rig's, for Corsa's sensors).
struct SensorReference {
  std::string name;
  Source source;
};

struct VisibilityAction {
  /// Each flag is required by the standard; absent (a lenient reading) means "unchanged".
  std::optional<bool> graphics = true;
  std::optional<bool> sensors = true;
  std::optional<bool> traffic = true;
  std::vector<SensorReference> sensor_refs;  ///< SensorReferenceSet
  Source source;
};

struct TargetDistanceSteadyState {
  double distance = 0.0;  ///< m
  Source source;
};
struct TargetTimeSteadyState {
  double time = 0.0;  ///< s
  Source source;
};
using SteadyState = std::variant<TargetDistanceSteadyState, TargetTimeSteadyState>;
struct AbsoluteSpeed {
  double value = 0.0;
  std::optional<SteadyState> steady_state;
  Source source;
};
struct RelativeSpeedToMaster {
  double value = 0.0;
  SpeedTargetValueType value_type = SpeedTargetValueType::kDelta;
  std::optional<SteadyState> steady_state;
  Source source;
};
struct SynchronizeAction {
  std::string master_entity_ref;
  Position target_position_master;
  Position target_position;
  std::optional<std::variant<AbsoluteSpeed, RelativeSpeedToMaster>> final_speed;
  std::optional<double> target_tolerance_master;  ///< m
  std::optional<double> target_tolerance;         ///< m
  Source source;
};

/// ActivateControllerAction (both the 1.0 placement directly under PrivateAction and the 1.1+
/// one under ControllerAction). Unset domains are left as they are.
struct ActivateControllerAction {
  std::optional<std::string> object_controller_ref;  ///< also the deprecated controllerRef
  std::optional<bool> lateral;
  std::optional<bool> longitudinal;
  std::optional<bool> animation;
  std::optional<bool> lighting;
  Source source;
};

/// AssignControllerAction: the controller (inline, from a catalog, or the 1.0/1.1 direct
/// Controller / CatalogReference children, all expanded) and which domains to activate.
struct AssignControllerAction {
  ObjectController controller;
  std::optional<bool> activate_lateral;
  std::optional<bool> activate_longitudinal;
  std::optional<bool> activate_animation;
  std::optional<bool> activate_lighting;
  Source source;
};

struct OverrideValue {
  bool active = false;
  double value = 0.0;
  std::optional<double> max_rate;
  Source source;
};
/// Brake / parking brake: BrakePercent (0..1) or BrakeForce (N); 1.0 `value` is a percentage.
struct OverrideBrake {
  bool active = false;
  bool force = false;  ///< BrakeForce rather than BrakePercent
  std::optional<double> value;
  std::optional<double> max_rate;
  Source source;
};
struct OverrideSteeringWheel {
  bool active = false;
  double value = 0.0;  ///< rad
  std::optional<double> max_rate;
  std::optional<double> max_torque;
  Source source;
};
struct ManualGear {
  int number = 0;
};
struct AutomaticGear {
  AutomaticGearType gear = AutomaticGearType::kD;
};
struct OverrideGear {
  bool active = false;
  std::optional<std::variant<ManualGear, AutomaticGear>> gear;  ///< 1.0 `number` -> ManualGear
  Source source;
};
struct OverrideControllerValueAction {
  std::optional<OverrideValue> throttle;
  std::optional<OverrideBrake> brake;
  std::optional<OverrideValue> clutch;
  std::optional<OverrideBrake> parking_brake;
  std::optional<OverrideSteeringWheel> steering_wheel;
  std::optional<OverrideGear> gear;
  Source source;
};

struct TeleportAction {
  Position position;
  Source source;
};

struct AssignRouteAction {
  Route route;
  Source source;
};

/// FollowTrajectoryAction: trajectory (inline, catalog, or via TrajectoryRef, all expanded),
/// time reference and following mode.
struct FollowTrajectoryAction {
  Trajectory trajectory;
  TimeReference time_reference;
  FollowingMode following_mode = FollowingMode::kPosition;
  std::optional<double> initial_distance_offset;  ///< m
  Source source;
};

struct AcquirePositionAction {
  Position position;
  Source source;
};

struct RandomRouteAction {
  Source source;
};

struct ColorRgb {
  double red = 0.0, green = 0.0, blue = 0.0;  ///< 0..1
};
struct ColorCmyk {
  double cyan = 0.0, magenta = 0.0, yellow = 0.0, key = 0.0;  ///< 0..1
};
struct Color {
  ColorType type = ColorType::kOther;
  std::optional<std::variant<ColorRgb, ColorCmyk>> value;
  Source source;
};
struct LightState {
  LightMode mode = LightMode::kOn;
  std::optional<double> luminous_intensity;     ///< cd
  std::optional<double> flashing_on_duration;   ///< s
  std::optional<double> flashing_off_duration;  ///< s
  std::optional<Color> color;
  Source source;
};
/// LightType: a standard vehicle light, or a user-defined light type name.
using LightType = std::variant<VehicleLightType, std::string>;
struct LightStateAction {
  LightType light_type;
  LightState light_state;
  std::optional<double> transition_time;  ///< s
  Source source;
};

struct PedestrianAnimation {
  std::optional<PedestrianMotionType> motion;
  std::optional<std::string> user_defined_pedestrian_animation;
  std::vector<PedestrianGestureType> gestures;
  Source source;
};
/// ComponentAnimation: a vehicle component, or a user-defined component type name.
struct ComponentAnimation {
  std::variant<VehicleComponentType, std::string> component;
  Source source;
};
struct AnimationFile {
  File file;
  std::optional<double> time_offset;  ///< s
  Source source;
};
struct UserDefinedAnimation {
  std::string type;
  Source source;
};
using AnimationType =
    std::variant<ComponentAnimation, PedestrianAnimation, AnimationFile, UserDefinedAnimation>;
struct AnimationAction {
  AnimationType animation_type;
  std::optional<double> state;  ///< AnimationState, 0..1
  std::optional<bool> loop;
  std::optional<double> animation_duration;  ///< s
  Source source;
};

struct ConnectTrailerAction {
  std::string trailer_ref;
  Source source;
};
struct DisconnectTrailerAction {
  Source source;
};

using PrivateAction =
    std::variant<SpeedAction, LongitudinalDistanceAction, SpeedProfileAction, LaneChangeAction,
                 LaneOffsetAction, LateralDistanceAction, VisibilityAction, SynchronizeAction,
                 ActivateControllerAction, AssignControllerAction, OverrideControllerValueAction,
                 TeleportAction, AssignRouteAction, FollowTrajectoryAction, AcquirePositionAction,
                 RandomRouteAction, LightStateAction, AnimationAction, ConnectTrailerAction,
                 DisconnectTrailerAction>;

}  // namespace corsa::xosc
