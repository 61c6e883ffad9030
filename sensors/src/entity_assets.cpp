// The shape of an entity the first time the scene sees it: generated from its category, its
// bounding box, its name and the run seed (same seed, same look), with the bones that move it.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "corsa/core/random.h"
#include "corsa/sensors/semantic.h"
#include "corsa/sensors/vehicle_size.h"
#include "scalar_math.h"
#include "scene_data.h"
#include "vehicle_generators.h"

namespace corsa::sensors::detail {
namespace {

using PoseFn = std::function<void(const engine::EntitySnapshot&, std::vector<Rigid>&)>;

PoseFn vehicle_pose(const GeneratedVehicle& v) {
  PoseFn wheels = wheel_pose(v.wheels, v.wheelbase, v.bones);
  if (!v.extra_pose) {
    return wheels;
  }
  return [wheels, extra = v.extra_pose](const engine::EntitySnapshot& e, std::vector<Rigid>& out) {
    wheels(e, out);
    extra(e, out);
  };
}

void person(const engine::EntitySnapshot& e, RandomStream& rng, EntityShape& shape) {
  const engine::Box& box = e.box;
  const PersonLook look = draw_person_look(box.height, rng);
  PersonPlacement where;
  where.ground = {box.center_x, box.center_y, box.center_z - 0.5 * box.height};
  MeshBuilder b;
  add_person(b, look, where);
  shape.mesh = b.take();
  // One gait cycle (two steps) is about 0.83 statures at a normal pace; the walk's amplitude
  // follows the speed.
  const double stride = 0.83 * look.stature;
  shape.pose = [look, where, stride](const engine::EntitySnapshot& s, std::vector<Rigid>& out) {
    out.assign(kBoneCount, Rigid{});
    const double v = std::fabs(s.speed);
    if (v < 0.15) {
      pose_person(look, where, Posture::kStand, 0.0, 0.0, out);
      return;
    }
    const double phase = std::fmod(s.odometer / stride, 1.0);
    pose_person(look, where, Posture::kWalk, phase, std::clamp(v / 1.4, 0.35, 1.25), out);
  };
}

void wheelchair(const engine::EntitySnapshot& e, RandomStream& rng, EntityShape& shape) {
  const engine::Box& box = e.box;
  const double zb = box.center_z - 0.5 * box.height;
  const PersonLook look = draw_person_look(1.7 * std::clamp(box.height / 1.3, 0.8, 1.2), rng);
  MeshBuilder b;
  b.semantic(SemanticClass::kPerson);
  std::vector<WheelSpec> wheels;
  const double r = 0.3;
  for (int side : {-1, 1}) {
    WheelSpec w{{box.center_x - 0.15, box.center_y + side * (0.5 * box.width - 0.04), zb + r},
                r,
                0.04,
                false,
                static_cast<uint8_t>(side < 0 ? 1 : 2),
                false};
    add_wheel(b, w, side, 6);
    wheels.push_back(w);
  }
  b.material(materials::metal("wheelchair frame", linear_rgb(60, 62, 66), 0.4));
  b.box({box.center_x - 0.3, box.center_y - 0.25, zb + 0.45},
        {box.center_x + 0.15, box.center_y + 0.25, zb + 0.5});
  b.box({box.center_x - 0.32, box.center_y - 0.25, zb + 0.5},
        {box.center_x - 0.28, box.center_y + 0.25, zb + 0.95});
  PersonPlacement where;
  where.ground = {box.center_x - 0.12, box.center_y, zb + 0.55};
  where.by_hip = true;
  where.first_bone = 3;
  where.feet = {box.center_x + 0.35, box.center_y, zb + 0.1};
  where.hands = {box.center_x - 0.05, box.center_y, zb + 0.62};
  where.hand_spread = 0.5;
  add_person(b, look, where);
  shape.mesh = b.take();
  GeneratedVehicle v;
  v.wheels = wheels;
  v.bones = 3 + kBoneCount - 1;
  PoseFn roll = wheel_pose(wheels, 0.0, v.bones);
  shape.pose = [roll, look, where](const engine::EntitySnapshot& s, std::vector<Rigid>& out) {
    roll(s, out);
    pose_person(look, where, Posture::kSit, 0.0, 0.0, out);
  };
}

/// A four-legged animal: body, neck and head, legs on bones that swing with the distance walked.
void animal(const engine::EntitySnapshot& e, RandomStream& rng, EntityShape& shape) {
  const engine::Box& box = e.box;
  const double zb = box.center_z - 0.5 * box.height;
  const double l = box.length;
  const double h = box.height;
  Material fur = materials::plain(
      "fur", rng.uniform01() < 0.5 ? linear_rgb(120, 90, 60) : linear_rgb(70, 60, 50), 0.9);
  fur.name += " " + std::to_string(rng.next_u64() % 1000);
  MeshBuilder b;
  b.semantic(SemanticClass::kAnimal).material(fur);
  const double leg = 0.55 * h;
  const Vec3 body{box.center_x - 0.05 * l, box.center_y, zb + leg + 0.15 * h};
  b.ellipsoid(body, {0.38 * l, 0.4 * box.width, 0.2 * h}, Mat3{}, 14, 8);
  const Vec3 neck{box.center_x + 0.3 * l, box.center_y, zb + 0.75 * h};
  b.tube(body + Vec3{0.25 * l, 0.0, 0.05 * h}, neck, 0.09 * h, 0.07 * h, 8, false);
  b.ellipsoid(neck + Vec3{0.1 * l, 0.0, 0.06 * h}, {0.13 * l, 0.25 * box.width, 0.1 * h}, Mat3{},
              10, 6);
  std::vector<Vec3> hips;
  uint8_t bone = 1;
  for (double fx : {0.25, -0.3}) {
    for (int side : {-1, 1}) {
      const Vec3 top{box.center_x + fx * l, box.center_y + side * 0.25 * box.width, zb + leg};
      b.bone(bone++);
      b.tube(top, top - Vec3{0.0, 0.0, leg}, 0.06 * h, 0.035 * h, 6, true);
      hips.push_back(top);
    }
  }
  b.bone(0);
  shape.mesh = b.take();
  shape.pose = [hips, l](const engine::EntitySnapshot& s, std::vector<Rigid>& out) {
    out.assign(5, Rigid{});
    const double phase = 2.0 * kPi * std::fmod(s.odometer / (1.2 * l), 1.0);
    const double a = std::fabs(s.speed) > 0.1 ? 0.45 : 0.0;
    for (size_t i = 0; i < hips.size(); ++i) {
      // Diagonal pairs move together (a trot).
      const double angle = a * std::sin(phase + ((i == 0 || i == 3) ? 0.0 : kPi));
      const Rigid swing = rigid_from_pose(0, 0, 0, 0, angle, 0);
      out[i + 1].rotation = swing.rotation;
      out[i + 1].translation = hips[i] - swing.rotation * hips[i];
    }
  };
}

/// A plain box of `box` in `semantic`, coloured `material`: no bones.
void plain_box_shape(const engine::Box& box, SemanticClass semantic, const Material& material,
                     EntityShape& shape) {
  MeshBuilder b;
  b.semantic(semantic).material(material);
  b.box({box.center_x - 0.5 * box.length, box.center_y - 0.5 * box.width,
         box.center_z - 0.5 * box.height},
        {box.center_x + 0.5 * box.length, box.center_y + 0.5 * box.width,
         box.center_z + 0.5 * box.height});
  shape.mesh = b.take();
  shape.pose = nullptr;
}

void obstacle(const engine::EntitySnapshot& e, EntityShape& shape) {
  plain_box_shape(e.box, SemanticClass::kDynamic,
                  materials::plain("obstacle", linear_rgb(200, 120, 40), 0.7), shape);
}

}  // namespace

void build_entity_shape(const engine::EntitySnapshot& e, uint64_t seed, EntityShape& shape) {
  using engine::EntityCategory;
  RandomStream rng(derive_seed(seed, "look of " + e.name));
  if (vehicle_too_large_for_details(e.category, e.box)) {
    // Bounded cost whatever the size (vehicle_size.h): a box in the vehicle's class and paint.
    plain_box_shape(e.box, semantic_class_of_entity(e.category), draw_car_paint(rng), shape);
    return;
  }
  GeneratedVehicle v;
  switch (e.category) {
    case EntityCategory::kCar:
    case EntityCategory::kVan:
      v = generate_car(car_style_for(e.category, e.box, rng), e.box, rng);
      break;
    case EntityCategory::kTruck:
    case EntityCategory::kTrailer:
    case EntityCategory::kSemitrailer:
      v = generate_truck(e.category, e.box, rng);
      break;
    case EntityCategory::kBus:
    case EntityCategory::kTrain:
    case EntityCategory::kTram:
      v = generate_bus(e.category, e.box, rng);
      break;
    case EntityCategory::kMotorbike:
    case EntityCategory::kBicycle:
      v = generate_two_wheeler(e.category, e.box, rng);
      break;
    case EntityCategory::kPedestrian:
      person(e, rng, shape);
      return;
    case EntityCategory::kWheelchair:
      wheelchair(e, rng, shape);
      return;
    case EntityCategory::kAnimal:
      animal(e, rng, shape);
      return;
    case EntityCategory::kObstacle:
      obstacle(e, shape);
      return;
  }
  shape.pose = vehicle_pose(v);
  shape.mesh = std::move(v.mesh);
}

}  // namespace corsa::sensors::detail
