// Bicycles and motorbikes with their riders: frames of tubes, wheels that turn and steer,
// cranks that turn with the distance ridden (and the rider's legs following the pedals), lamps
// on motorbikes; the rider is a person of class rider (with a helmet on a motorbike).

#include <algorithm>
#include <cmath>
#include <numbers>

#include "scalar_math.h"
#include "vehicle_generators.h"

namespace corsa::sensors::detail {
namespace {

/// A spoked bicycle wheel: a thin tyre ring, a rim, spokes and a hub, open between the spokes.
void add_bicycle_wheel(MeshBuilder& b, const WheelSpec& w) {
  b.bone(w.bone);
  const int segments = 32;
  const Vec3 c = w.centre;
  const double r = w.radius;
  const double t = 0.5 * w.width;
  std::vector<std::vector<Vec3>> rings;
  // The tyre's cross-section swept round the axle: a small diamond.
  const double profile[4][2] = {{r, 0.0}, {r - t, t}, {r - 2.2 * t, 0.0}, {r - t, -t}};
  for (int k = 0; k < 4; ++k) {
    std::vector<Vec3> ring;
    for (int i = 0; i < segments; ++i) {
      const double a = 2.0 * kPi * i / segments;
      ring.push_back({c.x + profile[k][0] * std::cos(a), c.y + profile[k][1],
                      c.z + profile[k][0] * std::sin(a)});
    }
    rings.push_back(ring);
  }
  rings.push_back(rings.front());
  b.material(tyre_material());
  b.loft(rings, false);
  b.material(rim_material());
  for (int i = 0; i < 12; ++i) {
    const double a = 2.0 * kPi * i / 12.0;
    const double side = (i % 2 == 0 ? 1.0 : -1.0) * 0.02;
    b.tube({c.x, c.y + side, c.z},
           {c.x + (r - 2.2 * t) * std::cos(a), c.y, c.z + (r - 2.2 * t) * std::sin(a)}, 0.004,
           0.004, 4, false);
  }
  b.tube({c.x, c.y - 0.04, c.z}, {c.x, c.y + 0.04, c.z}, 0.02, 0.02, 8, true);
  b.bone(0);
}

}  // namespace

GeneratedVehicle generate_two_wheeler(engine::EntityCategory category, const engine::Box& box,
                                      RandomStream& rng) {
  const bool motor = category == engine::EntityCategory::kMotorbike;
  GeneratedVehicle out;
  MeshBuilder b;
  const SemanticClass cls = motor ? SemanticClass::kMotorcycle : SemanticClass::kBicycle;
  b.semantic(cls);
  const double x0 = box.center_x - 0.5 * box.length;
  const double x1 = box.center_x + 0.5 * box.length;
  const double yc = box.center_y;
  const double zb = box.center_z - 0.5 * box.height;
  const double radius =
      motor ? std::clamp(0.15 * box.length, 0.28, 0.34) : std::clamp(0.19 * box.length, 0.28, 0.35);
  const double xr = x0 + radius + 0.03;
  const double xf = x1 - radius - (motor ? 0.08 : 0.03);
  const double wheelbase = xf - xr;
  Material frame_paint = motor ? draw_car_paint(rng) : draw_fleet_paint(rng);
  frame_paint.name = (motor ? "motorbike " : "bicycle ") + frame_paint.name;
  WheelSpec rear{{xr, yc, zb + radius}, radius, motor ? 0.14 : 0.035, false, 1, false};
  WheelSpec front{{xf, yc, zb + radius}, radius, motor ? 0.12 : 0.035, true, 2, false};
  // Scale of the frame to the wheelbase (a 1.05 m bicycle, a 1.45 m motorbike).
  const double k = wheelbase / (motor ? 1.45 : 1.05);
  PersonPlacement rider;
  rider.semantic = SemanticClass::kRider;
  rider.first_bone = 3;
  rider.by_hip = true;
  Vec3 crank_axis;
  if (motor) {
    add_wheel(b, rear, 1, 5);
    add_wheel(b, front, 1, 5);
    b.material(frame_paint);
    b.ellipsoid({xr + 0.78 * k, yc, zb + 0.86}, {0.28 * k, 0.15, 0.12}, Mat3{}, 12, 8);  // tank
    b.material(trim_material());
    b.box({xr + 0.2 * k, yc - 0.13, zb + 0.76}, {xr + 0.62 * k, yc + 0.13, zb + 0.84});  // seat
    b.material(materials::metal("engine", linear_rgb(90, 92, 95), 0.4));
    b.box({xr + 0.45 * k, yc - 0.17, zb + 0.3}, {xr + 0.95 * k, yc + 0.17, zb + 0.66});
    b.tube({xr + 0.5 * k, yc - 0.15, zb + 0.32}, {xr - 0.1, yc - 0.16, zb + 0.45}, 0.04, 0.045, 8);
    b.material(frame_paint);
    b.box({xr - 0.12, yc - 0.1, zb + 0.72}, {xr + 0.25 * k, yc + 0.1, zb + 0.82});  // tail
    b.material(materials::metal("fork", linear_rgb(160, 160, 165), 0.3));
    const Vec3 head{xf - 0.28 * k, yc, zb + 1.0};
    b.tube({xf, yc + 0.07, zb + radius}, head + Vec3{0.0, 0.07, 0.0}, 0.025, 0.025, 6);
    b.tube({xf, yc - 0.07, zb + radius}, head + Vec3{0.0, -0.07, 0.0}, 0.025, 0.025, 6);
    b.material(trim_material());
    b.tube(head + Vec3{-0.05, -0.36, 0.08}, head + Vec3{-0.05, 0.36, 0.08}, 0.014, 0.014, 6);
    b.material(headlamp_material());
    b.ellipsoid(head + Vec3{0.12, 0.0, -0.05}, {0.06, 0.09, 0.08}, Mat3{}, 10, 6);
    add_lamp(b, brake_lamp_material(), xr - 0.12, yc, zb + 0.8, 0.12, 0.05, -1);
    add_lamp(b, tail_lamp_material(), xr - 0.12, yc, zb + 0.75, 0.12, 0.04, -1);
    add_plate(b, xr - 0.13, yc, zb + 0.62, -1, rng);
    rider.ground = {xr + 0.42 * k, yc, zb + 0.88};
    rider.hands = head + Vec3{-0.08, 0.0, 0.08};
    rider.hand_spread = 0.62;
    rider.feet = {xr + 0.55 * k, yc, zb + 0.32};
  } else {
    add_bicycle_wheel(b, rear);
    add_bicycle_wheel(b, front);
    b.material(frame_paint);
    const Vec3 bb{xr + 0.42 * k, yc, zb + 0.29};
    const Vec3 seat{bb.x - 0.17 * k, yc, bb.z + 0.55};
    const Vec3 head_top{xf - 0.2 * k, yc, zb + 0.95};
    const Vec3 head_bottom{xf - 0.15 * k, yc, zb + 0.78};
    const double tr = 0.018;
    b.tube(bb, seat, tr, tr, 6);
    b.tube(seat, head_top, tr, tr, 6);
    b.tube(bb, head_bottom, tr * 1.2, tr * 1.2, 6);
    b.tube(head_bottom, head_top, tr * 1.3, tr * 1.3, 6);
    for (double side : {-0.05, 0.05}) {
      b.tube(bb, {xr, yc + side, zb + radius}, 0.011, 0.011, 5);
      b.tube(seat, {xr, yc + side, zb + radius}, 0.01, 0.01, 5);
      b.tube(head_bottom, {xf, yc + side, zb + radius}, 0.012, 0.012, 5);
    }
    b.material(trim_material());
    b.ellipsoid(seat + Vec3{0.0, 0.0, 0.07}, {0.13, 0.07, 0.035}, Mat3{}, 8, 5);
    b.tube(seat, seat + Vec3{0.0, 0.0, 0.06}, 0.012, 0.012, 5);
    b.tube(head_top + Vec3{0.05, -0.29, 0.06}, head_top + Vec3{0.05, 0.29, 0.06}, 0.013, 0.013, 6);
    b.tube(head_top, head_top + Vec3{0.05, 0.0, 0.06}, 0.014, 0.014, 5);
    add_lamp(b, tail_lamp_material(), xr - 0.05, yc, zb + 0.75, 0.06, 0.03, -1);
    // Cranks and pedals on their own bone, turning with the distance ridden.
    b.bone(static_cast<uint8_t>(3 + kBoneCount - 1));
    b.material(materials::metal("crank", linear_rgb(120, 120, 125), 0.35));
    b.tube(bb + Vec3{0.0, 0.07, 0.0}, bb + Vec3{0.17, 0.07, 0.0}, 0.01, 0.01, 5);
    b.tube(bb + Vec3{0.0, -0.07, 0.0}, bb + Vec3{-0.17, -0.07, 0.0}, 0.01, 0.01, 5);
    b.material(trim_material());
    b.box(bb + Vec3{0.14, 0.08, -0.01}, bb + Vec3{0.2, 0.17, 0.01});
    b.box(bb + Vec3{-0.2, -0.17, -0.01}, bb + Vec3{-0.14, -0.08, 0.01});
    b.bone(0);
    crank_axis = bb;
    rider.ground = seat + Vec3{-0.03, 0.0, 0.12};
    rider.hands = head_top + Vec3{0.05, 0.0, 0.06};
    rider.hand_spread = 0.56;
    rider.pedal_axis = bb;
    rider.crank = 0.17;
  }
  PersonLook look =
      draw_person_look(rng.uniform(1.62, 1.88) * std::clamp(box.height / 1.7, 0.85, 1.15), rng);
  if (motor) {
    Material helmet = rng.uniform01() < 0.5
                          ? materials::plain("helmet black", {0.01, 0.01, 0.012}, 0.2)
                          : materials::plain("helmet white", linear_rgb(220, 220, 220), 0.2);
    helmet.clearcoat = 1.0;
    look.hair = helmet;
    look.long_hair = false;
    look.long_sleeves = true;
  }
  b.semantic(SemanticClass::kRider);
  add_person(b, look, rider);
  const size_t bones = 3 + kBoneCount - 1 + (motor ? 0 : 1);
  out.mesh = b.take();
  out.wheels = {rear, front};
  out.wheelbase = wheelbase;
  out.bones = bones;
  const Posture posture = motor ? Posture::kRideMotorbike : Posture::kCycle;
  out.extra_pose = [look, rider, posture, crank_axis, radius, motor](
                       const engine::EntitySnapshot& e, std::vector<Rigid>& pose) {
    // One crank turn per 2.6 wheel turns (a middle gear); riding forward the front pedal goes
    // down, so the angle decreases.
    const double crank =
        motor ? 0.0 : -std::fmod(e.odometer / (2.0 * kPi * radius) / 2.6, 1.0) * 2.0 * kPi;
    pose_person(look, rider, posture, crank, 1.0, pose);
    if (!motor) {
      const Rigid turn = rigid_from_pose(0.0, 0.0, 0.0, 0.0, -crank, 0.0);
      Rigid t;
      t.rotation = turn.rotation;
      t.translation = crank_axis - turn.rotation * crank_axis;
      pose[3 + kBoneCount - 1] = t;
    }
  };
  return out;
}

}  // namespace corsa::sensors::detail
