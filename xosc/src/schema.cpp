// The OpenSCENARIO 1.3 schema as the loader checks it: for each XSD complex type the element
// names it may contain and its attribute names (transcribed from OpenSCENARIO.xsd 1.3, with the
// XSD groups expanded, the 1.0/1.1 deprecated children and attributes included, and the
// non-standard forms read leniently, docs/openscenario.md "Lenient reading"). Parse
// functions name the type they read; children not listed are errors ("unknown element"),
// attributes not listed are warnings. known_elements() is derived from this table.

#include <algorithm>
#include <array>
#include <vector>

#include "schema_table.h"

namespace corsa::xosc {
namespace {

// type|child elements|attributes
constexpr std::string_view kRules = R"(
AbsoluteSpeed|TargetDistanceSteadyState TargetTimeSteadyState|value
AbsoluteTargetLane||value
AbsoluteTargetLaneOffset||value
AbsoluteTargetSpeed||value
AccelerationCondition||rule value direction
AcquirePositionAction|Position|
Act|ManeuverGroup StartTrigger StopTrigger|name
Action|GlobalAction UserDefinedAction PrivateAction|name
ActivateControllerAction||controllerRef objectControllerRef lateral longitudinal animation lighting
Actors|EntityRef|selectTriggeringEntities
AddEntityAction|Position|
AngleCondition||angleType angle angleTolerance coordinateSystem
AnimationAction|AnimationType AnimationState|loop animationDuration
AnimationFile|File|timeOffset
AnimationState||state
AnimationType|ComponentAnimation PedestrianAnimation AnimationFile UserDefinedAnimation|
AppearanceAction|LightStateAction AnimationAction|
AssignControllerAction|Controller CatalogReference ObjectController|activateLateral activateLongitudinal activateAnimation activateLighting
AssignRouteAction|Route CatalogReference|
AutomaticGear||gear
Axle||maxSteering positionX positionZ trackWidth wheelDiameter
Axles|FrontAxle RearAxle AdditionalAxle|
Axels|FrontAxle RearAxle AdditionalAxle Axel|
BoundingBox|Center Dimensions|
Brake||value maxRate
ByEntityCondition|TriggeringEntities EntityCondition|
ByObjectType||type
ByType||objectType
ByValueCondition|ParameterCondition TimeOfDayCondition SimulationTimeCondition StoryboardElementStateCondition UserDefinedValueCondition TrafficSignalCondition TrafficSignalControllerCondition VariableCondition|
Catalog|Vehicle Controller Pedestrian MiscObject Environment Maneuver Trajectory Route|name
CatalogLocation|Directory|
CatalogLocations|VehicleCatalog ControllerCatalog PedestrianCatalog MiscObjectCatalog EnvironmentCatalog ManeuverCatalog TrajectoryCatalog RouteCatalog|
CatalogReference|ParameterAssignments|catalogName entryName
Center||x y z
CentralSwarmObject||entityRef
Clothoid|Position|curvature curvatureDot length startTime stopTime curvaturePrime
ClothoidSpline|ClothoidSplineSegment Segment|timeEnd
ClothoidSplineSegment|PositionStart|curvatureStart curvatureEnd length hOffset timeStart
CollisionCondition|EntityRef ByType|
Color|ColorRgb ColorCmyk|colorType
ColorCmyk||cyan magenta yellow key
ColorRgb||red green blue
ComponentAnimation|VehicleComponent UserDefinedComponent|
Condition|ByEntityCondition ByValueCondition|conditionEdge delay edge name
ConditionGroup|Condition|
ConnectTrailerAction||trailerRef
Controller|ParameterDeclarations Properties|name controllerType
ControllerAction|AssignControllerAction OverrideControllerValueAction ActivateControllerAction|
ControllerDistribution|ControllerDistributionEntry|
ControllerDistributionEntry|Controller CatalogReference|weight
ControlPoint|Position|time weight
CustomCommandAction||type
CustomContent||
DeleteEntityAction||
Deterministic|DeterministicMultiParameterDistribution DeterministicSingleParameterDistribution|
DeterministicMultiParameterDistribution|ValueSetDistribution|
DeterministicSingleParameterDistribution|DistributionSet DistributionRange UserDefinedDistribution|parameterName
Dimensions||height length width
DirectionOfTravelDistribution||same opposite
Directory||path
DisconnectTrailerAction||
DistanceCondition|Position|alongRoute freespace rule value coordinateSystem relativeDistanceType routingAlgorithm
DistributionRange|Range|stepWidth
DistributionSet|Element|
DistributionSetElement||value
DomeImage|DomeFile|azimuthOffset
DynamicConstraints||maxAcceleration maxAccelerationRate maxDeceleration maxDecelerationRate maxSpeed
EndOfRoadCondition||duration
Entities|ScenarioObject EntitySelection|
EntityAction|AddEntityAction DeleteEntityAction|entityRef
EntityCondition|EndOfRoadCondition CollisionCondition OffroadCondition TimeHeadwayCondition TimeToCollisionCondition AccelerationCondition StandStillCondition SpeedCondition RelativeSpeedCondition TraveledDistanceCondition ReachPositionCondition DistanceCondition RelativeDistanceCondition RelativeClearanceCondition AngleCondition RelativeAngleCondition|
EntityDistribution|EntityDistributionEntry|
EntityDistributionEntry|ScenarioObjectTemplate|weight
EntityRef||entityRef
EntitySelection|Members|name
Environment|ParameterDeclarations TimeOfDay Weather RoadCondition|name
EnvironmentAction|Environment CatalogReference|
Event|Action StartTrigger|maximumExecutionCount name priority
ExternalObjectReference||name
File||filepath
FileHeader|License Properties|author date description revMajor revMinor
FinalSpeed|AbsoluteSpeed RelativeSpeedToMaster SteadyState|
Fog|BoundingBox|visualRange
FollowTrajectoryAction|Trajectory CatalogReference TimeReference TrajectoryFollowingMode TrajectoryRef|initialDistanceOffset
GeoPosition|Orientation|latitude longitude height latitudeDeg longitudeDeg altitude verticalRoadSelection
GlobalAction|EnvironmentAction EntityAction InfrastructureAction SetMonitorAction ParameterAction TrafficAction VariableAction|
Histogram|Bin|
HistogramBin|Range|weight
InfrastructureAction|TrafficSignalAction|
Init|Actions|
InitActions|GlobalAction UserDefinedAction Private|
InRoutePosition|FromCurrentEntity FromRoadCoordinates FromLaneCoordinates|
Knot||value
Lane||id
LaneChangeAction|LaneChangeActionDynamics LaneChangeTarget|targetLaneOffset
LaneChangeTarget|RelativeTargetLane AbsoluteTargetLane|
LaneOffsetAction|LaneOffsetActionDynamics LaneOffsetTarget|continuous
LaneOffsetActionDynamics||dynamicsShape maxLateralAcc
LaneOffsetTarget|RelativeTargetLaneOffset AbsoluteTargetLaneOffset|
LanePosition|Orientation|laneId offset roadId s
LateralAction|LaneChangeAction LaneOffsetAction LateralDistanceAction|
LateralDistanceAction|DynamicConstraints|entityRef continuous distance freespace displacement coordinateSystem
License||name resource spdxId
LightState|Color|mode luminousIntensity flashingOnDuration flashingOffDuration
LightStateAction|LightType LightState|transitionTime
LightType|VehicleLight UserDefinedLight|
LogNormalDistribution|Range|expectedValue variance
LongitudinalAction|SpeedAction LongitudinalDistanceAction SpeedProfileAction|
LongitudinalDistanceAction|DynamicConstraints|entityRef continuous distance freespace timeGap displacement coordinateSystem
Maneuver|ParameterDeclarations Event|name
ManeuverGroup|Actors CatalogReference Maneuver|maximumExecutionCount name
ManualGear||number
MiscObject|ParameterDeclarations BoundingBox Properties|mass miscObjectCategory name model3d
ModifyRule|AddValue MultiplyByValue|
MonitorDeclaration||name value
MonitorDeclarations|MonitorDeclaration|
None||
NormalDistribution|Range|expectedValue variance
Nurbs|ControlPoint Knot|order
ObjectController|CatalogReference Controller|name
OffroadCondition||duration
OpenScenario|FileHeader ParameterDeclarations VariableDeclarations MonitorDeclarations CatalogLocations RoadNetwork Entities Storyboard Catalog ParameterValueDistribution|
Orientation||h p r type
OverrideBrakeAction|BrakePercent BrakeForce|active value
OverrideClutchAction||active value maxRate
OverrideControllerValueAction|Throttle Brake Clutch ParkingBrake SteeringWheel Gear|
OverrideGearAction|ManualGear AutomaticGear|active number
OverrideSteeringWheelAction||active value maxRate maxTorque
OverrideThrottleAction||active value maxRate
ParameterAction|SetAction ModifyAction|parameterRef
ParameterAssignment||parameterRef value
ParameterAssignments|ParameterAssignment|
ParameterCondition||parameterRef rule value
ParameterDeclaration|ConstraintGroup|name parameterType value
ParameterDeclarations|ParameterDeclaration|
ParameterModifyAction|Rule|
ParameterSetAction||value
ParameterValueDistribution|ScenarioFile Deterministic Stochastic|
ParameterValueSet|ParameterAssignment|
Pedestrian|ParameterDeclarations BoundingBox Properties|mass model name pedestrianCategory model3d role
PedestrianAnimation|PedestrianGesture|motion userDefinedPedestrianAnimation
PedestrianGesture||gesture
Performance||maxAcceleration maxAccelerationRate maxDeceleration maxDecelerationRate maxSpeed
Phase|TrafficSignalState TrafficSignalGroupState|duration name
PoissonDistribution|Range|expectedValue
Polygon|Position|
Polyline|Vertex|
Position|WorldPosition RelativeWorldPosition RelativeObjectPosition RoadPosition RelativeRoadPosition LanePosition RelativeLanePosition RoutePosition GeoPosition TrajectoryPosition|
PositionInLaneCoordinates||laneId laneOffset pathS
PositionInRoadCoordinates||pathS t
PositionOfCurrentEntity||entityRef
Precipitation||intensity precipitationType precipitationIntensity
Private|PrivateAction|entityRef
PrivateAction|LongitudinalAction LateralAction VisibilityAction SynchronizeAction ActivateControllerAction ControllerAction TeleportAction RoutingAction AppearanceAction TrailerAction|
ProbabilityDistributionSet|Element|
ProbabilityDistributionSetElement||value weight
Properties|Property File CustomContent|
Property||name value
RandomRouteAction||
Range||lowerLimit upperLimit
ReachPositionCondition|Position|tolerance
RelativeAngleCondition||entityRef angleType angle angleTolerance coordinateSystem
RelativeClearanceCondition|RelativeLaneRange EntityRef|oppositeLanes distanceForward distanceBackward freeSpace
RelativeDistanceCondition||entityRef freespace relativeDistanceType rule value coordinateSystem routingAlgorithm
RelativeLanePosition|Orientation|entityRef dLane ds offset dsLane
RelativeLaneRange||from to
RelativeObjectPosition|Orientation|entityRef dx dy dz
RelativeRoadPosition|Orientation|entityRef ds dt
RelativeSpeedCondition||entityRef rule value direction
RelativeSpeedToMaster|TargetDistanceSteadyState TargetTimeSteadyState|speedTargetValueType value
RelativeTargetLane||entityRef value
RelativeTargetLaneOffset||entityRef value
RelativeTargetSpeed||entityRef continuous speedTargetValueType value
RelativeWorldPosition|Orientation|entityRef dx dy dz
RoadCondition|Properties|frictionScaleFactor wetness
RoadCursor|Lane|roadId s
RoadNetwork|LogicFile SceneGraphFile TrafficSignals UsedArea|
RoadPosition|Orientation|roadId s t
RoadRange|RoadCursor|length
Route|ParameterDeclarations Waypoint|closed name
RoutePosition|RouteRef Orientation InRoutePosition|
RouteRef|Route CatalogReference|
RoutingAction|AssignRouteAction FollowTrajectoryAction AcquirePositionAction RandomRouteAction|
ScenarioObject|CatalogReference Vehicle Pedestrian MiscObject ExternalObjectReference ObjectController|name
ScenarioObjectTemplate|CatalogReference Vehicle Pedestrian MiscObject ExternalObjectReference ObjectController|
Segment|PositionStart|curvStart curvEnd curvatureStart curvatureEnd length hOffset timeStart
SelectedEntities|EntityRef ByType|
SensorReference||name
SensorReferenceSet|SensorReference|
SetMonitorAction||monitorRef value
Shape|Polyline Clothoid ClothoidSpline Nurbs|
SimulationTimeCondition||rule value
SpeedAction|SpeedActionDynamics SpeedActionTarget|
SpeedActionTarget|RelativeTargetSpeed AbsoluteTargetSpeed|
SpeedCondition||rule value direction
SpeedProfileAction|DynamicConstraints SpeedProfileEntry|entityRef followingMode
SpeedProfileEntry||speed time
StandStillCondition||duration
SteadyState|TargetDistanceSteadyState TargetTimeSteadyState|
Stochastic|StochasticDistribution|numberOfTestRuns randomSeed
StochasticDistribution|ProbabilityDistributionSet NormalDistribution LogNormalDistribution UniformDistribution PoissonDistribution Histogram UserDefinedDistribution|parameterName
Story|ParameterDeclarations Act|name
Storyboard|Init Story StopTrigger|
StoryboardElementStateCondition||storyboardElementRef state storyboardElementType
Sun||azimuth elevation intensity illuminance
SynchronizeAction|TargetPositionMaster TargetPosition FinalSpeed|masterEntityRef targetToleranceMaster targetTolerance
TargetDistanceSteadyState||distance
TargetTimeSteadyState||time
TeleportAction|Position|
TimeHeadwayCondition||entityRef alongRoute freespace rule value coordinateSystem relativeDistanceType routingAlgorithm
TimeOfDay||animation dateTime
TimeOfDayCondition||dateTime rule
TimeReference|None Timing|
TimeToCollisionCondition|TimeToCollisionConditionTarget|alongRoute freespace rule value relativeDistanceType coordinateSystem routingAlgorithm
TimeToCollisionConditionTarget|Position EntityRef|
Timing||domainAbsoluteRelative offset scale
TrafficAction|TrafficSourceAction TrafficSinkAction TrafficSwarmAction TrafficAreaAction TrafficStopAction|trafficName
TrafficArea|Polygon RoadRange|
TrafficAreaAction|TrafficDistribution TrafficArea|numberOfEntities continuous
TrailerCoupling||dx dz
TrafficDefinition|VehicleCategoryDistribution VehicleRoleDistribution ControllerDistribution|name
TrafficDistribution|TrafficDistributionEntry|
TrafficDistributionEntry|EntityDistribution Properties|weight
TrafficSignalAction|TrafficSignalControllerAction TrafficSignalStateAction|
TrafficSignalCondition||name state
TrafficSignalController|Phase|delay name reference
TrafficSignalControllerAction||trafficSignalControllerRef phase
TrafficSignalControllerCondition||trafficSignalControllerRef phase
TrafficSignalGroupState||state
TrafficSignals|TrafficSignalController|
TrafficSignalState||state trafficSignalId
TrafficSignalStateAction||name state
TrafficSinkAction|Position TrafficDefinition|radius rate
TrafficSourceAction|Position TrafficDefinition TrafficDistribution|radius rate velocity speed
TrafficStopAction||
TrafficSwarmAction|CentralObject CentralSwarmObject TrafficDefinition TrafficDistribution InitialSpeedRange DirectionOfTravelDistribution|innerRadius numberOfVehicles offset semiMajorAxis semiMinorAxis velocity
Trailer|Trailer TrailerRef EntityRef CatalogReference Vehicle|
TrailerAction|ConnectTrailerAction DisconnectTrailerAction|
Trajectory|ParameterDeclarations Shape|closed name
TrajectoryFollowingMode||followingMode
TrajectoryPosition|Orientation TrajectoryRef|s t
TrajectoryRef|Trajectory CatalogReference|
TransitionDynamics||dynamicsDimension dynamicsShape followingMode value
TraveledDistanceCondition||value
Trigger|ConditionGroup|
TriggeringEntities|EntityRef|triggeringEntitiesRule
UniformDistribution|Range|
UsedArea|Position|
UserDefinedAction|CustomCommandAction|
UserDefinedAnimation||userDefinedAnimationType
UserDefinedComponent||userDefinedComponentType
UserDefinedDistribution||type
UserDefinedLight||userDefinedLightType
UserDefinedValueCondition||name rule value
ValueConstraint||rule value
ValueConstraintGroup|ValueConstraint|
ValueRule||value
ValueSetDistribution|ParameterValueSet|
VariableAction|SetAction ModifyAction|variableRef
VariableCondition||variableRef rule value
VariableDeclaration||name variableType value
VariableDeclarations|VariableDeclaration|
VariableModifyAction|Rule|
VariableSetAction||value
Vehicle|ParameterDeclarations BoundingBox Performance Axles Axels Properties TrailerHitch TrailerCoupler Trailer|name vehicleCategory role mass model3d
VehicleCategoryDistribution|VehicleCategoryDistributionEntry|
VehicleCategoryDistributionEntry||category weight
VehicleComponent||vehicleComponentType
VehicleLight||vehicleLightType
VehicleRoleDistribution|VehicleRoleDistributionEntry|
VehicleRoleDistributionEntry||role weight
Vertex|Position|time
VisibilityAction|SensorReferenceSet|graphics sensors traffic
Waypoint|Position|routeStrategy
Weather|Sun Fog Precipitation Wind DomeImage|cloudState atmosphericPressure temperature fractionalCloudCover
Wind||direction speed
WorldPosition||h p r x y z
)";

// The table is laid out at compile time, as places in kRules (schema_table.h, SchemaWord): no
// run builds it, and it is read-only data without relocations.
static_assert(kRules.size() <= UINT16_MAX, "SchemaWord holds places in kRules in 16 bits");

constexpr SchemaWord word_at(std::string_view word) {
  return {static_cast<uint16_t>(word.data() - kRules.data()), static_cast<uint16_t>(word.size())};
}

constexpr std::string_view text_of(SchemaWord word) { return kRules.substr(word.start, word.size); }

// Calls f(word) for each space-separated word of `text`.
template <class F>
constexpr void for_each_word(std::string_view text, F&& f) {
  size_t start = 0;
  while (start < text.size()) {
    const size_t end = std::min(text.find(' ', start), text.size());
    if (end > start) {
      f(text.substr(start, end - start));
    }
    start = end + 1;
  }
}

// Calls f(type, children, attributes) for each line "type|children|attributes" of kRules.
template <class F>
constexpr void for_each_rule(F&& f) {
  size_t start = 0;
  while (start < kRules.size()) {
    const size_t end = std::min(kRules.find('\n', start), kRules.size());
    const std::string_view line = kRules.substr(start, end - start);
    start = end + 1;
    const size_t bar1 = line.find('|');
    if (bar1 == std::string_view::npos) {
      continue;
    }
    const size_t bar2 = line.find('|', bar1 + 1);
    f(line.substr(0, bar1), line.substr(bar1 + 1, bar2 - bar1 - 1), line.substr(bar2 + 1));
  }
}

struct Counts {
  size_t rules = 0;
  size_t children = 0;
  size_t words = 0;  ///< children and attributes
};

constexpr Counts count_table() {
  Counts counts;
  for_each_rule([&](std::string_view, std::string_view children, std::string_view attributes) {
    ++counts.rules;
    for_each_word(children, [&](std::string_view) { ++counts.children; });
    for_each_word(attributes, [&](std::string_view) { ++counts.words; });
  });
  counts.words += counts.children;
  return counts;
}
constexpr Counts kCounts = count_table();
static_assert(kCounts.words <= UINT16_MAX);

struct Table {
  std::array<SchemaWord, kCounts.words> words;  ///< each rule's children, then its attributes
  std::array<TypeRule, kCounts.rules> rules;    ///< by type
};

constexpr Table make_table() {
  Table table;
  size_t word = 0;
  size_t rule = 0;
  for_each_rule([&](std::string_view type, std::string_view children, std::string_view attributes) {
    TypeRule& r = table.rules[rule++];
    r.type_word = word_at(type);
    r.child_first = static_cast<uint16_t>(word);
    for_each_word(children, [&](std::string_view name) { table.words[word++] = word_at(name); });
    r.child_count = static_cast<uint16_t>(word - r.child_first);
    r.attribute_first = static_cast<uint16_t>(word);
    for_each_word(attributes, [&](std::string_view name) { table.words[word++] = word_at(name); });
    r.attribute_count = static_cast<uint16_t>(word - r.attribute_first);
  });
  std::sort(table.rules.begin(), table.rules.end(), [](const TypeRule& a, const TypeRule& b) {
    return text_of(a.type_word) < text_of(b.type_word);
  });
  return table;
}
constexpr Table kTable = make_table();

constexpr bool types_unique() {
  for (size_t i = 1; i < kTable.rules.size(); ++i) {
    if (text_of(kTable.rules[i - 1].type_word) == text_of(kTable.rules[i].type_word)) {
      return false;
    }
  }
  return true;
}
static_assert(types_unique(), "a type listed twice in kRules");

// Every element name the table knows (the root and every rule's children), sorted, once each.
std::vector<ElementInfo> build_elements() {
  std::vector<std::string_view> names{"OpenSCENARIO"};
  for (const TypeRule& rule : kTable.rules) {
    const SchemaNames children = rule.children();
    names.insert(names.end(), children.begin(), children.end());
  }
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  std::vector<ElementInfo> elements;
  elements.reserve(names.size());
  for (const auto name : names) {
    elements.push_back({name, Support::kParsed});
  }
  return elements;
}

}  // namespace

std::string_view schema_word(SchemaWord word) { return text_of(word); }

SchemaNames TypeRule::children() const { return {kTable.words.data() + child_first, child_count}; }

SchemaNames TypeRule::attributes() const {
  return {kTable.words.data() + attribute_first, attribute_count};
}

bool TypeRule::allows_child(std::string_view name) const {
  const SchemaNames names = children();
  return std::find(names.begin(), names.end(), name) != names.end();
}

bool TypeRule::allows_attribute(std::string_view name) const {
  const SchemaNames names = attributes();
  return std::find(names.begin(), names.end(), name) != names.end();
}

const TypeRule* find_type_rule(std::string_view type) {
  const auto& rules = kTable.rules;
  const auto found = std::lower_bound(
      rules.begin(), rules.end(), type,
      [](const TypeRule& rule, std::string_view name) { return rule.type() < name; });
  return found == rules.end() || found->type() != type ? nullptr : &*found;
}

// Built once, at the first call (a run needs none: the documentation's checks do).
std::span<const ElementInfo> known_elements() {
  static const std::vector<ElementInfo> kElements = build_elements();
  return kElements;
}

}  // namespace corsa::xosc
