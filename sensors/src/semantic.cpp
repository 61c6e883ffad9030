#include "corsa/sensors/semantic.h"

#include "corsa/core/json.h"

namespace corsa::sensors {
namespace {

// What the label files say of a class: its name, its colour and its KITTI object type.
struct ClassInfo {
  std::string_view name;
  Rgb8 color;
  std::string_view kitti = "Misc";
};

// CARLA 0.9.14 CityObjectLabel order and colours (Cityscapes palette), then Corsa's own; KITTI
// types as its object benchmark names them (trucks and buses "Truck", riders and two-wheelers
// "Cyclist", trains "Tram", everything else "Misc").
constexpr std::array<ClassInfo, kSemanticClassCount> kClasses = {{
    {"unlabeled", {0, 0, 0}},
    {"road", {128, 64, 128}},
    {"sidewalk", {244, 35, 232}},
    {"building", {70, 70, 70}},
    {"wall", {102, 102, 156}},
    {"fence", {190, 153, 153}},
    {"pole", {153, 153, 153}},
    {"traffic_light", {250, 170, 30}},
    {"traffic_sign", {220, 220, 0}},
    {"vegetation", {107, 142, 35}},
    {"terrain", {152, 251, 152}},
    {"sky", {70, 130, 180}},
    {"person", {220, 20, 60}, "Pedestrian"},
    {"rider", {255, 0, 0}, "Cyclist"},
    {"car", {0, 0, 142}, "Car"},
    {"truck", {0, 0, 70}, "Truck"},
    {"bus", {0, 60, 100}, "Truck"},
    {"train", {0, 80, 100}, "Tram"},
    {"motorcycle", {0, 0, 230}, "Cyclist"},
    {"bicycle", {119, 11, 32}, "Cyclist"},
    {"static", {110, 190, 160}},
    {"dynamic", {170, 120, 50}},
    {"other", {55, 90, 80}},
    {"water", {45, 60, 150}},
    {"lane_marking", {157, 234, 50}},
    {"ground", {81, 0, 81}},
    {"bridge", {150, 100, 100}},
    {"rail_track", {230, 150, 140}},
    {"guard_rail", {180, 165, 180}},
    {"parking", {250, 170, 160}},
    {"bike_lane", {128, 64, 255}},
    {"animal", {255, 128, 0}},
}};

}  // namespace

std::string_view semantic_name(SemanticClass c) {
  const auto i = static_cast<size_t>(c);
  return i < kClasses.size() ? kClasses[i].name : std::string_view("unlabeled");
}

Rgb8 semantic_color(SemanticClass c) {
  const auto i = static_cast<size_t>(c);
  return i < kClasses.size() ? kClasses[i].color : Rgb8{};
}

std::string_view kitti_type(SemanticClass c) {
  const auto i = static_cast<size_t>(c);
  return i < kClasses.size() ? kClasses[i].kitti : std::string_view("Misc");
}

SemanticClass semantic_class_of_lane(xodr::LaneType type) {
  using xodr::LaneType;
  switch (type) {
    case LaneType::kSidewalk:
    case LaneType::kWalking:
    case LaneType::kCurb:
      return SemanticClass::kSidewalk;
    case LaneType::kBiking:
      return SemanticClass::kBikeLane;
    case LaneType::kParking:
      return SemanticClass::kParking;
    case LaneType::kBorder:
    case LaneType::kMedian:
      return SemanticClass::kTerrain;
    case LaneType::kRail:
      return SemanticClass::kRailTrack;
    default:
      return SemanticClass::kRoad;  // driving, shoulder, ramps, bus, tram, restricted, none, ...
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
      return SemanticClass::kPerson;
    case EntityCategory::kAnimal:
      return SemanticClass::kAnimal;
    case EntityCategory::kObstacle:
      return SemanticClass::kDynamic;
  }
  return SemanticClass::kDynamic;
}

bool is_dynamic_class(SemanticClass c) {
  const auto i = static_cast<int>(c);
  return (i >= static_cast<int>(SemanticClass::kPerson) &&
          i <= static_cast<int>(SemanticClass::kBicycle)) ||
         c == SemanticClass::kDynamic || c == SemanticClass::kAnimal;
}

std::string class_table_json() {
  Json classes = Json::array();
  for (size_t i = 0; i < kClasses.size(); ++i) {
    const Rgb8 c = kClasses[i].color;
    classes.push_back(
        {{"id", i}, {"name", std::string(kClasses[i].name)}, {"color", {c.r, c.g, c.b}}});
  }
  Json table;
  table["format"] = "corsa semantic classes 1";
  table["ids_follow"] = "CARLA 0.9.14 CityObjectLabel (0-28), Corsa (29-31)";
  table["sky_id"] = static_cast<int>(SemanticClass::kSky);
  table["classes"] = std::move(classes);
  return json_document(table);
}

}  // namespace corsa::sensors
