#pragma once

// Semantic classes carried by every primitive of the scene and written by the segmentation
// cameras and LiDAR labels. The numeric values are part of the output format (class-id images,
// point labels): only ever append.

#include <array>
#include <cstdint>
#include <string_view>

#include "corsa/engine/world_snapshot.h"
#include "corsa/xodr/model.h"

namespace corsa::sensors {

enum class SemanticClass : uint8_t {
  kNone = 0,  ///< nothing hit (sky)
  kRoad = 1,
  kLaneMarking = 2,
  kSidewalk = 3,
  kBikeLane = 4,
  kParking = 5,
  kRoadside = 6,  ///< shoulder, border, curb, median
  kRailTrack = 7,
  kBuilding = 8,
  kStaticObject = 9,  ///< any other static model
  kCar = 10,
  kTruck = 11,
  kBus = 12,
  kMotorcycle = 13,
  kBicycle = 14,
  kTrain = 15,
  kPedestrian = 16,
  kAnimal = 17,
  kObstacle = 18,
};

inline constexpr int kSemanticClassCount = 19;

struct Rgb8 {
  uint8_t r = 0;
  uint8_t g = 0;
  uint8_t b = 0;
};

/// Lower-case name used in label files ("road", "lane_marking", "car", ...).
std::string_view semantic_name(SemanticClass c);
/// Colour of the class in colour-coded segmentation images (Cityscapes-like palette).
Rgb8 semantic_color(SemanticClass c);
/// Class of a road-mesh triangle: road marks are lane markings; lanes map by their type.
SemanticClass semantic_class_of_lane(xodr::LaneType type);
SemanticClass semantic_class_of_entity(engine::EntityCategory category);
/// True for the classes of movable objects that get 2D/3D box labels.
bool is_dynamic_class(SemanticClass c);

}  // namespace corsa::sensors
