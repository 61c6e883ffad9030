#pragma once

// Scenarios of many vehicles on the bundled 2 km motorway (scenarios/maps/motorway_2km.xodr:
// road 1, three lanes each way), written as OpenSCENARIO 1.3 text, for the tests and benchmarks
// that drive many vehicles under one controller (the dynamics controller's fleet integration).
// Needs CORSA_SOURCE_DIR (the repository root) defined.

#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace corsa::test {

/// One vehicle: a 4.5 m x 1.8 m car (with axles for the dynamics model) placed on road 1.
struct FleetVehicle {
  std::string name;
  int lane = -1;       ///< OpenDRIVE lane id (negative: right of the reference line, toward +s)
  double s = 0.0;      ///< m along road 1
  double speed = 0.0;  ///< m/s, set at once in Init

  /// Performance: maxSpeed (m/s), maxAcceleration and maxDeceleration (m/s^2).
  double max_speed = 50.0;
  double max_acceleration = 4.0;
  double max_deceleration = 8.0;

  /// A SpeedAction to `speed` (m/s), cubic over `duration` s, once the simulation time is past
  /// `after` s.
  struct SpeedChange {
    double speed = 0.0;
    double duration = 0.0;
    double after = 0.0;
  };
  std::optional<SpeedChange> speed_change;

  /// A LaneChangeAction by `lanes` relative to the vehicle's own lane (OpenSCENARIO sign: + to
  /// the left), sinusoidal over `duration` s, once the simulation time is past `after` s, or,
  /// with `after_traveled`, once the vehicle has driven that many metres.
  struct LaneChange {
    int lanes = 0;
    double after = 0.0;
    double duration = 4.0;
    std::optional<double> after_traveled;
  };
  std::optional<LaneChange> lane_change;
};

namespace detail {

inline std::string fleet_speed_action(double value, const char* shape, double time) {
  std::ostringstream out;
  out << "<PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape=\""
      << shape << "\" value=\"" << time
      << "\" dynamicsDimension=\"time\"/><SpeedActionTarget><AbsoluteTargetSpeed value=\"" << value
      << "\"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction>";
  return out.str();
}

inline std::string fleet_time_trigger(double after) {
  std::ostringstream out;
  out << "<StartTrigger><ConditionGroup><Condition name=\"t\" delay=\"0\" "
      << "conditionEdge=\"rising\"><ByValueCondition><SimulationTimeCondition value=\"" << after
      << "\" rule=\"greaterThan\"/></ByValueCondition></Condition></ConditionGroup>"
      << "</StartTrigger>";
  return out.str();
}

// The vehicle's lane change starts once it has driven `traveled` m.
inline std::string fleet_distance_trigger(const std::string& name, double traveled) {
  std::ostringstream out;
  out << "<StartTrigger><ConditionGroup><Condition name=\"near\" delay=\"0\" "
      << "conditionEdge=\"none\"><ByEntityCondition><TriggeringEntities "
      << "triggeringEntitiesRule=\"any\"><EntityRef entityRef=\"" << name
      << "\"/></TriggeringEntities><EntityCondition><TraveledDistanceCondition value=\"" << traveled
      << "\"/></EntityCondition></ByEntityCondition></Condition>"
      << "</ConditionGroup></StartTrigger>";
  return out.str();
}

inline std::string fleet_vehicle_object(const FleetVehicle& v) {
  std::ostringstream out;
  out << "<ScenarioObject name=\"" << v.name << "\"><Vehicle name=\"car\" "
      << "vehicleCategory=\"car\"><Performance maxSpeed=\"" << v.max_speed
      << "\" maxAcceleration=\"" << v.max_acceleration << "\" maxDeceleration=\""
      << v.max_deceleration << "\"/><BoundingBox><Center x=\"1.4\" y=\"0\" z=\"0.75\"/>"
      << "<Dimensions width=\"1.8\" length=\"4.5\" height=\"1.5\"/></BoundingBox><Axles>"
      << "<FrontAxle maxSteering=\"0.5\" wheelDiameter=\"0.6\" trackWidth=\"1.6\" "
      << "positionX=\"2.8\" positionZ=\"0.3\"/><RearAxle maxSteering=\"0\" "
      << "wheelDiameter=\"0.6\" trackWidth=\"1.6\" positionX=\"0\" positionZ=\"0.3\"/>"
      << "</Axles></Vehicle></ScenarioObject>";
  return out.str();
}

// The maneuver group of vehicle `index` (its speed and lane changes), or "" without any.
inline std::string fleet_group(const FleetVehicle& v, size_t index) {
  if (!v.speed_change && !v.lane_change) {
    return "";
  }
  std::ostringstream out;
  out << "<ManeuverGroup maximumExecutionCount=\"1\" name=\"G" << index << "\"><Actors "
      << "selectTriggeringEntities=\"false\"><EntityRef entityRef=\"" << v.name << "\"/>"
      << "</Actors><Maneuver name=\"M\">";
  if (v.speed_change) {
    out << "<Event name=\"Vary\" priority=\"parallel\"><Action name=\"Speed\">"
        << fleet_speed_action(v.speed_change->speed, "cubic", v.speed_change->duration)
        << "</Action>" << fleet_time_trigger(v.speed_change->after) << "</Event>";
  }
  if (v.lane_change) {
    out << "<Event name=\"Change\" priority=\"parallel\"><Action name=\"Lane\">"
        << "<PrivateAction><LateralAction><LaneChangeAction><LaneChangeActionDynamics "
        << "dynamicsShape=\"sinusoidal\" value=\"" << v.lane_change->duration
        << "\" dynamicsDimension=\"time\"/>"
        << "<LaneChangeTarget><RelativeTargetLane entityRef=\"" << v.name << "\" value=\""
        << v.lane_change->lanes << "\"/></LaneChangeTarget>"
        << "</LaneChangeAction></LateralAction></PrivateAction></Action>"
        << (v.lane_change->after_traveled
                ? fleet_distance_trigger(v.name, *v.lane_change->after_traveled)
                : fleet_time_trigger(v.lane_change->after))
        << "</Event>";
  }
  out << "</Maneuver></ManeuverGroup>";
  return out.str();
}

}  // namespace detail

