#pragma once

// Generators of entity shapes (private): vehicles per OpenSCENARIO category and bounding box,
// people with a skeleton. Every shape is in the entity's frame (x forward, y left, z up, metres,
// the reference point at the origin) and fills the entity's bounding box.

#include <functional>
#include <vector>

#include "corsa/core/random.h"
#include "corsa/engine/world_snapshot.h"
#include "mesh_builder.h"
#include "vehicle_parts.h"

namespace corsa::sensors::detail {

enum class CarStyle { kSedan, kHatchback, kSuv, kVan, kPickup };

struct GeneratedVehicle {
  ArticulatedMesh mesh;
  std::vector<WheelSpec> wheels;
  double wheelbase = 0.0;
  size_t bones = 1;
  /// Extra posing on top of the wheels (riders pedalling); may be empty.
  std::function<void(const engine::EntitySnapshot&, std::vector<Rigid>&)> extra_pose;
};

/// The body style of a car-category entity from its box (vans tall and long, SUVs tall, small
/// hatchbacks short) and the seed.
CarStyle car_style_for(engine::EntityCategory category, const engine::Box& box, RandomStream& rng);
GeneratedVehicle generate_car(CarStyle style, const engine::Box& box, RandomStream& rng);
/// Trucks: rigid (cab and cargo box) up to 11 m, tractor and semitrailer beyond; trailers and
/// semitrailers alone (no cab).
GeneratedVehicle generate_truck(engine::EntityCategory category, const engine::Box& box,
                                RandomStream& rng);
/// Buses, trams and trains: long bodies with window bands and doors.
GeneratedVehicle generate_bus(engine::EntityCategory category, const engine::Box& box,
                              RandomStream& rng);
/// Bicycles and motorbikes with their riders (class rider).
GeneratedVehicle generate_two_wheeler(engine::EntityCategory category, const engine::Box& box,
                                      RandomStream& rng);

/// A person's look, drawn from the seed: build and clothing.
struct PersonLook {
  double stature = 1.75;   ///< m
  double build = 1.0;      ///< girth factor, 0.85 slim .. 1.25 heavy
  double shoulders = 1.0;  ///< shoulder width factor
  Material skin, hair, top, bottom, shoes;
  bool long_sleeves = true;
  bool skirt = false;
  bool long_hair = false;
};
PersonLook draw_person_look(double stature, RandomStream& rng);

/// Body posture: walking (phase in cycles), standing, riding a bicycle (pedal crank angle) or
/// sitting on a motorbike.
enum class Posture { kStand, kWalk, kCycle, kRideMotorbike, kSit };

/// The skeleton's bones (0 is the entity body, never moving).
enum Bone : uint8_t {
  kBoneRoot = 0,
  kBonePelvis,
  kBoneTorso,
  kBoneHead,
  kBoneUpperArmL,
  kBoneForearmL,
  kBoneUpperArmR,
  kBoneForearmR,
  kBoneThighL,
  kBoneShinL,
  kBoneFootL,
  kBoneThighR,
  kBoneShinR,
  kBoneFootR,
  kBoneCount,
};

/// Where the person stands: the point between the feet on the ground (or the hip and grips for
/// riders), the facing (+x) and the first bone number to use.
struct PersonPlacement {
  Vec3 ground;                ///< entity frame: walkers' feet; riders: the hip joint
  Vec3 hands{0.0, 0.0, 0.0};  ///< riders: handlebar grips' centre (entity frame)
  double hand_spread = 0.5;   ///< riders: distance between the grips
  Vec3 pedal_axis;            ///< cyclists: the crank axle (entity frame)
  double crank = 0.17;        ///< cyclists: crank length
  Vec3 feet;                  ///< motorcyclists: foot pegs' centre
  uint8_t first_bone = 1;
  SemanticClass semantic = SemanticClass::kPerson;
  bool by_hip = false;  ///< `ground` is the hip joint (riders), not the feet
};

/// Adds a person in its rest pose, each part on its bone (first_bone + Bone - 1).
void add_person(MeshBuilder& b, const PersonLook& look, const PersonPlacement& where);

/// The bone transforms of a person for a posture; `phase` is the gait phase in cycles
/// (walking) or the crank angle in radians (cycling); `amplitude` scales the walk (0..1.3).
void pose_person(const PersonLook& look, const PersonPlacement& where, Posture posture,
                 double phase, double amplitude, std::vector<Rigid>& bones);

}  // namespace corsa::sensors::detail
