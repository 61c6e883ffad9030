#include "vehicle_parts.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "scalar_math.h"

namespace corsa::sensors::detail {
namespace {

Material paint(const std::string& name, Color c, bool metallic_flake) {
  Material m;
  m.name = name;
  m.base_color = c;
  m.roughness = 0.3;
  m.clearcoat = 1.0;
  m.metallic = metallic_flake ? 0.5 : 0.0;
  return m;
}

}  // namespace

Material draw_car_paint(RandomStream& rng) {
  // Shares of new cars worldwide, Axalta 2022 (see the header).
  static constexpr std::array<double, 8> kShares = {34, 21, 19, 8, 8, 5, 1, 4};
  switch (rng.weighted_index(kShares)) {
    case 0: {
      const bool pearl = rng.uniform01() < 14.0 / 34.0;  // 14 of the 34 points are pearl whites
      return pearl ? paint("paint pearl white", linear_rgb(230, 228, 222), true)
                   : paint("paint white", linear_rgb(236, 237, 238), false);
    }
    case 1:
      return paint("paint black", linear_rgb(16, 16, 18), rng.uniform01() < 0.5);
    case 2: {
      const double shade = rng.uniform01();
      return shade < 0.4   ? paint("paint grey", linear_rgb(92, 95, 99), true)
             : shade < 0.7 ? paint("paint dark grey", linear_rgb(55, 57, 61), true)
                           : paint("paint light grey", linear_rgb(140, 143, 146), false);
    }
    case 3:
      return paint("paint silver", linear_rgb(178, 181, 185), true);
    case 4:
      return rng.uniform01() < 0.6 ? paint("paint blue", linear_rgb(24, 48, 118), true)
                                   : paint("paint light blue", linear_rgb(70, 110, 165), false);
    case 5:
      return paint("paint red", linear_rgb(150, 14, 20), false);
    case 6:
      return paint("paint green", linear_rgb(28, 68, 44), true);
    default: {
      const double pick = rng.uniform01();
      return pick < 0.4    ? paint("paint beige", linear_rgb(192, 176, 146), true)
             : pick < 0.7  ? paint("paint brown", linear_rgb(88, 58, 38), true)
             : pick < 0.85 ? paint("paint yellow", linear_rgb(222, 182, 30), false)
                           : paint("paint orange", linear_rgb(212, 98, 24), false);
    }
  }
}

Material draw_fleet_paint(RandomStream& rng) {
  static constexpr std::array<double, 6> kShares = {50, 12, 12, 10, 8, 8};
  switch (rng.weighted_index(kShares)) {
    case 0:
      return paint("fleet white", linear_rgb(232, 233, 232), false);
    case 1:
      return paint("fleet blue", linear_rgb(30, 80, 160), false);
    case 2:
      return paint("fleet green", linear_rgb(40, 130, 70), false);
    case 3:
      return paint("fleet red", linear_rgb(170, 30, 30), false);
    case 4:
      return paint("fleet yellow", linear_rgb(230, 180, 20), false);
    default:
      return paint("fleet grey", linear_rgb(120, 122, 125), false);
  }
}

Material tyre_material() {
  Material m = materials::plain("tyre", linear_rgb(28, 28, 29), 0.9);
  m.pattern = Pattern::kRubber;
  return m;
}
Material rim_material() { return materials::metal("rim", linear_rgb(170, 172, 175), 0.3); }
Material trim_material() { return materials::plain("black trim", linear_rgb(22, 22, 24), 0.6); }
Material vehicle_glass() { return materials::glass("vehicle glass"); }

Material headlamp_material() {
  return materials::lamp("headlamp", linear_rgb(200, 205, 210), Color{6.0, 5.8, 5.2},
                         LightRole::kHeadlight);
}
Material tail_lamp_material() {
  return materials::lamp("tail lamp", linear_rgb(120, 10, 12), Color{1.2, 0.02, 0.01},
                         LightRole::kTail);
}
Material brake_lamp_material() {
  return materials::lamp("brake lamp", linear_rgb(140, 12, 14), Color{4.0, 0.05, 0.03},
                         LightRole::kBrake);
}
Material indicator_material(bool left) {
  return materials::lamp(left ? "indicator left" : "indicator right", linear_rgb(200, 120, 20),
                         Color{5.0, 2.2, 0.2},
                         left ? LightRole::kIndicatorLeft : LightRole::kIndicatorRight);
}
Material reversing_lamp_material() {
  return materials::lamp("reversing lamp", linear_rgb(215, 215, 215), Color{4.0, 4.0, 4.0},
                         LightRole::kReversing);
}

void add_wheel(MeshBuilder& b, const WheelSpec& w, int outward, int spokes) {
  b.bone(w.bone);
  const int segments = 28;
  const double r = w.radius;
  const double half = 0.5 * w.width;
  const double rim_r = 0.62 * r;
  const Vec3 c = w.centre;
  // Tyre: a ring profile swept around the axle (y): tread, rounded shoulders, sidewalls down
  // to the rim. Profile points (radius, y offset) from the inner to the outer side.
  const std::array<std::array<double, 2>, 8> profile = {{{rim_r, -half * 0.9},
                                                         {0.86 * r, -half},
                                                         {0.97 * r, -half * 0.93},
                                                         {r, -half * 0.7},
                                                         {r, half * 0.7},
                                                         {0.97 * r, half * 0.93},
                                                         {0.86 * r, half},
                                                         {rim_r, half * 0.9}}};
  b.material(tyre_material());
  std::vector<uint32_t> ids;
  for (int i = 0; i < segments; ++i) {
    const double a = 2.0 * kPi * i / segments;
    for (const auto& p : profile) {
      ids.push_back(
          b.vertex({c.x + p[0] * std::cos(a), c.y + p[1] * outward, c.z + p[0] * std::sin(a)}));
    }
  }
  const size_t n = profile.size();
  for (int i = 0; i < segments; ++i) {
    const int j = (i + 1) % segments;
    for (size_t k = 0; k + 1 < n; ++k) {
      b.quad(ids[i * n + k], ids[i * n + k + 1], ids[j * n + k + 1], ids[j * n + k]);
    }
  }
  // Rim face on the outer side, a little recessed: spokes (metal) and the dark gaps between
  // them alternate, so a turning wheel visibly turns. The hub closes the centre.
  const double face_y = c.y + outward * half * 0.75;
  const uint32_t hub = [&] {
    b.material(rim_material());
    return b.vertex({c.x, face_y + outward * 0.02, c.z});
  }();
  const int sectors = spokes * 2;
  for (int s = 0; s < sectors; ++s) {
    const double a0 = 2.0 * kPi * s / sectors;
    const double a1 = 2.0 * kPi * (s + 1) / sectors;
    const bool spoke = s % 2 == 0;
    b.material(spoke ? rim_material() : materials::plain("brake shadow", {0.01, 0.01, 0.01}));
    const double inner = 0.22 * rim_r;
    const uint32_t p0 = b.vertex({c.x + inner * std::cos(a0), face_y, c.z + inner * std::sin(a0)});
    const uint32_t p1 = b.vertex({c.x + inner * std::cos(a1), face_y, c.z + inner * std::sin(a1)});
    const uint32_t q0 = b.vertex({c.x + rim_r * std::cos(a0), face_y, c.z + rim_r * std::sin(a0)});
    const uint32_t q1 = b.vertex({c.x + rim_r * std::cos(a1), face_y, c.z + rim_r * std::sin(a1)});
    b.quad(p0, q0, q1, p1);
    b.material(rim_material());
    b.triangle(hub, p0, p1);
  }
  // Inner side: a dark disc closes the tyre.
  b.material(materials::plain("brake shadow", {0.01, 0.01, 0.01}));
  const uint32_t back = b.vertex({c.x, c.y - outward * half * 0.9, c.z});
  for (int i = 0; i < segments; ++i) {
    b.triangle(back, ids[i * n], ids[((i + 1) % segments) * n]);
  }
  b.bone(0);
}

std::function<void(const engine::EntitySnapshot&, std::vector<Rigid>&)> wheel_pose(
    std::vector<WheelSpec> wheels, double wheelbase, size_t bones) {
  return [wheels = std::move(wheels), wheelbase, bones](const engine::EntitySnapshot& e,
                                                        std::vector<Rigid>& out) {
    out.assign(bones, Rigid{});
    double steer = 0.0;
    if (std::fabs(e.speed) > 0.5 && wheelbase > 0.0) {
      steer = std::atan(wheelbase * e.yaw_rate / e.speed);
      steer = std::clamp(steer, -0.61, 0.61);  // 35 degrees
    }
    for (const WheelSpec& w : wheels) {
      if (w.bone >= bones) {
        continue;
      }
      // Rolling forward turns the top of the wheel forward: +angle about the axle (y).
      const double spin = std::fmod(e.odometer / w.radius, 2.0 * kPi);
      const Rigid turn = rigid_from_pose(0.0, 0.0, 0.0, w.steers ? steer : 0.0, spin, 0.0);
      Rigid t;
      t.rotation = turn.rotation;
      t.translation = w.centre - turn.rotation * w.centre;
      out[w.bone] = t;
    }
  };
}

void add_lamp(MeshBuilder& b, const Material& m, double x_face, double y, double z, double size_y,
              double size_z, int facing) {
  b.material(m);
  const double depth = 0.03;
  const double x0 = facing > 0 ? x_face - depth : x_face;
  const double x1 = facing > 0 ? x_face : x_face + depth;
  b.box({x0, y - 0.5 * size_y, z - 0.5 * size_z}, {x1, y + 0.5 * size_y, z + 0.5 * size_z});
}

void add_plate(MeshBuilder& b, double x_face, double y, double z, int facing, RandomStream& rng) {
  Material m;
  m.name = "plate " + std::to_string(rng.next_u64() % 1000000);
  m.pattern = Pattern::kPlate;
  m.roughness = 0.4;
  m.sign.shape = SignShape::kRectangle;
  m.sign.fill = linear_rgb(225, 226, 224);
  m.sign.border = linear_rgb(20, 20, 22);
  m.sign.border_width = 0.06;
  m.sign.symbol = SignSymbol::kNumber;
  m.sign.symbol_color = linear_rgb(15, 15, 18);
  m.sign.number = static_cast<int>(100000 + rng.next_u64() % 900000);
  m.sign.aspect = 0.52 / 0.11;
  m.base_color = m.sign.fill;
  b.material(m);
  const double hw = 0.26;
  const double hh = 0.055;
  const double x = x_face + facing * 0.008;
  // Seen from the front of the plate, u runs to the viewer's right.
  const double right = facing > 0 ? -1.0 : 1.0;  // the viewer's right in entity y
  b.polygon({{x, y - right * hw, z - hh},
             {x, y + right * hw, z - hh},
             {x, y + right * hw, z + hh},
             {x, y - right * hw, z + hh}},
            {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}});
  // A backing plate so that the plate is solid from the side.
  b.material(trim_material());
  const double x0 = facing > 0 ? x - 0.012 : x + 0.002;
  b.box({x0, y - hw, z - hh}, {x0 + 0.01, y + hw, z + hh});
}

}  // namespace corsa::sensors::detail