/// The scenario of `vehicles`, described by `description`: each placed in Init at its speed, one
/// maneuver group per vehicle with a speed or lane change, and a stop trigger after an hour (a
/// run ends at its duration). Parse it as if read from motorway_fleet_path().
inline std::string motorway_fleet_scenario(const std::vector<FleetVehicle>& vehicles,
                                           const std::string& description) {
  std::ostringstream entities, init, groups;
  for (size_t i = 0; i < vehicles.size(); ++i) {
    const FleetVehicle& v = vehicles[i];
    entities << detail::fleet_vehicle_object(v);
    init << "<Private entityRef=\"" << v.name << "\"><PrivateAction><TeleportAction><Position>"
         << "<LanePosition roadId=\"1\" laneId=\"" << v.lane << "\" s=\"" << v.s << "\"/>"
         << "</Position></TeleportAction></PrivateAction>"
         << detail::fleet_speed_action(v.speed, "step", 0) << "</Private>";
    groups << detail::fleet_group(v, i);
  }
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?><OpenSCENARIO><FileHeader revMajor=\"1\" revMinor=\"3\" "
      << "date=\"2026-01-01T00:00:00\" description=\"" << description << "\" author=\"Corsa\"/>"
      << "<ParameterDeclarations/><CatalogLocations/><RoadNetwork><LogicFile "
         "filepath=\"maps/motorway_2km.xodr\"/></RoadNetwork><Entities>"
      << entities.str() << "</Entities><Storyboard><Init><Actions>" << init.str()
      << "</Actions></Init><Story name=\"Traffic\"><Act name=\"Drive\">" << groups.str()
      << "</Act></Story><StopTrigger><ConditionGroup><Condition name=\"end\" delay=\"0\" "
         "conditionEdge=\"none\"><ByValueCondition><SimulationTimeCondition value=\"3600\" "
         "rule=\"greaterThan\"/></ByValueCondition></Condition></ConditionGroup></StopTrigger>"
         "</Storyboard></OpenSCENARIO>";
  return out.str();
}

/// Where a motorway fleet scenario is taken to be (scenarios/, so that its road network
/// maps/motorway_2km.xodr resolves); no such file exists.
inline std::filesystem::path motorway_fleet_path() {
  return std::filesystem::path(CORSA_SOURCE_DIR) / "scenarios/motorway_fleet.xosc";
}

}  // namespace corsa::test
