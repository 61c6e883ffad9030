// Trucks (rigid, tractor with semitrailer), trailers, buses, trams and trains: bodies lofted from
// rounded-rectangle sections, cabs with windscreens and side windows, window bands with pillars,
// doors, lamps, plates, and axles with single or twin tyres.

#include <algorithm>
#include <cmath>
#include <vector>

#include "vehicle_generators.h"

namespace corsa::sensors::detail {
namespace {

/// A rounded-rectangle section at x: half width w, from z0 to z1, corner radius r (8 points a
/// corner).
std::vector<Vec3> rounded_section(double x, double yc, double w, double z0, double z1, double r_top,
                                  double r_bottom) {
  std::vector<Vec3> ring;
  auto corner = [&](double cy, double cz, double r, double a0) {
    for (int i = 0; i <= 4; ++i) {
      const double a = a0 + 0.5 * 3.14159265358979 * i / 4.0;
      ring.push_back({x, yc + cy + r * std::cos(a), cz + r * std::sin(a)});
    }
  };
  r_top = std::min({r_top, 0.45 * w, 0.45 * (z1 - z0)});
  r_bottom = std::min({r_bottom, 0.45 * w, 0.45 * (z1 - z0)});
  corner(-w + r_bottom, z0 + r_bottom, r_bottom, 3.14159265358979);       // bottom right
  corner(w - r_bottom, z0 + r_bottom, r_bottom, 1.5 * 3.14159265358979);  // bottom left
  corner(w - r_top, z1 - r_top, r_top, 0.0);                              // top left
  corner(-w + r_top, z1 - r_top, r_top, 0.5 * 3.14159265358979);          // top right
  return ring;
}

/// A box-like body from x0 to x1 whose front end is rounded in plan (shrinking sections).
void add_box_body(MeshBuilder& b, double x0, double x1, double yc, double w, double z0, double z1,
                  double r_top, double front_round) {
  std::vector<std::vector<Vec3>> rings;
  const int n = 12;
  for (int i = 0; i <= n; ++i) {
    const double t = static_cast<double>(i) / n;
    const double x = x0 + (x1 - x0) * t;
    // The last 8% of the length rounds off the front edges.
    const double f = std::clamp((t - 0.92) / 0.08, 0.0, 1.0);
    const double shrink = front_round * f * f;
    rings.push_back(
        rounded_section(x, yc, w - shrink, z0 + 0.3 * shrink, z1 - shrink, r_top + shrink, 0.05));
  }
  b.loft(rings, true);
}

/// A flat pane (glass or panel) on a face: `facing` along x (+1 front, -1 rear) or along y
/// (+2 left side, -2 right side), at coordinate `at`, spanning the other two ranges.
void pane(MeshBuilder& b, const Material& m, int facing, double at, double a0, double a1, double z0,
          double z1) {
  b.material(m);
  const double t = 0.012;
  if (facing == 1 || facing == -1) {
    const double x = at + facing * 0.004;
    b.box({std::min(x, x - facing * t), a0, z0}, {std::max(x, x - facing * t), a1, z1});
  } else {
    const double y = at + (facing > 0 ? 0.004 : -0.004);
    const double d = facing > 0 ? -t : t;
    b.box({a0, std::min(y, y + d), z0}, {a1, std::max(y, y + d), z1});
  }
}

void lamps_front(MeshBuilder& b, double x, double yc, double w, double z, double size) {
  for (int side : {-1, 1}) {
    add_lamp(b, headlamp_material(), x + 0.01, yc + side * (w - 0.3), z, 0.32 * size, 0.16 * size,
             1);
    add_lamp(b, indicator_material(side > 0), x + 0.01, yc + side * (w - 0.08), z, 0.1, 0.12, 1);
  }
}

void lamps_rear(MeshBuilder& b, double x, double yc, double w, double z) {
  for (int side : {-1, 1}) {
    add_lamp(b, brake_lamp_material(), x - 0.01, yc + side * (w - 0.2), z + 0.07, 0.25, 0.1, -1);
    add_lamp(b, tail_lamp_material(), x - 0.01, yc + side * (w - 0.2), z - 0.05, 0.25, 0.1, -1);
    add_lamp(b, indicator_material(side > 0), x - 0.01, yc + side * (w - 0.45), z, 0.16, 0.12, -1);
  }
}

/// Axles: each a wheel per side (twin tyres are one wide wheel with a groove look).
void add_axles(MeshBuilder& b, GeneratedVehicle& out, const std::vector<double>& xs, double yc,
               double w, double zb, double radius, double steer_x, const std::vector<bool>& twin) {
  uint8_t bone = static_cast<uint8_t>(out.bones);
  for (size_t i = 0; i < xs.size(); ++i) {
    for (int side : {-1, 1}) {
      WheelSpec s;
      s.radius = radius;
      s.width = twin[i] ? 0.5 : 0.3;
      s.centre = {xs[i], yc + side * (w - 0.5 * s.width - 0.02), zb + radius};
      s.steers = xs[i] == steer_x;
      s.bone = bone++;
      s.dual = twin[i];
      add_wheel(b, s, side, 8);
      out.wheels.push_back(s);
    }
  }
  out.bones = bone;
}

/// A cab: rounded front, windscreen, door windows, lamps and a plate at the front end x1.
void add_cab(MeshBuilder& b, const Material& paint, double x0, double x1, double yc, double w,
             double z0, double z1, RandomStream& rng) {
  b.material(paint);
  add_box_body(b, x0, x1, yc, w, z0, z1, 0.2, 0.15);
  const double screen_low = z0 + 0.48 * (z1 - z0);
  pane(b, vehicle_glass(), 1, x1 - 0.03, yc - w + 0.22, yc + w - 0.22, screen_low, z1 - 0.25);
  for (int side : {-1, 1}) {
    pane(b, vehicle_glass(), 2 * side, yc + side * w, x1 - 1.2, x1 - 0.45, screen_low + 0.1,
         z1 - 0.3);
  }
  lamps_front(b, x1, yc, w, z0 + 0.35, 1.0);
  b.material(trim_material());
  b.box({x1 - 0.08, yc - w + 0.05, z0}, {x1 + 0.02, yc + w - 0.05, z0 + 0.22});  // bumper
  Material grille = materials::plain("grille", linear_rgb(35, 35, 38), 0.5);
  grille.pattern = Pattern::kMetalGrid;
  grille.secondary = linear_rgb(8, 8, 9);
  pane(b, grille, 1, x1 - 0.02, yc - 0.5 * w, yc + 0.5 * w, z0 + 0.5, screen_low - 0.1);
  add_plate(b, x1 + 0.02, yc, z0 + 0.11, 1, rng);
  // Mirrors on arms.
  for (int side : {-1, 1}) {
    b.material(trim_material());
    const double y0 = yc + side * w;
    const double y1 = yc + side * (w + 0.3);
    b.box({x1 - 0.35, std::min(y0, y1), screen_low + 0.2},
          {x1 - 0.25, std::max(y0, y1), screen_low + 0.65});
  }
}

/// A cargo box or trailer body from x0 to x1.
void add_cargo(MeshBuilder& b, const Material& panel, double x0, double x1, double yc, double w,
               double z0, double z1, RandomStream& rng) {
  b.material(panel);
  add_box_body(b, x0, x1, yc, w, z0, z1, 0.05, 0.0);
  b.material(trim_material());
  b.box({x0, yc - w + 0.02, z0 - 0.12}, {x1, yc + w - 0.02, z0});  // underrun rail
  lamps_rear(b, x0, yc, w, z0 + 0.12);
  add_plate(b, x0 - 0.02, yc, z0 + 0.1, -1, rng);
  // Rear doors' seam and hinges: a dark vertical line.
  b.material(trim_material());
  b.box({x0 - 0.015, yc - 0.01, z0 + 0.05}, {x0 + 0.002, yc + 0.01, z1 - 0.05});
}

}  // namespace

GeneratedVehicle generate_truck(engine::EntityCategory category, const engine::Box& box,
                                RandomStream& rng) {
  GeneratedVehicle out;
  MeshBuilder b;
  b.semantic(SemanticClass::kTruck);
  const double x0 = box.center_x - 0.5 * box.length;
  const double x1 = box.center_x + 0.5 * box.length;
  const double yc = box.center_y;
  const double w = 0.5 * box.width;
  const double zb = box.center_z - 0.5 * box.height;
  const double zt = zb + box.height;
  const double radius = std::clamp(0.15 * box.height, 0.4, 0.55);
  const Material cab_paint = draw_fleet_paint(rng);
  Material panel = rng.uniform01() < 0.7
                       ? materials::plain("cargo white", linear_rgb(225, 226, 224), 0.5)
                       : draw_fleet_paint(rng);
  panel.name = "cargo " + panel.name;
  out.bones = 1;
  const bool trailer_only = category == engine::EntityCategory::kTrailer ||
                            category == engine::EntityCategory::kSemitrailer;
  if (trailer_only) {
    const double z0 = zb + (category == engine::EntityCategory::kSemitrailer ? 1.25 : 1.0);
    add_cargo(b, panel, x0, x1, yc, w, z0, zt, rng);
    std::vector<double> axles = {x0 + 1.4, x0 + 2.7};
    if (category == engine::EntityCategory::kTrailer) {
      axles.push_back(x1 - 1.2);
    }
    add_axles(b, out, axles, yc, w, zb, radius, 1e9, std::vector<bool>(axles.size(), false));
    out.wheelbase = 0.0;
  } else if (box.length <= 11.0) {
    const double cab_len = std::min(2.3, 0.35 * box.length);
    const double cab_top = std::min(zt, zb + 3.0);
    add_cab(b, cab_paint, x1 - cab_len, x1, yc, w, zb + 0.55, cab_top, rng);
    add_cargo(b, panel, x0, x1 - cab_len - 0.15, yc, w, zb + 1.05, zt, rng);
    b.material(trim_material());
    b.box({x0 + 0.3, yc - 0.45, zb + 0.55}, {x1 - 0.5, yc + 0.45, zb + 0.95});  // chassis
    const double rear = (0.0 > x0 + 0.8 && 0.0 < x1 - cab_len - 1.0) ? 0.0 : x0 + 0.3 * box.length;
    const double front = x1 - 0.6 * cab_len;
    add_axles(b, out, {front, rear}, yc, w, zb, radius, front, {false, true});
    out.wheelbase = front - rear;
  } else {
    // Tractor and semitrailer in one box: the cab in front, the trailer behind.
    const double cab_len = 2.4;
    add_cab(b, cab_paint, x1 - cab_len, x1, yc, w, zb + 0.6, std::min(zt, zb + 3.6), rng);
    add_cargo(b, panel, x0, x1 - cab_len - 0.6, yc, w, zb + 1.3, zt, rng);
    b.material(trim_material());
    b.box({x1 - cab_len - 2.8, yc - 0.5, zb + 0.6}, {x1 - 0.4, yc + 0.5, zb + 1.1});  // chassis
    const double front = x1 - 1.4;
    const double drive = x1 - cab_len - 2.0;
    add_axles(b, out, {front, drive, x0 + 1.3, x0 + 2.6, x0 + 3.9}, yc, w, zb, radius, front,
              {false, true, false, false, false});
    out.wheelbase = front - drive;
  }
  out.mesh = b.take();
  return out;
}

GeneratedVehicle generate_bus(engine::EntityCategory category, const engine::Box& box,
                              RandomStream& rng) {
  GeneratedVehicle out;
  MeshBuilder b;
  const bool rail =
      category == engine::EntityCategory::kTrain || category == engine::EntityCategory::kTram;
  b.semantic(rail ? SemanticClass::kTrain : SemanticClass::kBus);
  const double x0 = box.center_x - 0.5 * box.length;
  const double x1 = box.center_x + 0.5 * box.length;
  const double yc = box.center_y;
  const double w = 0.5 * box.width;
  const double zb = box.center_z - 0.5 * box.height;
  const double zt = zb + box.height;
  const double floor = zb + (rail ? 0.6 : 0.32);
  Material paint = draw_fleet_paint(rng);
  paint.name = "bus " + paint.name;
  b.material(paint);
  add_box_body(b, x0, x1, yc, w, floor, zt, 0.3, rail ? 0.35 : 0.12);
  // Windscreen and rear window.
  pane(b, vehicle_glass(), 1, x1 - 0.02, yc - w + 0.12, yc + w - 0.12, floor + 0.6, zt - 0.35);
  pane(b, vehicle_glass(), -1, x0, yc - w + 0.3, yc + w - 0.3, floor + 1.3, zt - 0.35);
  // Destination display over the windscreen.
  pane(b,
       materials::lamp("destination display", linear_rgb(30, 28, 20), Color{1.2, 0.7, 0.1},
                       LightRole::kAlways),
       1, x1 - 0.02, yc - w + 0.35, yc + w - 0.35, zt - 0.3, zt - 0.1);
  // Side windows with pillars every ~1.35 m, doors on the right (y < 0) side.
  const double win_low = floor + (rail ? 0.7 : 0.85);
  const double win_high = zt - 0.3;
  const double door_w = 1.1;
  const std::vector<double> doors = {x1 - 0.5 - door_w, x0 + 0.5 * box.length - 0.5 * door_w};
  for (int side : {-1, 1}) {
    for (double x = x0 + 0.4; x + 1.1 < x1 - 0.3; x += 1.35) {
      pane(b, vehicle_glass(), 2 * side, yc + side * w, x, x + 1.2, win_low, win_high);
    }
    if (side < 0 || rail) {
      for (const double d : doors) {
        pane(b, vehicle_glass(), 2 * side, yc + side * (w + 0.005), d, d + door_w, floor + 0.05,
             win_high);
      }
    }
  }
  lamps_front(b, x1, yc, w, floor + 0.35, 1.0);
  lamps_rear(b, x0, yc, w, floor + 0.5);
  b.material(trim_material());
  b.box({x1 - 0.06, yc - w + 0.04, floor}, {x1 + 0.03, yc + w - 0.04, floor + 0.25});
  b.box({x0 - 0.03, yc - w + 0.04, floor}, {x0 + 0.06, yc + w - 0.04, floor + 0.25});
  if (!rail) {
    add_plate(b, x1 + 0.03, yc, floor + 0.12, 1, rng);
    add_plate(b, x0 - 0.03, yc, floor + 0.12, -1, rng);
  }
  out.bones = 1;
  const double radius = rail ? 0.42 : std::clamp(0.16 * box.height, 0.42, 0.52);
  if (rail) {
    // Bogies under each end, their wheels hidden behind skirts but turning.
    b.material(trim_material());
    for (double xb : {x0 + 2.5, x1 - 2.5}) {
      b.box({xb - 1.3, yc - w + 0.25, zb + 0.1}, {xb + 1.3, yc + w - 0.25, floor});
    }
    add_axles(b, out, {x0 + 1.8, x0 + 3.2, x1 - 3.2, x1 - 1.8}, yc, w - 0.2, zb, radius, 1e9,
              {false, false, false, false});
  } else {
    const double front = x1 - 2.5;
    const double rear = (0.0 > x0 + 1.5 && 0.0 < x1 - 4.0) ? 0.0 : x0 + 0.3 * box.length;
    std::vector<double> axles = {front, rear};
    std::vector<bool> twin = {false, true};
    if (box.length > 13.5) {
      axles.push_back(rear - 1.4);
      twin.push_back(false);
    }
    add_axles(b, out, axles, yc, w, zb, radius, front, twin);
    out.wheelbase = front - rear;
  }
  out.mesh = b.take();
  return out;
}

}  // namespace corsa::sensors::detail
