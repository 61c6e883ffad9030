// Spellings of the OpenSCENARIO 1.3 enumerations, with the deprecated 1.0/1.1 spellings the
// loader still accepts (each mapped to its successor, with a deprecation warning).

#include "enum_tables.h"

namespace corsa::xosc {

template <>
std::span<const EnumEntry<AngleType>> enum_entries<AngleType>() {
  using E = AngleType;
  static constexpr EnumEntry<E> kEntries[] = {
      {"heading", E::kHeading, false, {}},
      {"pitch", E::kPitch, false, {}},
      {"roll", E::kRoll, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<AutomaticGearType>> enum_entries<AutomaticGearType>() {
  using E = AutomaticGearType;
  static constexpr EnumEntry<E> kEntries[] = {
      {"n", E::kN, false, {}},
      {"p", E::kP, false, {}},
      {"r", E::kR, false, {}},
      {"d", E::kD, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<CloudState>> enum_entries<CloudState>() {
  using E = CloudState;
  static constexpr EnumEntry<E> kEntries[] = {
      {"cloudy", E::kCloudy, false, {}},     {"free", E::kFree, false, {}},
      {"overcast", E::kOvercast, false, {}}, {"rainy", E::kRainy, false, {}},
      {"skyOff", E::kSkyOff, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<ColorType>> enum_entries<ColorType>() {
  using E = ColorType;
  static constexpr EnumEntry<E> kEntries[] = {
      {"other", E::kOther, false, {}},   {"red", E::kRed, false, {}},
      {"yellow", E::kYellow, false, {}}, {"green", E::kGreen, false, {}},
      {"blue", E::kBlue, false, {}},     {"violet", E::kViolet, false, {}},
      {"orange", E::kOrange, false, {}}, {"brown", E::kBrown, false, {}},
      {"black", E::kBlack, false, {}},   {"grey", E::kGrey, false, {}},
      {"white", E::kWhite, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<ConditionEdge>> enum_entries<ConditionEdge>() {
  using E = ConditionEdge;
  static constexpr EnumEntry<E> kEntries[] = {
      {"falling", E::kFalling, false, {}},
      {"none", E::kNone, false, {}},
      {"rising", E::kRising, false, {}},
      {"risingOrFalling", E::kRisingOrFalling, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<ControllerType>> enum_entries<ControllerType>() {
  using E = ControllerType;
  static constexpr EnumEntry<E> kEntries[] = {
      {"lateral", E::kLateral, false, {}},   {"longitudinal", E::kLongitudinal, false, {}},
      {"lighting", E::kLighting, false, {}}, {"animation", E::kAnimation, false, {}},
      {"movement", E::kMovement, false, {}}, {"appearance", E::kAppearance, false, {}},
      {"all", E::kAll, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<CoordinateSystem>> enum_entries<CoordinateSystem>() {
  using E = CoordinateSystem;
  static constexpr EnumEntry<E> kEntries[] = {
      {"entity", E::kEntity, false, {}}, {"lane", E::kLane, false, {}},
      {"road", E::kRoad, false, {}},     {"trajectory", E::kTrajectory, false, {}},
      {"world", E::kWorld, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<DirectionalDimension>> enum_entries<DirectionalDimension>() {
  using E = DirectionalDimension;
  static constexpr EnumEntry<E> kEntries[] = {
      {"longitudinal", E::kLongitudinal, false, {}},
      {"lateral", E::kLateral, false, {}},
      {"vertical", E::kVertical, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<DynamicsDimension>> enum_entries<DynamicsDimension>() {
  using E = DynamicsDimension;
  static constexpr EnumEntry<E> kEntries[] = {
      {"distance", E::kDistance, false, {}},
      {"rate", E::kRate, false, {}},
      {"time", E::kTime, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<DynamicsShape>> enum_entries<DynamicsShape>() {
  using E = DynamicsShape;
  static constexpr EnumEntry<E> kEntries[] = {
      {"cubic", E::kCubic, false, {}},
      {"linear", E::kLinear, false, {}},
      {"sinusoidal", E::kSinusoidal, false, {}},
      {"step", E::kStep, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<FollowingMode>> enum_entries<FollowingMode>() {
  using E = FollowingMode;
  static constexpr EnumEntry<E> kEntries[] = {
      {"follow", E::kFollow, false, {}},
      {"position", E::kPosition, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<FractionalCloudCover>> enum_entries<FractionalCloudCover>() {
  using E = FractionalCloudCover;
  static constexpr EnumEntry<E> kEntries[] = {
      {"zeroOktas", E::kZeroOktas, false, {}},   {"oneOktas", E::kOneOktas, false, {}},
      {"twoOktas", E::kTwoOktas, false, {}},     {"threeOktas", E::kThreeOktas, false, {}},
      {"fourOktas", E::kFourOktas, false, {}},   {"fiveOktas", E::kFiveOktas, false, {}},
      {"sixOktas", E::kSixOktas, false, {}},     {"sevenOktas", E::kSevenOktas, false, {}},
      {"eightOktas", E::kEightOktas, false, {}}, {"nineOktas", E::kNineOktas, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<LateralDisplacement>> enum_entries<LateralDisplacement>() {
  using E = LateralDisplacement;
  static constexpr EnumEntry<E> kEntries[] = {
      {"any", E::kAny, false, {}},
      {"leftToReferencedEntity", E::kLeftToReferencedEntity, false, {}},
      {"rightToReferencedEntity", E::kRightToReferencedEntity, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<LightMode>> enum_entries<LightMode>() {
  using E = LightMode;
  static constexpr EnumEntry<E> kEntries[] = {
      {"on", E::kOn, false, {}},
      {"off", E::kOff, false, {}},
      {"flashing", E::kFlashing, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<LongitudinalDisplacement>> enum_entries<LongitudinalDisplacement>() {
  using E = LongitudinalDisplacement;
  static constexpr EnumEntry<E> kEntries[] = {
      {"any", E::kAny, false, {}},
      {"trailingReferencedEntity", E::kTrailingReferencedEntity, false, {}},
      {"leadingReferencedEntity", E::kLeadingReferencedEntity, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<MiscObjectCategory>> enum_entries<MiscObjectCategory>() {
  using E = MiscObjectCategory;
  static constexpr EnumEntry<E> kEntries[] = {
      {"barrier", E::kBarrier, false, {}},
      {"building", E::kBuilding, false, {}},
      {"crosswalk", E::kCrosswalk, false, {}},
      {"gantry", E::kGantry, false, {}},
      {"none", E::kNone, false, {}},
      {"obstacle", E::kObstacle, false, {}},
      {"parkingSpace", E::kParkingSpace, false, {}},
      {"patch", E::kPatch, false, {}},
      {"pole", E::kPole, false, {}},
      {"railing", E::kRailing, false, {}},
      {"roadMark", E::kRoadMark, false, {}},
      {"soundBarrier", E::kSoundBarrier, false, {}},
      {"streetLamp", E::kStreetLamp, false, {}},
      {"trafficIsland", E::kTrafficIsland, false, {}},
      {"tree", E::kTree, false, {}},
      {"vegetation", E::kVegetation, false, {}},
      {"wind", E::kWind, true, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<ObjectType>> enum_entries<ObjectType>() {
  using E = ObjectType;
  static constexpr EnumEntry<E> kEntries[] = {
      {"miscellaneous", E::kMiscellaneous, false, {}},
      {"pedestrian", E::kPedestrian, false, {}},
      {"vehicle", E::kVehicle, false, {}},
      {"external", E::kExternal, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<ParameterType>> enum_entries<ParameterType>() {
  using E = ParameterType;
  static constexpr EnumEntry<E> kEntries[] = {
      {"boolean", E::kBoolean, false, {}},
      {"dateTime", E::kDateTime, false, {}},
      {"double", E::kDouble, false, {}},
      {"string", E::kString, false, {}},
      {"unsignedInt", E::kUnsignedInt, false, {}},
      {"unsignedShort", E::kUnsignedShort, false, {}},
      {"int", E::kInt, false, {}},
      {"integer", E::kInt, true, "int"},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<PedestrianCategory>> enum_entries<PedestrianCategory>() {
  using E = PedestrianCategory;
  static constexpr EnumEntry<E> kEntries[] = {
      {"animal", E::kAnimal, false, {}},
      {"pedestrian", E::kPedestrian, false, {}},
      {"wheelchair", E::kWheelchair, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<PedestrianGestureType>> enum_entries<PedestrianGestureType>() {
  using E = PedestrianGestureType;
  static constexpr EnumEntry<E> kEntries[] = {
      {"phoneCallRightHand", E::kPhoneCallRightHand, false, {}},
      {"phoneCallLeftHand", E::kPhoneCallLeftHand, false, {}},
      {"phoneTextRightHand", E::kPhoneTextRightHand, false, {}},
      {"phoneTextLeftHand", E::kPhoneTextLeftHand, false, {}},
      {"wavingRightArm", E::kWavingRightArm, false, {}},
      {"wavingLeftArm", E::kWavingLeftArm, false, {}},
      {"umbrellaRightHand", E::kUmbrellaRightHand, false, {}},
      {"umbrellaLeftHand", E::kUmbrellaLeftHand, false, {}},
      {"crossArms", E::kCrossArms, false, {}},
      {"coffeeRightHand", E::kCoffeeRightHand, false, {}},
      {"coffeeLeftHand", E::kCoffeeLeftHand, false, {}},
      {"sandwichRightHand", E::kSandwichRightHand, false, {}},
      {"sandwichLeftHand", E::kSandwichLeftHand, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<PedestrianMotionType>> enum_entries<PedestrianMotionType>() {
  using E = PedestrianMotionType;
  static constexpr EnumEntry<E> kEntries[] = {
      {"standing", E::kStanding, false, {}}, {"sitting", E::kSitting, false, {}},
      {"lying", E::kLying, false, {}},       {"squatting", E::kSquatting, false, {}},
      {"walking", E::kWalking, false, {}},   {"running", E::kRunning, false, {}},
      {"reeling", E::kReeling, false, {}},   {"crawling", E::kCrawling, false, {}},
      {"cycling", E::kCycling, false, {}},   {"jumping", E::kJumping, false, {}},
      {"ducking", E::kDucking, false, {}},   {"bendingDown", E::kBendingDown, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<PrecipitationType>> enum_entries<PrecipitationType>() {
  using E = PrecipitationType;
  static constexpr EnumEntry<E> kEntries[] = {
      {"dry", E::kDry, false, {}},
      {"rain", E::kRain, false, {}},
      {"snow", E::kSnow, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<Priority>> enum_entries<Priority>() {
  using E = Priority;
  static constexpr EnumEntry<E> kEntries[] = {
      {"override", E::kOverride, false, {}},
      {"parallel", E::kParallel, false, {}},
      {"skip", E::kSkip, false, {}},
      {"overwrite", E::kOverride, true, "override"},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<ReferenceContext>> enum_entries<ReferenceContext>() {
  using E = ReferenceContext;
  static constexpr EnumEntry<E> kEntries[] = {
      {"absolute", E::kAbsolute, false, {}},
      {"relative", E::kRelative, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<RelativeDistanceType>> enum_entries<RelativeDistanceType>() {
  using E = RelativeDistanceType;
  static constexpr EnumEntry<E> kEntries[] = {
      {"lateral", E::kLateral, false, {}},
      {"longitudinal", E::kLongitudinal, false, {}},
      {"euclidianDistance", E::kEuclidianDistance, false, {}},
      {"cartesianDistance", E::kEuclidianDistance, true, "euclidianDistance"},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<Role>> enum_entries<Role>() {
  using E = Role;
  static constexpr EnumEntry<E> kEntries[] = {
      {"none", E::kNone, false, {}},
      {"ambulance", E::kAmbulance, false, {}},
      {"civil", E::kCivil, false, {}},
      {"fire", E::kFire, false, {}},
      {"military", E::kMilitary, false, {}},
      {"police", E::kPolice, false, {}},
      {"publicTransport", E::kPublicTransport, false, {}},
      {"roadAssistance", E::kRoadAssistance, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<RouteStrategy>> enum_entries<RouteStrategy>() {
  using E = RouteStrategy;
  static constexpr EnumEntry<E> kEntries[] = {
      {"fastest", E::kFastest, false, {}},
      {"leastIntersections", E::kLeastIntersections, false, {}},
      {"random", E::kRandom, false, {}},
      {"shortest", E::kShortest, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<RoutingAlgorithm>> enum_entries<RoutingAlgorithm>() {
  using E = RoutingAlgorithm;
  static constexpr EnumEntry<E> kEntries[] = {
      {"assignedRoute", E::kAssignedRoute, false, {}},
      {"fastest", E::kFastest, false, {}},
      {"leastIntersections", E::kLeastIntersections, false, {}},
      {"shortest", E::kShortest, false, {}},
      {"undefined", E::kUndefined, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<Rule>> enum_entries<Rule>() {
  using E = Rule;
  static constexpr EnumEntry<E> kEntries[] = {
      {"equalTo", E::kEqualTo, false, {}},
      {"greaterThan", E::kGreaterThan, false, {}},
      {"lessThan", E::kLessThan, false, {}},
      {"greaterOrEqual", E::kGreaterOrEqual, false, {}},
      {"lessOrEqual", E::kLessOrEqual, false, {}},
      {"notEqualTo", E::kNotEqualTo, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<SpeedTargetValueType>> enum_entries<SpeedTargetValueType>() {
  using E = SpeedTargetValueType;
  static constexpr EnumEntry<E> kEntries[] = {
      {"delta", E::kDelta, false, {}},
      {"factor", E::kFactor, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<StoryboardElementState>> enum_entries<StoryboardElementState>() {
  using E = StoryboardElementState;
  static constexpr EnumEntry<E> kEntries[] = {
      {"completeState", E::kCompleteState, false, {}},
      {"endTransition", E::kEndTransition, false, {}},
      {"runningState", E::kRunningState, false, {}},
      {"skipTransition", E::kSkipTransition, false, {}},
      {"standbyState", E::kStandbyState, false, {}},
      {"startTransition", E::kStartTransition, false, {}},
      {"stopTransition", E::kStopTransition, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<StoryboardElementType>> enum_entries<StoryboardElementType>() {
  using E = StoryboardElementType;
  static constexpr EnumEntry<E> kEntries[] = {
      {"act", E::kAct, false, {}},
      {"action", E::kAction, false, {}},
      {"event", E::kEvent, false, {}},
      {"maneuver", E::kManeuver, false, {}},
      {"maneuverGroup", E::kManeuverGroup, false, {}},
      {"story", E::kStory, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<TriggeringEntitiesRule>> enum_entries<TriggeringEntitiesRule>() {
  using E = TriggeringEntitiesRule;
  static constexpr EnumEntry<E> kEntries[] = {
      {"all", E::kAll, false, {}},
      {"any", E::kAny, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<VehicleCategory>> enum_entries<VehicleCategory>() {
  using E = VehicleCategory;
  static constexpr EnumEntry<E> kEntries[] = {
      {"bicycle", E::kBicycle, false, {}},
      {"bus", E::kBus, false, {}},
      {"car", E::kCar, false, {}},
      {"motorbike", E::kMotorbike, false, {}},
      {"semitrailer", E::kSemitrailer, false, {}},
      {"trailer", E::kTrailer, false, {}},
      {"train", E::kTrain, false, {}},
      {"tram", E::kTram, false, {}},
      {"truck", E::kTruck, false, {}},
      {"van", E::kVan, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<VehicleComponentType>> enum_entries<VehicleComponentType>() {
  using E = VehicleComponentType;
  static constexpr EnumEntry<E> kEntries[] = {
      {"hood", E::kHood, false, {}},
      {"trunk", E::kTrunk, false, {}},
      {"doorFrontRight", E::kDoorFrontRight, false, {}},
      {"doorFrontLeft", E::kDoorFrontLeft, false, {}},
      {"doorRearRight", E::kDoorRearRight, false, {}},
      {"doorRearLeft", E::kDoorRearLeft, false, {}},
      {"windowFrontRight", E::kWindowFrontRight, false, {}},
      {"windowFrontLeft", E::kWindowFrontLeft, false, {}},
      {"windowRearRight", E::kWindowRearRight, false, {}},
      {"windowRearLeft", E::kWindowRearLeft, false, {}},
      {"sideMirrors", E::kSideMirrors, false, {}},
      {"sideMirrorRight", E::kSideMirrorRight, false, {}},
      {"sideMirrorLeft", E::kSideMirrorLeft, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<VehicleLightType>> enum_entries<VehicleLightType>() {
  using E = VehicleLightType;
  static constexpr EnumEntry<E> kEntries[] = {
      {"daytimeRunningLights", E::kDaytimeRunningLights, false, {}},
      {"lowBeam", E::kLowBeam, false, {}},
      {"highBeam", E::kHighBeam, false, {}},
      {"fogLights", E::kFogLights, false, {}},
      {"fogLightsFront", E::kFogLightsFront, false, {}},
      {"fogLightsRear", E::kFogLightsRear, false, {}},
      {"brakeLights", E::kBrakeLights, false, {}},
      {"warningLights", E::kWarningLights, false, {}},
      {"indicatorLeft", E::kIndicatorLeft, false, {}},
      {"indicatorRight", E::kIndicatorRight, false, {}},
      {"reversingLights", E::kReversingLights, false, {}},
      {"licensePlateIllumination", E::kLicensePlateIllumination, false, {}},
      {"specialPurposeLights", E::kSpecialPurposeLights, false, {}},
  };
  return kEntries;
}

template <>
std::span<const EnumEntry<Wetness>> enum_entries<Wetness>() {
  using E = Wetness;
  static constexpr EnumEntry<E> kEntries[] = {
      {"dry", E::kDry, false, {}},
      {"moist", E::kMoist, false, {}},
      {"wetWithPuddles", E::kWetWithPuddles, false, {}},
      {"lowFlooded", E::kLowFlooded, false, {}},
      {"highFlooded", E::kHighFlooded, false, {}},
  };
  return kEntries;
}

#define CORSA_XOSC_DEFINE_TO_STRING(E)                         \
  std::string_view to_string(E value) {                        \
    for (const auto& entry : enum_entries<E>()) {              \
      if (entry.value == value && entry.replacement.empty()) { \
        return entry.name;                                     \
      }                                                        \
    }                                                          \
    return "?";                                                \
  }                                                            \
  template <>                                                  \
  std::string_view enum_type_name<E>() {                       \
    return #E;                                                 \
  }
CORSA_XOSC_ENUMS(CORSA_XOSC_DEFINE_TO_STRING)
#undef CORSA_XOSC_DEFINE_TO_STRING

}  // namespace corsa::xosc
