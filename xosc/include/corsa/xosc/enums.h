#pragma once

// The enumerations of OpenSCENARIO 1.3 (XSD simple types). Deprecated spellings of 1.0/1.1 are
// mapped to their successors by the loader (with a warning), so e.g. Priority has no kOverwrite.
// to_string gives the 1.3 spelling.

#include <cstdint>
#include <string_view>

namespace corsa::xosc {

enum class AngleType : uint8_t { kHeading, kPitch, kRoll };
enum class AutomaticGearType : uint8_t { kN, kP, kR, kD };
/// Deprecated in 1.2 in favour of FractionalCloudCover; kept for 1.0/1.1 files.
enum class CloudState : uint8_t { kCloudy, kFree, kOvercast, kRainy, kSkyOff };
enum class ColorType : uint8_t {
  kOther,
  kRed,
  kYellow,
  kGreen,
  kBlue,
  kViolet,
  kOrange,
  kBrown,
  kBlack,
  kGrey,
  kWhite
};
enum class ConditionEdge : uint8_t { kFalling, kNone, kRising, kRisingOrFalling };
enum class ControllerType : uint8_t {
  kLateral,
  kLongitudinal,
  kLighting,
  kAnimation,
  kMovement,
  kAppearance,
  kAll
};
enum class CoordinateSystem : uint8_t { kEntity, kLane, kRoad, kTrajectory, kWorld };
enum class DirectionalDimension : uint8_t { kLongitudinal, kLateral, kVertical };
enum class DynamicsDimension : uint8_t { kDistance, kRate, kTime };
enum class DynamicsShape : uint8_t { kCubic, kLinear, kSinusoidal, kStep };
enum class FollowingMode : uint8_t { kFollow, kPosition };
enum class FractionalCloudCover : uint8_t {
  kZeroOktas,
  kOneOktas,
  kTwoOktas,
  kThreeOktas,
  kFourOktas,
  kFiveOktas,
  kSixOktas,
  kSevenOktas,
  kEightOktas,
  kNineOktas
};
enum class LateralDisplacement : uint8_t {
  kAny,
  kLeftToReferencedEntity,
  kRightToReferencedEntity
};
enum class LightMode : uint8_t { kOn, kOff, kFlashing };
enum class LongitudinalDisplacement : uint8_t {
  kAny,
  kTrailingReferencedEntity,
  kLeadingReferencedEntity
};
enum class MiscObjectCategory : uint8_t {
  kBarrier,
  kBuilding,
  kCrosswalk,
  kGantry,
  kNone,
  kObstacle,
  kParkingSpace,
  kPatch,
  kPole,
  kRailing,
  kRoadMark,
  kSoundBarrier,
  kStreetLamp,
  kTrafficIsland,
  kTree,
  kVegetation,
  kWind  ///< deprecated in 1.1, still a valid value
};
enum class ObjectType : uint8_t { kMiscellaneous, kPedestrian, kVehicle, kExternal };
/// "integer" (1.0) is read as kInt with a deprecation warning.
enum class ParameterType : uint8_t {
  kBoolean,
  kDateTime,
  kDouble,
  kString,
  kUnsignedInt,
  kUnsignedShort,
  kInt
};
enum class PedestrianCategory : uint8_t { kAnimal, kPedestrian, kWheelchair };
enum class PedestrianGestureType : uint8_t {
  kPhoneCallRightHand,
  kPhoneCallLeftHand,
  kPhoneTextRightHand,
  kPhoneTextLeftHand,
  kWavingRightArm,
  kWavingLeftArm,
  kUmbrellaRightHand,
  kUmbrellaLeftHand,
  kCrossArms,
  kCoffeeRightHand,
  kCoffeeLeftHand,
  kSandwichRightHand,
  kSandwichLeftHand
};
enum class PedestrianMotionType : uint8_t {
  kStanding,
  kSitting,
  kLying,
  kSquatting,
  kWalking,
  kRunning,
  kReeling,
  kCrawling,
  kCycling,
  kJumping,
  kDucking,
  kBendingDown
};
enum class PrecipitationType : uint8_t { kDry, kRain, kSnow };
/// "overwrite" (1.0/1.1) is read as kOverride with a deprecation warning.
enum class Priority : uint8_t { kOverride, kParallel, kSkip };
enum class ReferenceContext : uint8_t { kAbsolute, kRelative };
/// "cartesianDistance" (1.0) is read as kEuclidianDistance with a deprecation warning.
enum class RelativeDistanceType : uint8_t { kLateral, kLongitudinal, kEuclidianDistance };
enum class Role : uint8_t {
  kNone,
  kAmbulance,
  kCivil,
  kFire,
  kMilitary,
  kPolice,
  kPublicTransport,
  kRoadAssistance
};
enum class RouteStrategy : uint8_t { kFastest, kLeastIntersections, kRandom, kShortest };
enum class RoutingAlgorithm : uint8_t {
  kAssignedRoute,
  kFastest,
  kLeastIntersections,
  kShortest,
  kUndefined
};
enum class Rule : uint8_t {
  kEqualTo,
  kGreaterThan,
  kLessThan,
  kGreaterOrEqual,
  kLessOrEqual,
  kNotEqualTo
};
enum class SpeedTargetValueType : uint8_t { kDelta, kFactor };
enum class StoryboardElementState : uint8_t {
  kCompleteState,
  kEndTransition,
  kRunningState,
  kSkipTransition,
  kStandbyState,
  kStartTransition,
  kStopTransition
};
enum class StoryboardElementType : uint8_t {
  kAct,
  kAction,
  kEvent,
  kManeuver,
  kManeuverGroup,
  kStory
};
enum class TriggeringEntitiesRule : uint8_t { kAll, kAny };
enum class VehicleCategory : uint8_t {
  kBicycle,
  kBus,
  kCar,
  kMotorbike,
  kSemitrailer,
  kTrailer,
  kTrain,
  kTram,
  kTruck,
  kVan
};
enum class VehicleComponentType : uint8_t {
  kHood,
  kTrunk,
  kDoorFrontRight,
  kDoorFrontLeft,
  kDoorRearRight,
  kDoorRearLeft,
  kWindowFrontRight,
  kWindowFrontLeft,
  kWindowRearRight,
  kWindowRearLeft,
  kSideMirrors,
  kSideMirrorRight,
  kSideMirrorLeft
};
enum class VehicleLightType : uint8_t {
  kDaytimeRunningLights,
  kLowBeam,
  kHighBeam,
  kFogLights,
  kFogLightsFront,
  kFogLightsRear,
  kBrakeLights,
  kWarningLights,
  kIndicatorLeft,
  kIndicatorRight,
  kReversingLights,
  kLicensePlateIllumination,
  kSpecialPurposeLights
};
enum class Wetness : uint8_t { kDry, kMoist, kWetWithPuddles, kLowFlooded, kHighFlooded };

// The OpenSCENARIO spelling of each value (e.g. Rule::kGreaterOrEqual -> "greaterOrEqual").
// clang-format off
#define CORSA_XOSC_ENUMS(X) \
  X(AngleType) X(AutomaticGearType) X(CloudState) X(ColorType) \
  X(ConditionEdge) X(ControllerType) X(CoordinateSystem) X(DirectionalDimension) \
  X(DynamicsDimension) X(DynamicsShape) X(FollowingMode) X(FractionalCloudCover) \
  X(LateralDisplacement) X(LightMode) X(LongitudinalDisplacement) X(MiscObjectCategory) \
  X(ObjectType) X(ParameterType) X(PedestrianCategory) X(PedestrianGestureType) \
  X(PedestrianMotionType) X(PrecipitationType) X(Priority) X(ReferenceContext) \
  X(RelativeDistanceType) X(Role) X(RouteStrategy) X(RoutingAlgorithm) \
  X(Rule) X(SpeedTargetValueType) X(StoryboardElementState) X(StoryboardElementType) \
  X(TriggeringEntitiesRule) X(VehicleCategory) X(VehicleComponentType) X(VehicleLightType) \
  X(Wetness)
// clang-format on

#define CORSA_XOSC_DECLARE_TO_STRING(E) std::string_view to_string(E value);
CORSA_XOSC_ENUMS(CORSA_XOSC_DECLARE_TO_STRING)
#undef CORSA_XOSC_DECLARE_TO_STRING

}  // namespace corsa::xosc
