#pragma once

// Global actions (§7.5) and user-defined actions. The grouping elements (EntityAction,
// ParameterAction, InfrastructureAction/TrafficSignalAction, TrafficAction, VariableAction) are
// flattened into GlobalAction, each concrete action keeping the grouping element's attributes.

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "corsa/xosc/common.h"
#include "corsa/xosc/entities.h"
#include "corsa/xosc/environment.h"
#include "corsa/xosc/positions.h"

namespace corsa::xosc {

struct EnvironmentAction {
  Environment environment;  ///< inline or expanded from a catalog
  Source source;
};

struct AddEntityAction {
  std::string entity_ref;
  Position position;
  Source source;
};
struct DeleteEntityAction {
  std::string entity_ref;
  Source source;
};

/// ParameterAction/SetAction (deprecated in 1.2 in favour of VariableAction, still valid).
struct ParameterSetAction {
  std::string parameter_ref;
  std::string value;
  Source source;
};
enum class ModifyRule : uint8_t { kAddValue, kMultiplyByValue };
/// ParameterAction/ModifyAction (deprecated in 1.2).
struct ParameterModifyAction {
  std::string parameter_ref;
  ModifyRule rule = ModifyRule::kAddValue;
  double value = 0.0;
  Source source;
};

struct VariableSetAction {
  std::string variable_ref;
  std::string value;
  Source source;
};
struct VariableModifyAction {
  std::string variable_ref;
  ModifyRule rule = ModifyRule::kAddValue;
  double value = 0.0;
  Source source;
};

struct TrafficSignalControllerAction {
  std::string traffic_signal_controller_ref;
  std::string phase;
  Source source;
};
struct TrafficSignalStateAction {
  std::string name;  ///< traffic signal id
  std::string state;
  Source source;
};

struct SetMonitorAction {
  std::string monitor_ref;
  bool value = false;
  Source source;
};

// --- traffic ---------------------------------------------------------------------------------

struct WeightedVehicleCategory {
  VehicleCategory category = VehicleCategory::kCar;
  double weight = 0.0;
};
struct WeightedRole {
  Role role = Role::kNone;
  double weight = 0.0;
};
struct WeightedController {
  double weight = 0.0;
  Controller controller;  ///< inline or expanded from a catalog
};
/// TrafficDefinition (deprecated in 1.3 in favour of TrafficDistribution).
struct TrafficDefinition {
  std::string name;
  std::vector<WeightedVehicleCategory> vehicle_categories;
  std::vector<WeightedRole> vehicle_roles;
  std::vector<WeightedController> controllers;
  Source source;
};

/// ScenarioObjectTemplate: an entity without a name, as spawned by traffic actions.
struct ScenarioObjectTemplate {
  EntityObject object;
  std::vector<ObjectController> controllers;
  Source source;
};
struct EntityDistributionEntry {
  double weight = 0.0;
  ScenarioObjectTemplate object;
};
struct TrafficDistributionEntry {
  double weight = 0.0;
  std::vector<EntityDistributionEntry> entities;
  Properties properties;
  Source source;
};
struct TrafficDistribution {
  std::vector<TrafficDistributionEntry> entries;
  Source source;
};

struct TrafficSourceAction {
  std::optional<std::string> traffic_name;
  double radius = 0.0;          ///< m
  double rate = 0.0;            ///< vehicles/s
  std::optional<double> speed;  ///< m/s (also the deprecated `velocity`)
  Position position;
  std::optional<TrafficDefinition> traffic_definition;
  std::optional<TrafficDistribution> traffic_distribution;
  Source source;
};
struct TrafficSinkAction {
  std::optional<std::string> traffic_name;
  double radius = 0.0;         ///< m
  std::optional<double> rate;  ///< vehicles/s; unset: infinite
  Position position;
  std::optional<TrafficDefinition> traffic_definition;
  Source source;
};
struct TrafficSwarmAction {
  std::optional<std::string> traffic_name;
  std::string central_object;  ///< entityRef of CentralObject
  double inner_radius = 0.0;   ///< m
  uint32_t number_of_vehicles = 0;
  double offset = 0.0;             ///< m
  double semi_major_axis = 0.0;    ///< m
  double semi_minor_axis = 0.0;    ///< m
  std::optional<double> velocity;  ///< deprecated
  std::optional<TrafficDefinition> traffic_definition;
  std::optional<TrafficDistribution> traffic_distribution;
  std::optional<Range> initial_speed_range;
  std::optional<double> direction_same;  ///< DirectionOfTravelDistribution weights
  std::optional<double> direction_opposite;
  Source source;
};
struct RoadCursor {
  std::string road_id;
  std::optional<double> s;
  std::vector<int> lanes;
  Source source;
};
struct RoadRange {
  std::optional<double> length;
  std::vector<RoadCursor> cursors;
  Source source;
};
struct TrafficAreaAction {
  std::optional<std::string> traffic_name;
  uint32_t number_of_entities = 0;
  bool continuous = false;
  TrafficDistribution traffic_distribution;
  std::vector<Position> polygon;       ///< TrafficArea/Polygon, or
  std::vector<RoadRange> road_ranges;  ///< TrafficArea/RoadRange
  Source source;
};
struct TrafficStopAction {
  std::optional<std::string> traffic_name;
  Source source;
};

using GlobalAction =
    std::variant<EnvironmentAction, AddEntityAction, DeleteEntityAction, ParameterSetAction,
                 ParameterModifyAction, TrafficSignalControllerAction, TrafficSignalStateAction,
                 SetMonitorAction, TrafficSourceAction, TrafficSinkAction, TrafficSwarmAction,
                 TrafficAreaAction, TrafficStopAction, VariableSetAction, VariableModifyAction>;

/// UserDefinedAction/CustomCommandAction: a command for the simulator, type plus text content.
struct UserDefinedAction {
  std::string type;
  std::string content;
  Source source;
};

}  // namespace corsa::xosc
