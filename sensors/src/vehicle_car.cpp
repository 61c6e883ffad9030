// Cars, SUVs, vans and pickups: a body lofted from a side profile (bonnet, windscreen, roof,
// rear window, boot) and a plan-view taper, with tumblehome above the belt line, wheel arches
// cut into its sides, glazing cut out of the greenhouse, and add-on lamps, grille, bumpers,
// mirrors and plates. Everything is scaled to the entity's bounding box.

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "scalar_math.h"
#include "vehicle_generators.h"
#include "vehicle_parts.h"

namespace corsa::sensors::detail {
namespace {

using Curve = std::vector<std::array<double, 2>>;

double interpolate(const Curve& c, double x) {
  if (x <= c.front()[0]) {
    return c.front()[1];
  }
  for (size_t i = 1; i < c.size(); ++i) {
    if (x <= c[i][0]) {
      const double t = (x - c[i - 1][0]) / (c[i][0] - c[i - 1][0]);
      return c[i - 1][1] + t * (c[i][1] - c[i - 1][1]);
    }
  }
  return c.back()[1];
}

/// Side profile of a body style, rear (xi = 0) to front (xi = 1); heights as shares of the box.
struct Profile {
  Curve top;                ///< roof and bonnet line
  double belt = 0.6;        ///< window sill
  double clearance = 0.15;  ///< m
  double headlamp = 0.56;   ///< lamp centres
  double taillamp = 0.57;
  double bed_end = 0.0;  ///< pickups: the bed runs from the rear to here
  double nose = 0.16;    ///< plan-view rounding of the front (share of the half width)
  double tail = 0.09;
  double tumble = 0.16;         ///< roof narrower than the belt by this share
  double front_overhang = 0.2;  ///< share of the length
  bool cargo = false;           ///< vans without rear side windows
};

Profile profile_of(CarStyle style, RandomStream& rng) {
  Profile p;
  const double j = rng.uniform(-0.02, 0.02);  // a little variation between models
  switch (style) {
    case CarStyle::kSedan:
      p.top = {{0.0, 0.52},  {0.015, 0.60}, {0.10, 0.63 + j}, {0.17, 0.70},
               {0.28, 0.96}, {0.36, 1.0},   {0.55, 1.0},      {0.62, 0.95},
               {0.73, 0.66}, {0.90, 0.61},  {0.975, 0.55},    {1.0, 0.45}};
      p.belt = 0.60 + j;
      break;
    case CarStyle::kHatchback:
      p.top = {{0.0, 0.50},  {0.012, 0.62}, {0.05, 0.88}, {0.11, 0.98}, {0.18, 1.0}, {0.52, 1.0},
               {0.60, 0.95}, {0.72, 0.66},  {0.92, 0.59}, {0.98, 0.52}, {1.0, 0.42}};
      p.belt = 0.58 + j;
      p.front_overhang = 0.17;
      break;
    case CarStyle::kSuv:
      p.top = {{0.0, 0.50},  {0.01, 0.62}, {0.03, 0.92}, {0.08, 1.0},   {0.58, 1.0},
               {0.64, 0.96}, {0.74, 0.70}, {0.93, 0.66}, {0.985, 0.58}, {1.0, 0.47}};
      p.belt = 0.62 + j;
      p.clearance = 0.2;
      p.headlamp = 0.6;
      p.taillamp = 0.62;
      p.nose = 0.1;
      p.tail = 0.06;
      p.tumble = 0.12;
      break;
    case CarStyle::kVan:
      p.top = {{0.0, 0.25},  {0.005, 0.95}, {0.02, 1.0},   {0.76, 1.0},
               {0.83, 0.93}, {0.90, 0.58},  {0.975, 0.53}, {1.0, 0.40}};
      p.belt = 0.52 + j;
      p.clearance = 0.17;
      p.headlamp = 0.47;
      p.taillamp = 0.42;
      p.nose = 0.1;
      p.tail = 0.03;
      p.tumble = 0.07;
      p.front_overhang = 0.15;
      p.cargo = rng.uniform01() < 0.5;
      break;
    case CarStyle::kPickup:
      p.top = {{0.0, 0.50},  {0.01, 0.58}, {0.36, 0.58}, {0.375, 0.96}, {0.40, 1.0}, {0.58, 1.0},
               {0.64, 0.95}, {0.74, 0.68}, {0.93, 0.64}, {0.985, 0.57}, {1.0, 0.47}};
      p.belt = 0.58;
      p.clearance = 0.22;
      p.headlamp = 0.6;
      p.taillamp = 0.5;
      p.bed_end = 0.36;
      p.nose = 0.1;
      p.tail = 0.04;
      p.tumble = 0.1;
      p.front_overhang = 0.17;
      break;
  }
  return p;
}

/// The body's dimensions and its analytic cross-sections.
struct Body {
  double x0 = 0.0, length = 4.5;  ///< rear end, length (m)
  /// Ends of the bounding box (m): the body stops short of them so that lamps and plates can
  /// stand proud of its rear and front faces and still keep inside the box.
  double box_x0 = 0.0, box_x1 = 4.5;
  double yc = 0.0, hw = 0.9;      ///< centre line, half width of the body
  double box_hw = 1.0;            ///< half width of the box (mirrors reach it)
  double zb = 0.0, height = 1.5;  ///< ground (box bottom), height
  Profile p;
  std::vector<std::array<double, 2>> axles;  ///< (x, wheel radius)

