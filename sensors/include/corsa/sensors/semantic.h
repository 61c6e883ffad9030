#pragma once

// Semantic classes carried by every primitive of the scene and written by the segmentation
// cameras and LiDAR labels. Ids 0-28 and their colours are CARLA's (0.9.14 and later,
// carla::rpc::CityObjectLabel), which follow the Cityscapes names and palette, so that models
// trained on CARLA or Cityscapes read Corsa's images without a mapping; ids from 29 on are
// Corsa's own. Every dataset carries the table as classes.json (write_class_table). The numeric
// values are part of the output format: only ever append.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "corsa/engine/world_snapshot.h"
#include "corsa/xodr/model.h"

namespace corsa::sensors {

enum class SemanticClass : uint8_t {
  kUnlabeled = 0,
  kRoad = 1,
  kSidewalk = 2,  ///< sidewalks, walkways and curbs
  kBuilding = 3,
  kWall = 4,  ///< free-standing walls, noise barriers
  kFence = 5,
  kPole = 6,  ///< sign and lamp posts, utility poles, traffic-light masts
  kTrafficLight = 7,
  kTrafficSign = 8,
  kVegetation = 9,  ///< trees, bushes, hedges
  kTerrain = 10,    ///< grass, soil, sand beside the road
  kSky = 11,        ///< what a camera ray hits when it hits nothing
  kPerson = 12,     ///< pedestrians and wheelchair users
  kRider = 13,      ///< the person on a bicycle or motorcycle
  kCar = 14,        ///< cars and vans
  kTruck = 15,      ///< trucks, trailers and semitrailers
  kBus = 16,
  kTrain = 17,  ///< trains and trams
  kMotorcycle = 18,
  kBicycle = 19,
  kStatic = 20,   ///< immovable props (benches, bollards, hydrants) and unclassified models
  kDynamic = 21,  ///< movable props: the scenario's MiscObjects
  kOther = 22,
  kWater = 23,
  kLaneMarking = 24,  ///< painted road marks, stop lines, crosswalks (CARLA's RoadLines)
  kGround = 25,       ///< other flat ground (gravel, dirt tracks)
  kBridge = 26,
  kRailTrack = 27,
  kGuardRail = 28,
  kParking = 29,   ///< parking lanes and spaces (Cityscapes' parking colour)
  kBikeLane = 30,  ///< cycle lanes (Mapillary's bike-lane colour)
  kAnimal = 31,
};

inline constexpr int kSemanticClassCount = 32;

struct Rgb8 {
  uint8_t r = 0;
  uint8_t g = 0;
  uint8_t b = 0;
};

/// Lower-case name used in label files ("road", "lane_marking", "car", ...).
std::string_view semantic_name(SemanticClass c);
/// Colour of the class in colour-coded segmentation images (CARLA / Cityscapes palette).
Rgb8 semantic_color(SemanticClass c);
/// KITTI object type of the class ("Car", "Truck", "Pedestrian", "Cyclist", "Tram", "Misc").
std::string_view kitti_type(SemanticClass c);
/// Class of a lane surface by its OpenDRIVE type: driving, shoulder and the other lanes cars
/// use -> road; sidewalk, walking and curb -> sidewalk; biking -> bike_lane; parking; rail ->
/// rail_track; border and median -> terrain.
SemanticClass semantic_class_of_lane(xodr::LaneType type);
/// Class of an entity by category (MiscObjects -> dynamic).
SemanticClass semantic_class_of_entity(engine::EntityCategory category);
/// True for the classes of movable objects that get 2D/3D box labels (person to bicycle,
/// dynamic, animal).
bool is_dynamic_class(SemanticClass c);

/// The class table as JSON: {"format": ..., "classes": [{"id", "name", "color": [r, g, b]}]},
/// the contents of a dataset's classes.json.
std::string class_table_json();

}  // namespace corsa::sensors
