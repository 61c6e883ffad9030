#include "corsa/sensors/semantic.h"

namespace corsa::sensors {
namespace {

struct ClassInfo {
  std::string_view name;
  Rgb8 color;
};

// Colours follow the Cityscapes palette where a class exists there.
constexpr std::array<ClassInfo, kSemanticClassCount> kClasses = {{
    {"none", {0, 0, 0}},
    {"road", {128, 64, 128}},
    {"lane_marking", {157, 234, 50}},
    {"sidewalk", {244, 35, 232}},
    {"bike_lane", {119, 11, 200}},
    {"parking", {250, 170, 160}},
    {"roadside", {152, 251, 152}},
    {"rail_track", {230, 150, 140}},
    {"building", {70, 70, 70}},
    {"static_object", {190, 153, 153}},
    {"car", {0, 0, 142}},
    {"truck", {0, 0, 70}},
    {"bus", {0, 60, 100}},
    {"motorcycle", {0, 0, 230}},
    {"bicycle", {119, 11, 32}},
    {"train", {0, 80, 100}},
    {"pedestrian", {220, 20, 60}},
    {"animal", {255, 128, 0}},
    {"obstacle", {220, 220, 0}},
}};

}  // namespace

std::string_view semantic_name(SemanticClass c) {
  const auto i = static_cast<size_t>(c);
  return i < kClasses.size() ? kClasses[i].name : std::string_view("none");
}

Rgb8 semantic_color(SemanticClass c) {
  const auto i = static_cast<size_t>(c);
  return i < kClasses.size() ? kClasses[i].color : Rgb8{};
}

SemanticClass semantic_class_of_lane(xodr::LaneType type) {
  using xodr::LaneType;
  switch (type) {
    case LaneType::kSidewalk:
    case LaneType::kWalking:
      return SemanticClass::kSidewalk;
    case LaneType::kBiking:
      return SemanticClass::kBikeLane;
    case LaneType::kParking:
      return SemanticClass::kParking;
    case LaneType::kShoulder:
    case LaneType::kBorder:
    case LaneType::kCurb:
    case LaneType::kMedian:
      return SemanticClass::kRoadside;
    case LaneType::kRail:
      return SemanticClass::kRailTrack;
    default:
      return SemanticClass::kRoad;  // driving, ramps, bus, tram, restricted, none, ...
  }
}

SemanticClass semantic_class_of_entity(engine::EntityCategory category) {
  using engine::EntityCategory;
  switch (category) {
    case EntityCategory::kCar:
    case EntityCategory::kVan:
      return SemanticClass::kCar;
    case EntityCategory::kTruck:
    case EntityCategory::kTrailer:
    case EntityCategory::kSemitrailer:
      return SemanticClass::kTruck;
    case EntityCategory::kBus:
      return SemanticClass::kBus;
    case EntityCategory::kMotorbike:
      return SemanticClass::kMotorcycle;
    case EntityCategory::kBicycle:
      return SemanticClass::kBicycle;
    case EntityCategory::kTrain:
    case EntityCategory::kTram:
      return SemanticClass::kTrain;
    case EntityCategory::kPedestrian:
    case EntityCategory::kWheelchair:
      return SemanticClass::kPedestrian;
    case EntityCategory::kAnimal:
      return SemanticClass::kAnimal;
    case EntityCategory::kObstacle:
      return SemanticClass::kObstacle;
  }
  return SemanticClass::kObstacle;
}

bool is_dynamic_class(SemanticClass c) {
  return static_cast<int>(c) >= static_cast<int>(SemanticClass::kCar);
}

}  // namespace corsa::sensors
