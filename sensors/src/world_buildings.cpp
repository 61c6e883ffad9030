// Generated buildings along the streets of maps that bring none (WorldOptions::buildings): lots
// of 8-24 m frontage behind the outermost lane (at the back of the sidewalk, or 3-8 m from a
// road without one) on every road outside junctions that is not a motorway, each holding one
// building drawn from the run seed and the road: a terraced house (two to four floors, pitched
// tiled roof, front doors with steps), a block of flats or offices (four to nine floors, shop
// fronts on the ground floor, an entrance, a flat roof with a plant room) or a low shop (one or
// two floors, shop fronts under awnings). Facades are real geometry (facade.h: recessed windows,
// ledges, cornices, balconies, shop fronts) in a style drawn per building, so no two are alike. A
// lot is left empty where it would touch a lane of any road, another building (the map's
// models, its objects or one generated before), a prop, or lie within 12 m of a junction.

#include <algorithm>
#include <array>
#include <cmath>

#include "facade.h"
#include "world_build.h"

namespace corsa::sensors::detail {
namespace {

constexpr double kBuildingJunctionGap = 12.0;  // m kept clear at road ends meeting a junction

enum class Kind { kHouse, kBlock, kShop };

/// A lot's rectangle in the map frame: front corners a (at s0) and b (at s1), depth outward.
struct Lot {
  Vec3 a, b;
  Vec3 out;  ///< unit, horizontal, away from the road
  double depth = 0.0;
  std::array<Vec3, 4> corners() const { return {a, b, b + out * depth, a + out * depth}; }
};

/// Separating-axis test of two convex quads in plan, grown by `slack` metres.
bool overlaps(const std::array<Vec3, 4>& p, const std::array<Vec3, 4>& q, double slack) {
  for (const auto* poly : {&p, &q}) {
    for (size_t i = 0; i < 4; ++i) {
      const Vec3 e = (*poly)[(i + 1) % 4] - (*poly)[i];
      const double len = std::hypot(e.x, e.y);
      if (len < 1e-9) {
        continue;
      }
      const double nx = -e.y / len, ny = e.x / len;
      double p0 = 1e300, p1 = -1e300, q0 = 1e300, q1 = -1e300;
      for (const Vec3& v : p) {
        p0 = std::min(p0, v.x * nx + v.y * ny), p1 = std::max(p1, v.x * nx + v.y * ny);
      }
      for (const Vec3& v : q) {
        q0 = std::min(q0, v.x * nx + v.y * ny), q1 = std::max(q1, v.x * nx + v.y * ny);
      }
      if (p1 + slack <= q0 || q1 + slack <= p0) {
        return false;
      }
    }
  }
  return true;
}

Color jitter(RandomStream& rng, Color c, double amount) {
  const double k = 1.0 + rng.uniform(-amount, amount);
  return Color{c.r * k * rng.uniform(0.97, 1.03), c.g * k, c.b * k * rng.uniform(0.97, 1.03)};
}

/// The wall colour of one building, from its stream.
Color wall_colour(RandomStream& rng) {
  static constexpr std::array<std::array<uint8_t, 3>, 10> kWalls = {{{225, 215, 190},
                                                                     {232, 230, 222},
                                                                     {205, 185, 150},
                                                                     {182, 180, 174},
                                                                     {202, 162, 104},
                                                                     {152, 84, 62},
                                                                     {112, 64, 48},
                                                                     {170, 180, 190},
                                                                     {212, 152, 122},
                                                                     {150, 160, 140}}};
  const auto& w =
      kWalls[static_cast<size_t>(rng.uniform_int(0, static_cast<int64_t>(kWalls.size()) - 1))];
  return jitter(rng, linear_rgb(w[0], w[1], w[2]), 0.08);
}

/// A pitched roof over [0, w] x [0, d dir] from the eaves at `eave` metres, ridge along x.
void add_pitched_roof(MeshBuilder& b, RandomStream& rng, const Material& walls, double w, double d,
                      double dir, double eave) {
  const double rise = 0.5 * d * std::tan(rng.uniform(0.45, 0.7));
  const double o = 0.3;  // overhang of the eaves
  const double y0 = -o * dir, y1 = (d + o) * dir, ym = 0.5 * d * dir;
  const double drop = o * rise / (0.5 * d);
  static constexpr std::array<std::array<uint8_t, 3>, 4> kTiles = {
      {{150, 70, 48}, {84, 80, 80}, {110, 60, 44}, {60, 62, 66}}};
  const auto& t =
      kTiles[static_cast<size_t>(rng.uniform_int(0, static_cast<int64_t>(kTiles.size()) - 1))];
  Material tiles = materials::plain("generated roof tiles", linear_rgb(t[0], t[1], t[2]), 0.75);
  tiles.pattern = Pattern::kPaving;
  tiles.pattern_scale = 0.4;
  tiles.secondary = tiles.base_color * 0.6;
  b.material(tiles);
  const double top = eave + rise;
  // Front and back slopes (wound so that their normals face up and out).
  const auto slope = [&](double ya, double yb) {
    const Vec3 p0{-o, ya, eave - drop}, p1{w + o, ya, eave - drop};
    const Vec3 p2{w + o, yb, top}, p3{-o, yb, top};
    if ((yb - ya) * dir > 0.0) {
      b.polygon({p0, p3, p2, p1}, {});
    } else {
      b.polygon({p0, p1, p2, p3}, {});
    }
  };
  slope(y0, ym);
  slope(y1, ym);
  // Gable walls carry the facade (an attic window row).
  b.material(walls);
  b.polygon({{0, 0, eave}, {0, d * dir, eave}, {0, ym, top}}, {});
  b.polygon({{w, 0, eave}, {w, ym, top}, {w, d * dir, eave}}, {});
}

/// One building filling a lot of frontage `w` and depth `d` (local frame: front face along +x
/// at y = 0, the building towards y dir, ground at z = 0): four facade walls (shop fronts and
/// entrances on the front), a flat roof with a plant room or a pitched roof with gables.
ArticulatedMesh make_building(RandomStream& rng, Kind kind, double w, double d, double dir,
                              uint32_t seed) {
  MeshBuilder b;
  b.semantic(SemanticClass::kBuilding);
  FacadeBrief brief;
  brief.floor_h = rng.uniform(2.8, 3.4);
  const bool shops = kind == Kind::kShop || (kind == Kind::kBlock && rng.uniform01() < 0.6);
  brief.ground_h = shops ? rng.uniform(3.8, 4.6) : 0.0;
  const int floors = kind == Kind::kHouse   ? static_cast<int>(rng.uniform_int(2, 4))
                     : kind == Kind::kBlock ? static_cast<int>(rng.uniform_int(4, 9))
                                            : static_cast<int>(rng.uniform_int(1, 2));
  const double height =
      shops ? brief.ground_h + (floors - 1) * brief.floor_h : floors * brief.floor_h;
  brief.wall = wall_colour(rng);
  brief.flat_roof = kind != Kind::kHouse;
  brief.seed = seed;
  const FacadeStyle style = draw_facade_style(rng, brief);
  // The footprint's corners anticlockwise seen from above (the outside on the right of each
  // wall); the front wall first.
  std::array<Vec3, 4> ring = {Vec3{0.0, 0.0, 0.0}, Vec3{w, 0.0, 0.0}, Vec3{w, d * dir, 0.0},
                              Vec3{0.0, d * dir, 0.0}};
  if (dir < 0.0) {
    ring = {ring[1], ring[0], ring[3], ring[2]};
  }
  for (size_t i = 0; i < 4; ++i) {
    add_facade_wall(b, {.a = ring[i], .b = ring[(i + 1) % 4], .height = height, .street = i == 0},
                    style, rng);
  }
  if (kind == Kind::kHouse) {
    add_pitched_roof(b, rng, style.plaster, w, d, dir, height);
  } else {
    Material roof = materials::plain("generated flat roof", linear_rgb(90, 90, 90), 0.95);
    roof.pattern = Pattern::kRoof;
    roof.seed = seed;
    b.material(roof);
    std::vector<Vec3> top;
    for (const Vec3& c : ring) {
      top.push_back(c + Vec3{0.0, 0.0, height});
    }
    b.polygon(top, {});
    if (kind == Kind::kBlock && w > 8.0 && d > 8.0) {
      b.material(style.plaster);
      const double cx = rng.uniform(0.3, 0.7) * w, cy = rng.uniform(0.35, 0.65) * d * dir;
      b.box({cx - 2.0, cy - 2.0, height}, {cx + 2.0, cy + 2.0, height + rng.uniform(2.0, 3.0)});
    }
  }
  return b.take();
}

}  // namespace

void build_buildings(WorldBuild& w) {
  const xodr::Map& map = w.map;
  std::vector<xodr::LaneSpan> spans;
  std::vector<std::array<Vec3, 4>> built;
  xodr::LocateOptions on_lane;
  on_lane.max_distance = 0.5;
  for (size_t r = 0; r < map.road_count(); ++r) {
    const xodr::Road& road = map.road(r);
    if (road.in_junction() || road.length < 20.0) {
      continue;
    }
    for (int side : {1, -1}) {
      RandomStream rng(
          derive_seed(w.options.seed, "buildings " + road.id + (side > 0 ? " left" : " right")));
      double s = rng.uniform(0.0, 4.0);
      while (s < road.length) {
        // Every draw of a lot is taken before any test, so one lot's fate never shifts the next.
        const double frontage = rng.uniform(8.0, 24.0);
        const double gap = rng.uniform(0.5, 5.0);
        const double depth = rng.uniform(9.0, 18.0);
        const double pick = rng.uniform01();
        const double setback_walk = rng.uniform(0.3, 2.5);
        const double setback_verge = rng.uniform(3.0, 8.0);
        RandomStream look(rng.next_u64());
        const double s0 = s, s1 = s + frontage;
        s = s1 + gap;
        if (s1 > road.length || next_to_junction(map, r, s0, kBuildingJunctionGap) ||
            next_to_junction(map, r, s1, kBuildingJunctionGap) ||
            motorway_at(road, 0.5 * (s0 + s1))) {
          continue;
        }
        const Edge e0 = edge_at(map, r, s0, side, spans);
        const Edge e1 = edge_at(map, r, s1, side, spans);
        if (!e0.valid || !e1.valid) {
          continue;
        }
        const double setback = e0.sidewalk && e1.sidewalk ? setback_walk : setback_verge;
        const xodr::WorldPose a = map.world_pose(r, s0, e0.t_outer + side * setback);
        const xodr::WorldPose b = map.world_pose(r, s1, e1.t_outer + side * setback);
        Lot lot;
        lot.a = {a.x, a.y, a.z};
        lot.b = {b.x, b.y, b.z};
        const double len = std::hypot(b.x - a.x, b.y - a.y);
        if (len < 6.0) {
          continue;
        }
        // Away from the road: right of a -> b on the right side, left of it on the left.
        lot.out = Vec3{-(b.y - a.y) / len, (b.x - a.x) / len, 0.0} * static_cast<double>(side);
        lot.depth = depth;
        const auto quad = lot.corners();
        bool free = true;
        for (int i = 0; i <= 4 && free; ++i) {
          for (int j = 0; j <= 4 && free; ++j) {
            const Vec3 p = lot.a + (lot.b - lot.a) * (i / 4.0) + lot.out * (depth * j / 4.0);
            free = !map.locate(p.x, p.y, on_lane) && !w.under_building(p.x, p.y, p.z) &&
                   w.clear_of_props(p.x, p.y, 0.5);
          }
        }
        for (const auto& other : built) {
          free = free && !overlaps(quad, other, 0.3);
        }
        if (!free) {
          continue;
        }
        const Kind kind = pick < 0.45 ? Kind::kHouse : pick < 0.8 ? Kind::kBlock : Kind::kShop;
        // Local frame: x along the front from a, y to the left; the building lies towards
        // y = side (left of the front on the left side of the road, right of it on the right).
        const double heading = std::atan2(b.y - a.y, b.x - a.x);
        const double base = std::min(a.z, b.z);
        const auto seed = static_cast<uint32_t>(look.next_u64());
        ObjectInfo info;
        info.kind = "building";
        w.place(make_building(look, kind, len, depth, static_cast<double>(side), seed),
                rigid_from_pose(a.x, a.y, base, heading, 0.0, 0.0), "building " + road.id, info);
        built.push_back(quad);
        ++w.report.buildings;
      }
    }
  }
}

}  // namespace corsa::sensors::detail
