#pragma once

// Conditions and triggers (§8): ByEntityCondition (16 kinds) and ByValueCondition (8 kinds).
// A Trigger fires when any ConditionGroup fires; a group fires when all its conditions hold.

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "corsa/xosc/common.h"
#include "corsa/xosc/enums.h"
#include "corsa/xosc/positions.h"

namespace corsa::xosc {

struct EndOfRoadCondition {
  double duration = 0.0;  ///< s
  Source source;
};
/// Collision with a named entity, or with any object of a type.
struct CollisionCondition {
  std::optional<std::string> entity_ref;
  std::optional<ObjectType> by_type;
  Source source;
};
struct OffroadCondition {
  double duration = 0.0;  ///< s
  Source source;
};
struct TimeHeadwayCondition {
  std::string entity_ref;
  double value = 0.0;  ///< s
  bool freespace = false;
  Rule rule = Rule::kLessThan;
  std::optional<bool> along_route;  ///< deprecated
  std::optional<CoordinateSystem> coordinate_system;
  std::optional<RelativeDistanceType> relative_distance_type;
  std::optional<RoutingAlgorithm> routing_algorithm;
  Source source;
};
struct TimeToCollisionCondition {
  double value = 0.0;  ///< s
  bool freespace = false;
  Rule rule = Rule::kLessThan;
  std::optional<bool> along_route;  ///< deprecated
  std::optional<CoordinateSystem> coordinate_system;
  std::optional<RelativeDistanceType> relative_distance_type;
  std::optional<RoutingAlgorithm> routing_algorithm;
  std::optional<std::string> target_entity_ref;  ///< target is an entity, or
  std::optional<Position> target_position;       ///< a position
  Source source;
};
struct AccelerationCondition {
  double value = 0.0;  ///< m/s^2
  Rule rule = Rule::kGreaterThan;
  std::optional<DirectionalDimension> direction;
  Source source;
};
struct StandStillCondition {
  double duration = 0.0;  ///< s
  Source source;
};
struct SpeedCondition {
  double value = 0.0;  ///< m/s
  Rule rule = Rule::kGreaterThan;
  std::optional<DirectionalDimension> direction;
  Source source;
};
struct RelativeSpeedCondition {
  std::string entity_ref;
  double value = 0.0;  ///< m/s, triggering minus reference
  Rule rule = Rule::kGreaterThan;
  std::optional<DirectionalDimension> direction;
  Source source;
};
struct TraveledDistanceCondition {
  double value = 0.0;  ///< m
  Source source;
};
/// ReachPositionCondition (deprecated in 1.2 in favour of DistanceCondition).
struct ReachPositionCondition {
  Position position;
  double tolerance = 0.0;  ///< m
  Source source;
};
struct DistanceCondition {
  Position position;
  double value = 0.0;  ///< m
  bool freespace = false;
  Rule rule = Rule::kLessThan;
  std::optional<bool> along_route;  ///< deprecated
  std::optional<CoordinateSystem> coordinate_system;
  std::optional<RelativeDistanceType> relative_distance_type;
  std::optional<RoutingAlgorithm> routing_algorithm;
  Source source;
};
struct RelativeDistanceCondition {
  std::string entity_ref;
  double value = 0.0;  ///< m
  bool freespace = false;
  RelativeDistanceType relative_distance_type = RelativeDistanceType::kEuclidianDistance;
  Rule rule = Rule::kLessThan;
  std::optional<CoordinateSystem> coordinate_system;
  std::optional<RoutingAlgorithm> routing_algorithm;
  Source source;
};
struct RelativeLaneRange {
  std::optional<int> from;
  std::optional<int> to;
};
struct RelativeClearanceCondition {
  bool opposite_lanes = false;
  bool free_space = false;
  std::optional<double> distance_forward;   ///< m
  std::optional<double> distance_backward;  ///< m
  std::vector<RelativeLaneRange> lane_ranges;
  std::vector<std::string> entity_refs;
  Source source;
};
struct AngleCondition {
  AngleType angle_type = AngleType::kHeading;
  double angle = 0.0;            ///< rad
  double angle_tolerance = 0.0;  ///< rad
  std::optional<CoordinateSystem> coordinate_system;
  Source source;
};
struct RelativeAngleCondition {
  std::string entity_ref;
  AngleType angle_type = AngleType::kHeading;
  double angle = 0.0;
  double angle_tolerance = 0.0;
  std::optional<CoordinateSystem> coordinate_system;
  Source source;
};

using EntityCondition =
    std::variant<EndOfRoadCondition, CollisionCondition, OffroadCondition, TimeHeadwayCondition,
                 TimeToCollisionCondition, AccelerationCondition, StandStillCondition,
                 SpeedCondition, RelativeSpeedCondition, TraveledDistanceCondition,
                 ReachPositionCondition, DistanceCondition, RelativeDistanceCondition,
                 RelativeClearanceCondition, AngleCondition, RelativeAngleCondition>;

struct TriggeringEntities {
  TriggeringEntitiesRule rule = TriggeringEntitiesRule::kAny;
  std::vector<std::string> entity_refs;
  Source source;
};

struct ByEntityCondition {
  TriggeringEntities triggering_entities;
  EntityCondition condition;
  Source source;
};

/// ParameterCondition: compares a parameter's current value (text, typed by its declaration).
struct ParameterCondition {
  std::string parameter_ref;
  Rule rule = Rule::kEqualTo;
  std::string value;
  Source source;
};
struct TimeOfDayCondition {
  std::string date_time;
  Rule rule = Rule::kGreaterThan;
  Source source;
};
struct SimulationTimeCondition {
  double value = 0.0;  ///< s
  Rule rule = Rule::kGreaterThan;
  Source source;
};
struct StoryboardElementStateCondition {
  StoryboardElementType type = StoryboardElementType::kEvent;
  std::string storyboard_element_ref;  ///< as written (a name or a `::`-qualified name)
  /// The referenced element's full path ("Story::Act::ManeuverGroup::Maneuver::Event..."), as
  /// resolved by the loader with the standard's name-lookup rules.
  std::string resolved_path;
  StoryboardElementState state = StoryboardElementState::kCompleteState;
  Source source;
};
struct UserDefinedValueCondition {
  std::string name;
  Rule rule = Rule::kEqualTo;
  std::string value;
  Source source;
};
struct TrafficSignalCondition {
  std::string name;
  std::string state;
  Source source;
};
struct TrafficSignalControllerCondition {
  std::string traffic_signal_controller_ref;
  std::string phase;
  Source source;
};
struct VariableCondition {
  std::string variable_ref;
  Rule rule = Rule::kEqualTo;
  std::string value;
  Source source;
};

using ByValueCondition =
    std::variant<ParameterCondition, TimeOfDayCondition, SimulationTimeCondition,
                 StoryboardElementStateCondition, UserDefinedValueCondition, TrafficSignalCondition,
                 TrafficSignalControllerCondition, VariableCondition>;

struct Condition {
  std::string name;
  double delay = 0.0;  ///< s
  ConditionEdge edge = ConditionEdge::kNone;
  std::variant<ByEntityCondition, ByValueCondition> kind;
  Source source;
};

struct ConditionGroup {
  std::vector<Condition> conditions;
  Source source;
};

/// Trigger: fires when any of its groups holds. An empty trigger never fires.
struct Trigger {
  std::vector<ConditionGroup> groups;
  Source source;
};

}  // namespace corsa::xosc