  double xi(double x) const { return (x - x0) / length; }
  double top(double x) const { return zb + height * interpolate(p.top, xi(x)); }
  double half_width(double x) const {
    const double s = xi(x);
    const double front = 1.0 - smoothstep(0.0, 0.09, 1.0 - s);
    const double rear = 1.0 - smoothstep(0.0, 0.07, s);
    return hw * (1.0 - p.nose * front * front - p.tail * rear * rear);
  }
  double bottom_centre(double x) const {
    const double s = xi(x);
    return zb + p.clearance + 0.16 * (1.0 - smoothstep(0.0, 0.05, s)) +
           0.14 * (1.0 - smoothstep(0.0, 0.06, 1.0 - s));
  }
  double side_bottom(double x) const {
    double z = bottom_centre(x) + 0.03;
    for (const auto& a : axles) {
      const double r = a[1] + 0.045;
      const double dx = x - a[0];
      if (std::fabs(dx) < r) {
        z = std::max(z, zb + a[1] + std::sqrt(r * r - dx * dx));
      }
    }
    return z;
  }
  /// The cross-section at x: 18 points (y, z) around, bottom centre first, right side (y < 0)
  /// up to the top centre, then the left side down.
  std::vector<Vec3> ring(double x) const {
    const double zt = top(x);
    const double zbelt = std::min(zb + height * p.belt, zt);
    const double w = half_width(x);
    const double g = std::clamp((zt - zbelt) / (height * (1.0 - p.belt) + 1e-9), 0.0, 1.0);
    const double wt = w * (1.0 - p.tumble * g);
    const double zbc = bottom_centre(x);
    const double zsb = std::min(side_bottom(x), zbelt - 0.02);
    const double z3 = zsb + 0.4 * std::max(0.0, zbelt - zsb);
    const double z5 = zbelt + 0.02 * height * g + 0.002;
    const double z6 = std::max(z5 + 0.002, zt - 0.05 * height * g - 0.002);
    const double z7 = std::max(z6 + 0.001, zt - 0.01 * height);
    const double ztop = std::max(zt, z7 + 0.001);
    const bool bed = p.bed_end > 0.0 && xi(x) < p.bed_end - 0.005 && xi(x) > 0.012;
    const double floor_z = zbc + 0.45;
    std::array<std::array<double, 2>, 9> right = {
        {{-0.80 * w, zbc},
         {-0.96 * w, zsb + 0.04},
         {-w, z3},
         {-w, zbelt},
         {-(w - 0.15 * (w - wt)), z5},
         {-wt, z6},
         {-0.88 * wt, z7},
         {bed ? -0.80 * wt : -0.5 * wt, bed ? floor_z : ztop},
         {0.0, bed ? floor_z : ztop}}};
    if (bed) {
      right[6] = {-0.86 * wt, z7};
    }
    std::vector<Vec3> out;
    out.push_back({x, yc, zbc});
    for (const auto& q : right) {
      out.push_back({x, yc + q[0], q[1]});
    }
    for (int i = 7; i >= 0; --i) {
      out.push_back({x, yc - right[i][0], right[i][1]});
    }
    return out;
  }
  /// Half width of the section at x at height z (0 outside it).
  double width_at(double x, double z) const {
    const std::vector<Vec3> r = ring(x);
    // Right side: points 0..9 going up (y < 0).
    for (size_t i = 0; i + 1 < 10; ++i) {
      const Vec3 a = r[i];
      const Vec3 b = r[i + 1];
      if ((z >= a.z && z <= b.z) || (z <= a.z && z >= b.z)) {
        const double t = std::fabs(b.z - a.z) < 1e-9 ? 0.0 : (z - a.z) / (b.z - a.z);
        return std::fabs((a.y + t * (b.y - a.y)) - yc);
      }
    }
    return 0.0;
  }
  /// The body surface at (y, z) seen from the front (facing +1) or the rear (-1): the x where
  /// the section first covers the point.
  double surface_x(double y, double z, int facing) const {
    const double step = 0.005;
    const double start = facing > 0 ? x0 + length : x0;
    for (double d = 0.0; d < 0.5 * length; d += step) {
      const double x = start - facing * d;
      if (width_at(x, z) >= std::fabs(y - yc)) {
        return x;
      }
    }
    return start - facing * 0.5 * length;
  }
};

void add_body(MeshBuilder& b, const Body& body, CarStyle style, const Material& paint) {
  const int stations = std::max(48, static_cast<int>(body.length / 0.075));
  std::vector<std::vector<Vec3>> rings;
  for (int i = 0; i <= stations; ++i) {
    rings.push_back(body.ring(body.x0 + body.length * i / stations));
  }
  b.material(paint);
  const size_t first = b.triangle_count();
  b.loft(rings, true);
  // Greenhouse extent (where the roof stands well above the belt line).
  double gs = 1.0, ge = 0.0;
  for (int i = 0; i <= 200; ++i) {
    const double s = i / 200.0;
    if (interpolate(body.p.top, s) > body.p.belt + 0.12 &&
        !(body.p.bed_end > 0.0 && s < body.p.bed_end)) {
      gs = std::min(gs, s);
      ge = std::max(ge, s);
    }
  }
  const double b_pillar = 0.5 * (gs + ge) + 0.04;
  const ArticulatedMesh& m = b.mesh();
  for (size_t t = first; t < b.triangle_count(); ++t) {
    const auto& tri = m.triangles[t];
    const Vec3 a = m.vertices[tri[0]], c1 = m.vertices[tri[1]], c2 = m.vertices[tri[2]];
    const Vec3 c = (a + c1 + c2) * (1.0 / 3.0);
    const Vec3 n = normalized(cross(c1 - a, c2 - a));
    const double s = body.xi(c.x);
    const double zeta = (c.z - body.zb) / body.height;
    const double top = interpolate(body.p.top, s);
    if (n.z < -0.5 && zeta < 0.35) {
      b.set_material(t, trim_material());
      continue;
    }
    if (zeta < body.p.belt + 0.015 || s < gs - 0.03 || s > ge + 0.03) {
      continue;
    }
    const double w = body.half_width(c.x);
    const double off = std::fabs(c.y - body.yc);
    if (std::fabs(n.y) > 0.6) {
      // Side windows: below the roof rail, between the pillars.
      bool glass = top > body.p.belt + 0.1 && zeta < top - 0.025 && s > gs + 0.025 &&
                   s < ge - 0.02 && std::fabs(s - b_pillar) > 0.013;
      if (style == CarStyle::kVan && body.p.cargo) {
        glass = glass && s > 0.74;
      }
      if (glass) {
        b.set_material(t, vehicle_glass());
      }
    } else if (std::fabs(n.x) > 0.3 && n.z < 0.92 && zeta > body.p.belt + 0.04) {
      // Windscreen and rear window: the sloped top between the pillars.
      const bool front = s > 0.5;
      if (off < (front ? 0.86 : 0.82) * w) {
        b.set_material(t, vehicle_glass());
      }
    }
  }
}

/// Lamps, grille, bumpers, plates and mirrors on the body's surface.
void add_details(MeshBuilder& b, const Body& body, RandomStream& rng) {
  const double hw = body.hw;
  const double yc = body.yc;
  auto lamp = [&](const Material& mat, double y0, double y1, double z, double size_z, int facing) {
    // Pieces about 15 cm square, each on the surface under it (noses and tails are round).
    const int ny = std::max(1, static_cast<int>(std::ceil(std::fabs(y1 - y0) / 0.15)));
    const int nz = std::max(1, static_cast<int>(std::ceil(size_z / 0.15)));
    for (int k = 0; k < ny; ++k) {
      const double ya = y0 + (y1 - y0) * k / ny;
      const double yb = y0 + (y1 - y0) * (k + 1) / ny;
      for (int m = 0; m < nz; ++m) {
        const double za = z - 0.5 * size_z + size_z * m / nz;
        const double zb = za + size_z / nz;
        double x = facing > 0 ? -1e9 : 1e9;
        for (double y : {ya, yb, 0.5 * (ya + yb)}) {
          for (double zz : {za, zb, 0.5 * (za + zb)}) {
            const double sx = body.surface_x(y, zz, facing);
            x = facing > 0 ? std::max(x, sx) : std::min(x, sx);
          }
        }
        // Proud of the surface by 4 mm, never out of the bounding box.
        const double face = std::clamp(x + facing * 0.004, body.box_x0, body.box_x1);
        add_lamp(b, mat, face, 0.5 * (ya + yb), 0.5 * (za + zb), std::fabs(yb - ya), zb - za,
                 facing);
      }
    }
  };
  const double z_head = body.zb + body.height * body.p.headlamp;
  const double z_tail = body.zb + body.height * body.p.taillamp;
  for (int side : {-1, 1}) {
    const double s = side;
    lamp(headlamp_material(), yc + s * 0.48 * hw, yc + s * 0.86 * hw, z_head, 0.11, 1);
    lamp(indicator_material(side > 0), yc + s * 0.86 * hw, yc + s * 0.95 * hw, z_head, 0.07, 1);
    lamp(brake_lamp_material(), yc + s * 0.62 * hw, yc + s * 0.95 * hw, z_tail + 0.035, 0.07, -1);
    lamp(tail_lamp_material(), yc + s * 0.62 * hw, yc + s * 0.95 * hw, z_tail - 0.035, 0.07, -1);
    lamp(indicator_material(side > 0), yc + s * 0.5 * hw, yc + s * 0.62 * hw, z_tail, 0.07, -1);
    lamp(reversing_lamp_material(), yc + s * 0.42 * hw, yc + s * 0.5 * hw, z_tail - 0.02, 0.05, -1);
  }
  // Grille between the headlamps, lower intake and rear valance.
  Material grille = materials::plain("grille", linear_rgb(30, 30, 32), 0.5);
  grille.pattern = Pattern::kMetalGrid;
  grille.secondary = linear_rgb(6, 6, 7);
  lamp(grille, yc - 0.44 * hw, yc + 0.44 * hw, z_head - 0.03, 0.14, 1);
  const double z_low = body.zb + body.p.clearance + 0.12;
  lamp(trim_material(), yc - 0.8 * hw, yc + 0.8 * hw, z_low, 0.12, 1);
  lamp(trim_material(), yc - 0.85 * hw, yc + 0.85 * hw, z_low - 0.02, 0.1, -1);
  // Plates: front low on the bumper, rear between the tail lamps.
  const double z_front_plate = z_low + 0.14;
  add_plate(b, std::min(body.surface_x(yc + 0.26, z_front_plate, 1) + 0.01, body.box_x1 - 0.012),
            yc, z_front_plate, 1, rng);
  const double z_rear_plate = std::max(z_low + 0.15, z_tail - 0.2);
  add_plate(b, std::max(body.surface_x(yc + 0.26, z_rear_plate, -1) - 0.01, body.box_x0 + 0.012),
            yc, z_rear_plate, -1, rng);
  // Rear windows of steep tails (vans, SUVs, hatchbacks) as panes on the surface: the body's
  // sections there are too coarse to cut them out.
  const double top_rear = body.zb + body.height * interpolate(body.p.top, 0.03);
  const double z_belt = body.zb + body.height * body.p.belt;
  if (body.p.bed_end == 0.0 && top_rear > z_belt + 0.25 * body.height * (1.0 - body.p.belt)) {
    lamp(vehicle_glass(), yc - 0.72 * hw, yc + 0.72 * hw, 0.5 * (z_belt + top_rear) + 0.01,
         top_rear - z_belt - 0.08, -1);
  }
  // Mirrors at the front of the side windows.
  double ws = 1.0;
  for (int i = 200; i >= 0; --i) {
    if (interpolate(body.p.top, i / 200.0) > body.p.belt + 0.12) {
      ws = i / 200.0;
      break;
    }
  }
  const double xm = body.x0 + body.length * (ws - 0.03);
  const double zm = body.zb + body.height * (body.p.belt + 0.06);
  const double wm = body.half_width(xm);
  for (int side : {-1, 1}) {
    b.material(trim_material());
    const double y0 = yc + side * (wm - 0.02);
    const double y1 = yc + side * std::min(wm + 0.2, body.box_hw);
    b.box({xm - 0.08, std::min(y0, y1), zm - 0.06}, {xm + 0.04, std::max(y0, y1), zm + 0.06});
  }
}

}  // namespace

CarStyle car_style_for(engine::EntityCategory category, const engine::Box& box, RandomStream& rng) {
  if (category == engine::EntityCategory::kVan) {
    return CarStyle::kVan;
  }
  const double l = box.length;
  const double h = box.height;
  if (h > 1.9 && l > 4.4) {
    return CarStyle::kVan;
  }
  if (l > 5.0 && rng.uniform01() < 0.5) {
    return CarStyle::kPickup;
  }
  if (h > 1.62) {
    return CarStyle::kSuv;
  }
  if (l < 4.25) {
    return CarStyle::kHatchback;
  }
  return rng.uniform01() < 0.25 ? CarStyle::kHatchback : CarStyle::kSedan;
}

GeneratedVehicle generate_car(CarStyle style, const engine::Box& box, RandomStream& rng) {
  Body body;
  // The body 15 mm short of each end of the box: lamps stand 4 mm and plates 11 mm proud of its
  // end faces (flush with them they would z-fight, or hide inside the body).
  constexpr double kEndInset = 0.015;
  body.box_x0 = box.center_x - 0.5 * box.length;
  body.box_x1 = box.center_x + 0.5 * box.length;
  body.length = std::max(box.length - 2.0 * kEndInset, 0.5 * box.length);
  body.x0 = box.center_x - 0.5 * body.length;
  body.yc = box.center_y;
  // Bounding boxes of cars include the mirrors: the body is a little narrower.
  body.box_hw = 0.5 * box.width;
  body.hw = body.box_hw - std::clamp(0.05 * box.width, 0.0, 0.1);
  body.zb = box.center_z - 0.5 * box.height;
  body.height = box.height;
  body.p = profile_of(style, rng);
  const double radius = std::clamp(0.21 * box.height, 0.27, 0.4);
  // The reference point is the rear axle (OpenSCENARIO 1.2 §6.2 vehicle frame) when it lies
  // where a rear axle can be; otherwise a usual rear overhang.
  const double x_min = body.x0 + 0.12 * body.length;
  const double x_max = body.x0 + 0.32 * body.length;
  const double rear = (0.0 >= x_min && 0.0 <= x_max) ? 0.0 : body.x0 + 0.2 * body.length;
  const double front = body.x0 + body.length * (1.0 - body.p.front_overhang);
  body.axles = {{rear, radius}, {front, radius}};
  Material paint = draw_car_paint(rng);
  MeshBuilder b;
  b.semantic(SemanticClass::kCar);
  add_body(b, body, style, paint);
  add_details(b, body, rng);
  GeneratedVehicle out;
  const double tyre = std::clamp(0.13 * box.width, 0.18, 0.28);
  uint8_t bone = 1;
  for (const auto& axle : body.axles) {
    for (int side : {-1, 1}) {
      WheelSpec w;
      w.centre = {axle[0], body.yc + side * (body.hw - 0.5 * tyre - 0.03), body.zb + radius};
      w.radius = radius;
      w.width = tyre;
      w.steers = axle[0] == front;
      w.bone = bone++;
      add_wheel(b, w, side, 5);
      out.wheels.push_back(w);
    }
  }
  out.mesh = b.take();
  out.wheelbase = front - rear;
  out.bones = bone;
  return out;
}

}  // namespace corsa::sensors::detail
