#include "street_furniture.h"

#include <algorithm>
#include <cmath>

#include "corsa/sensors/color.h"
#include "scalar_math.h"
#include "world_props.h"

namespace corsa::sensors::detail {
namespace {

Material furniture_steel() {
  return materials::metal("furniture steel", linear_rgb(140, 142, 140), 0.4);
}
Material powder_coat(const char* name, Rgb8 c) {
  return materials::plain(name, linear_rgb(c.r, c.g, c.b), 0.55);
}

/// One of a few colours in which towns paint their furniture (named by index so that the scene
/// shares them between objects).
Material furniture_paint(RandomStream& rng) {
  static constexpr Rgb8 kColours[4] = {{34, 62, 44}, {52, 54, 56}, {22, 22, 24}, {36, 52, 84}};
  const auto i = static_cast<size_t>(rng.uniform_int(0, 3));
  static constexpr const char* kNames[4] = {"furniture green", "furniture grey", "furniture black",
                                            "furniture blue"};
  return powder_coat(kNames[i], kColours[i]);
}

Material bench_timber() {
  Material m = materials::plain("bench timber", linear_rgb(120, 84, 52), 0.75);
  m.pattern = Pattern::kBark;  // grain along the slats
  return m;
}

/// A flat sign face (class traffic_sign) in the plane x = `x`, facing +x (or -x when `back`),
/// between y0..y1 and z0..z1, with uvs over its rectangle.
void sign_blade(MeshBuilder& b, const SignFace& face, const char* name, double x, double y0,
                double y1, double z0, double z1, bool back) {
  const Material m = sign_face_material(face, name);
  b.material(m);
  const float u0 = back ? 1.0f : 0.0f;
  const float u1 = back ? 0.0f : 1.0f;
  // Seen from +x, y decreases to the right: u runs from y1 to y0 on the front.
  const uint32_t a = b.vertex({x, y1, z0}, u0, 0.0f);
  const uint32_t c = b.vertex({x, y0, z0}, u1, 0.0f);
  const uint32_t d = b.vertex({x, y0, z1}, u1, 1.0f);
  const uint32_t e = b.vertex({x, y1, z1}, u0, 1.0f);
  if (back) {
    b.quad(a, e, d, c);
  } else {
    b.quad(a, c, d, e);
  }
}

}  // namespace

ArticulatedMesh make_litter_bin(RandomStream& rng) {
  MeshBuilder b;
  b.semantic(SemanticClass::kStatic).material(furniture_paint(rng));
  const double h = rng.uniform(0.85, 1.0);
  const double r = rng.uniform(0.2, 0.24);
  b.tube({0, 0, 0.08}, {0, 0, h - 0.06}, 0.92 * r, r, 16, true);
  b.tube({0, 0, h - 0.06}, {0, 0, h}, r + 0.02, r + 0.02, 16, false);  // the rim
  b.material(powder_coat("bin opening", {12, 12, 12}));
  b.tube({0, 0, h - 0.01}, {0, 0, h}, r - 0.01, r - 0.01, 16, true);
  b.material(furniture_steel());
  b.tube({0, 0, 0}, {0, 0, 0.08}, 0.5 * r, 0.5 * r, 10, true);  // the foot
  return b.take();
}

ArticulatedMesh make_bollard(RandomStream& rng) {
  MeshBuilder b;
  b.semantic(SemanticClass::kStatic);
  const bool steel = rng.uniform01() < 0.4;
  b.material(steel ? furniture_steel() : powder_coat("bollard", {30, 30, 32}));
  const double h = rng.uniform(0.9, 1.0);
  b.tube({0, 0, 0}, {0, 0, h - 0.08}, 0.1, 0.1, 14, false);
  b.ellipsoid({0, 0, h - 0.08}, {0.1, 0.1, 0.08}, Mat3{}, 14, 6);
  // A retroreflective band below the cap.
  b.material(materials::plain("bollard band", linear_rgb(225, 225, 215), 0.35));
  b.tube({0, 0, h - 0.25}, {0, 0, h - 0.17}, 0.103, 0.103, 14, false);
  return b.take();
}

ArticulatedMesh make_fire_hydrant(RandomStream& rng) {
  MeshBuilder b;
  b.semantic(SemanticClass::kStatic);
  const bool yellow = rng.uniform01() < 0.35;
  b.material(yellow ? powder_coat("hydrant yellow", {196, 150, 18})
                    : powder_coat("hydrant red", {150, 22, 18}));
  b.tube({0, 0, 0}, {0, 0, 0.06}, 0.16, 0.16, 16, true);      // flange
  b.tube({0, 0, 0.06}, {0, 0, 0.58}, 0.11, 0.11, 16, false);  // barrel
  b.tube({0, 0, 0.58}, {0, 0, 0.62}, 0.14, 0.14, 16, true);   // bonnet flange
  b.ellipsoid({0, 0, 0.62}, {0.12, 0.12, 0.09}, Mat3{}, 16, 6);
  b.tube({0, 0, 0.7}, {0, 0, 0.76}, 0.03, 0.02, 6, true);  // the operating nut
  for (const double side : {-1.0, 1.0}) {
    b.tube({0, 0.0, 0.42}, {0, side * 0.19, 0.42}, 0.045, 0.045, 10, true);
  }
  b.tube({0, 0, 0.36}, {0.2, 0, 0.36}, 0.065, 0.065, 12, true);
  return b.take();
}

ArticulatedMesh make_bench(RandomStream& rng) {
  MeshBuilder b;
  b.semantic(SemanticClass::kStatic).material(furniture_paint(rng));
  constexpr double kHalf = 0.9;
  // Two cast frames: legs, a seat support and the backrest's upright (the back at -x).
  for (const double y : {-kHalf + 0.15, kHalf - 0.15}) {
    b.box({0.15, y - 0.03, 0.0}, {0.21, y + 0.03, 0.43});
    b.box({-0.24, y - 0.03, 0.0}, {-0.18, y + 0.03, 0.43});
    b.box({-0.25, y - 0.03, 0.4}, {0.24, y + 0.03, 0.44});
    b.box({-0.27, y - 0.03, 0.44}, {-0.22, y + 0.03, 0.85});
  }
  b.material(bench_timber());
  for (int k = 0; k < 4; ++k) {  // seat slats
    const double x0 = -0.25 + 0.125 * k;
    b.box({x0, -kHalf, 0.44}, {x0 + 0.1, kHalf, 0.47});
  }
  for (int k = 0; k < 3; ++k) {  // backrest slats
    const double z0 = 0.52 + 0.11 * k;
    b.box({-0.22, -kHalf, z0}, {-0.19, kHalf, z0 + 0.09});
  }
  return b.take();
}

ArticulatedMesh make_bus_shelter(RandomStream& rng, double length) {
  MeshBuilder b;
  b.semantic(SemanticClass::kStatic).material(furniture_paint(rng));
  const double half = 0.5 * length;
  constexpr double kDepth = 1.4;
  constexpr double kHeight = 2.5;
  const double back = -0.5 * kDepth;
  const double front = 0.5 * kDepth;
  // Posts at the back corners and the back's middle, and at the front corners.
  for (const double y : {-half, 0.0, half}) {
    b.box({back, y - 0.04, 0.0}, {back + 0.08, y + 0.04, kHeight});
  }
  for (const double y : {-half, half}) {
    b.box({front - 0.08, y - 0.04, 0.0}, {front, y + 0.04, kHeight});
  }
  // The roof, sloping a little towards the back, with a fascia.
  b.box({back - 0.1, -half - 0.1, kHeight}, {front + 0.15, half + 0.1, kHeight + 0.1});
  b.material(powder_coat("shelter fascia", {210, 210, 205}));
  b.box({front + 0.15, -half - 0.1, kHeight - 0.05}, {front + 0.18, half + 0.1, kHeight + 0.12});
  // Glass: the back wall and the side panel at -y (the other end holds the advert panel).
  b.material(materials::glass("shelter glass"));
  b.box({back + 0.02, -half + 0.04, 0.15}, {back + 0.04, half - 0.04, kHeight - 0.1});
  b.box({back + 0.08, -half - 0.01, 0.15}, {front - 0.35, -half + 0.01, kHeight - 0.1});
  // The advert panel: a lit-looking poster in a frame.
  b.material(powder_coat("shelter advert frame", {40, 40, 42}));
  b.box({back + 0.08, half - 0.08, 0.1}, {back + 1.0, half, 2.1});
  const Color poster = rng.uniform01() < 0.5 ? linear_rgb(200, 150, 60) : linear_rgb(70, 140, 190);
  b.material(materials::plain(rng.uniform01() < 0.5 ? "shelter poster a" : "shelter poster b",
                              poster, 0.3));
  b.box({back + 0.14, half - 0.09, 0.2}, {back + 0.94, half - 0.08, 2.0});
  // A perch seat along the back.
  b.material(furniture_steel());
  b.box({back + 0.1, -0.4 * length, 0.5}, {back + 0.45, 0.2 * length, 0.55});
  return b.take();
}

ArticulatedMesh make_bus_stop_sign() {
  // A yellow round face with a green border (the German Haltestelle, StVO 224, without its H).
  SignFace face;
  face.shape = SignShape::kCircle;
  face.fill = linear_rgb(240, 200, 20);
  face.border = linear_rgb(20, 110, 60);
  face.border_width = 0.12;
  return make_sign(face, 0.45, 0.45, 2.0, "bus stop sign");
}

ArticulatedMesh make_street_name_sign(RandomStream& rng) {
  MeshBuilder b;
  b.semantic(SemanticClass::kPole).material(furniture_steel());
  b.tube({0, 0, 0}, {0, 0, 2.75}, 0.035, 0.035, 8, true);
  SignFace face;
  face.shape = SignShape::kRectangle;
  const bool blue = rng.uniform01() < 0.6;
  face.fill = blue ? linear_rgb(20, 50, 120) : linear_rgb(20, 95, 55);
  face.border = linear_rgb(235, 235, 235);
  face.border_width = 0.12;
  face.aspect = 4.0;
  b.semantic(SemanticClass::kTrafficSign);
  const char* name = blue ? "street name blue" : "street name green";
  // One blade across x (read from ±x) at 2.45-2.65 m, one across y a little higher.
  sign_blade(b, face, name, 0.04, -0.05, 0.75, 2.45, 2.65, false);
  sign_blade(b, face, name, 0.03, -0.05, 0.75, 2.45, 2.65, true);
  b.transform(rigid_from_pose(0, 0, 0, -0.5 * kPi, 0, 0));  // the second blade over the path
  sign_blade(b, face, name, 0.04, -0.05, 0.75, 2.68, 2.88, false);
  sign_blade(b, face, name, 0.03, -0.05, 0.75, 2.68, 2.88, true);
  b.transform(Rigid{});
  return b.take();
}

}  // namespace corsa::sensors::detail
