// Facades in real geometry: a building's style drawn from its stream, and the walls it dresses.
// A wall is laid out in its own frame (x along the wall from its first corner, y into the
// building, z up from its base; the street is at -y): corner piers, a ground floor (shop fronts
// with recessed glazing under sign bands and awnings, or windows and doors), upper floors of
// recessed windows (reveals, sills, a pane set back by the recess) with a different top floor,
// optional string courses, pilasters and balconies stacked in the same bays, and a cornice and
// parapet at the top. Openings cut the wall into pieces, so nothing overlaps the panes.

#include "facade.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace corsa::sensors::detail {
namespace {

/// A quad p, p + e1, p + e1 + e2, p + e2 facing e1 x e2.
void facade_quad(MeshBuilder& b, Vec3 p, Vec3 e1, Vec3 e2) {
  b.quad(b.vertex(p), b.vertex(p + e1), b.vertex(p + e1 + e2), b.vertex(p + e2));
}

/// The wall plane (y = 0, facing the street) over [x0, x1] x [z0, z1].
void wall_piece(MeshBuilder& b, double x0, double x1, double z0, double z1) {
  if (x1 - x0 > 1e-6 && z1 - z0 > 1e-6) {
    facade_quad(b, {x0, 0.0, z0}, {x1 - x0, 0.0, 0.0}, {0.0, 0.0, z1 - z0});
  }
}

/// A box standing proud of the wall (its back face, against the wall at y = hi.y, left out).
void proud_box(MeshBuilder& b, Vec3 lo, Vec3 hi) {
  uint32_t v[8];
  for (int i = 0; i < 8; ++i) {
    v[i] = b.vertex({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  }
  // MeshBuilder::box's faces (counter-clockwise seen from outside) but the one at y = hi.y.
  const int faces[5][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    b.quad(v[f[0]], v[f[1]], v[f[2]], v[f[3]]);
  }
}

/// A window or door cut into the wall: [x0, x1] x [z0, z1], its pane `depth` metres in.
struct FacadeOpening {
  double x0 = 0.0, x1 = 0.0, z0 = 0.0, z1 = 0.0;
  double depth = 0.2;
  const Material* pane = nullptr;
  int column = 0;  ///< the pane's uv cell: which window it is (curtains, lit rooms)
  int row = 0;
  bool sill = true;
};

/// The reveals (left, right, head, bottom) in the wall's material, the pane with its uv cell,
/// and a sill.
void add_opening(MeshBuilder& b, const FacadeOpening& o, const FacadeStyle& s,
                 const Material& wall) {
  const double w = o.x1 - o.x0, h = o.z1 - o.z0, d = o.depth;
  b.material(wall);
  facade_quad(b, {o.x0, 0.0, o.z0}, {0.0, d, 0.0}, {0.0, 0.0, h});
  facade_quad(b, {o.x1, 0.0, o.z0}, {0.0, 0.0, h}, {0.0, d, 0.0});
  facade_quad(b, {o.x0, 0.0, o.z1}, {0.0, d, 0.0}, {w, 0.0, 0.0});
  facade_quad(b, {o.x0, 0.0, o.z0}, {w, 0.0, 0.0}, {0.0, d, 0.0});
  b.material(*o.pane);
  const auto u0 = static_cast<float>(o.column), v0 = static_cast<float>(o.row);
  b.quad(b.vertex({o.x0, d, o.z0}, u0, v0), b.vertex({o.x1, d, o.z0}, u0 + 1.0f, v0),
         b.vertex({o.x1, d, o.z1}, u0 + 1.0f, v0 + 1.0f), b.vertex({o.x0, d, o.z1}, u0, v0 + 1.0f));
  if (o.sill) {
    b.material(s.trim);
    proud_box(b, {o.x0 - 0.06, -0.07, o.z0 - 0.06}, {o.x1 + 0.06, 0.0, o.z0});
  }
}

/// The wall over [0, length] x [z0, z1] less the openings (in order along x, inside the band):
/// horizontal slabs between the openings' sills and heads, each cut only where an opening
/// crosses it, so a storey of equal windows is a few long quads.
void cut_wall(MeshBuilder& b, double length, double z0, double z1,
              const std::vector<FacadeOpening>& openings) {
  std::vector<double> levels = {z0, z1};
  for (const FacadeOpening& o : openings) {
    levels.push_back(o.z0);
    levels.push_back(o.z1);
  }
  std::sort(levels.begin(), levels.end());
  levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
  for (size_t k = 0; k + 1 < levels.size(); ++k) {
    const double lo = levels[k], hi = levels[k + 1];
    double x = 0.0;
    for (const FacadeOpening& o : openings) {
      if (o.z0 <= lo && o.z1 >= hi) {
        wall_piece(b, x, o.x0, lo, hi);
        x = o.x1;
      }
    }
    wall_piece(b, x, length, lo, hi);
  }
}

/// A balcony in front of [x0, x1] at floor level z: a slab and a railing on three sides.
void add_balcony(MeshBuilder& b, double x0, double x1, double z, double depth,
                 const FacadeStyle& s) {
  b.material(s.trim);
  proud_box(b, {x0, -depth, z - 0.16}, {x1, 0.0, z});
  b.material(s.railing);
  b.box({x0, -depth, z}, {x1, -depth + 0.04, z + 1.0});
  b.box({x0, -depth + 0.04, z}, {x0 + 0.04, 0.0, z + 1.0});
  b.box({x1 - 0.04, -depth + 0.04, z}, {x1, 0.0, z + 1.0});
}

/// How a wall's length splits: corner piers of `margin` and `count` bays of `width`.
struct BayLayout {
  double margin = 0.0;
  int count = 0;
  double width = 0.0;
  double x0(int i) const { return margin + i * width; }
};

BayLayout lay_out_bays(double length, double bay) {
  BayLayout l;
  l.margin = std::clamp(0.08 * length, 0.4, 1.0);
  l.count = std::max(1, static_cast<int>(std::lround((length - 2.0 * l.margin) / bay)));
  l.width = (length - 2.0 * l.margin) / l.count;
  return l;
}

/// What one wall gets, drawn once per wall so that storeys stack (balconies in the same bays).
struct WallPlan {
  BayLayout bays;
  double ground_h = 0.0;
  int upper_floors = 0;
  double top = 0.0;           ///< height of the wall (the parapet rises above)
  std::vector<char> balcony;  ///< per bay
  std::vector<char> door;     ///< per bay, ground floor
  std::vector<int> shop;      ///< per bay: which shop unit (sign colour), ground floor
  int column_base = 0;        ///< the panes' uv columns start here (windows differ per wall)
};

WallPlan plan_wall(double length, double height, const FacadeWall& wall, const FacadeStyle& s,
                   RandomStream& rng) {
  WallPlan p;
  p.bays = lay_out_bays(length, s.bay);
  p.top = height;
  p.ground_h = std::min(s.ground_h, height);
  p.upper_floors =
      std::max(0, static_cast<int>(std::floor((height - p.ground_h) / s.floor_h + 0.05)));
  const auto n = static_cast<size_t>(p.bays.count);
  p.balcony.assign(n, 0);
  p.door.assign(n, 0);
  p.shop.assign(n, 0);
  p.column_base = static_cast<int>(rng.uniform_int(0, 200));
  for (size_t i = 0; i < n; ++i) {
    p.balcony[i] = rng.uniform01() < s.balconies ? 1 : 0;
  }
  if (wall.street && length >= 4.0) {
    // Entrances: one per shop unit of one to three bays, or one per 8 m of housing.
    const int doors = s.shops ? 0 : std::max(1, static_cast<int>(length / 8.0));
    for (int k = 0; k < doors; ++k) {
      p.door[static_cast<size_t>((k + 0.5) * p.bays.count / doors)] = 1;
    }
    int unit = 0;
    for (size_t i = 0; i < n;) {
      const auto size = static_cast<size_t>(rng.uniform_int(1, 3));
      const size_t door =
          i + static_cast<size_t>(rng.uniform_int(0, static_cast<int64_t>(size) - 1));
      for (size_t j = i; j < std::min(n, i + size); ++j) {
        p.shop[j] = unit;
      }
      if (s.shops && door < n) {
        p.door[door] = 1;
      }
      i += size;
      ++unit;
    }
  }
  return p;
}

/// The ground floor as shop fronts: piers, stall risers, recessed glazing, doors, sign bands and
/// awnings per shop unit.
void add_shop_fronts(MeshBuilder& b, const WallPlan& p, const FacadeStyle& s, double length,
                     RandomStream& rng) {
  const double g = p.ground_h;
  const double fascia_h = std::min(0.7, 0.18 * g);
  const double glass_top = g - fascia_h - 0.35;
  const double pier = 0.45;
  std::vector<FacadeOpening> openings;
  for (int i = 0; i < p.bays.count; ++i) {
    const auto k = static_cast<size_t>(i);
    const double bx0 = p.bays.x0(i), bx1 = bx0 + p.bays.width;
    openings.push_back({.x0 = bx0 + 0.5 * pier,
                        .x1 = bx1 - 0.5 * pier,
                        .z0 = p.door[k] ? 0.0 : 0.55,
                        .z1 = glass_top,
                        .depth = 0.3,
                        .pane = p.door[k] ? &s.door : &s.shop_glazing,
                        .column = p.column_base + i,
                        .row = 0,
                        .sill = false});
  }
  b.material(s.base);
  cut_wall(b, length, -0.3, g, openings);
  for (const FacadeOpening& o : openings) {
    add_opening(b, o, s, s.base);
  }
  // Sign bands and awnings, one per unit.
  int first = 0;
  while (first < p.bays.count) {
    int last = first;
    while (last + 1 < p.bays.count &&
           p.shop[static_cast<size_t>(last + 1)] == p.shop[static_cast<size_t>(first)]) {
      ++last;
    }
    const double x0 = p.bays.x0(first) + 0.1, x1 = p.bays.x0(last + 1) - 0.1;
    const auto colour = static_cast<size_t>(rng.uniform_int(0, 2));
    b.material(s.fascia[colour]);
    proud_box(b, {x0, -0.12, glass_top + 0.1}, {x1, 0.0, glass_top + 0.1 + fascia_h});
    if (rng.uniform01() < 0.4) {
      const double reach = rng.uniform(0.9, 1.4), drop = 0.45, z = glass_top + 0.05;
      b.material(s.awning);
      facade_quad(b, {x0, 0.0, z}, {0.0, -reach, -drop}, {x1 - x0, 0.0, 0.0});
      facade_quad(b, {x0, -reach, z - drop - 0.25}, {x1 - x0, 0.0, 0.0}, {0.0, 0.0, 0.25});
    }
    first = last + 1;
  }
}

/// One storey [z0, z1] (row `row`) of windows, with doors on the ground floor and balconies
/// in the plan's bays; its wall reaches down to `bottom` (below the ground for the ground floor).
void add_storey(MeshBuilder& b, const WallPlan& p, const FacadeStyle& s, double length,
                double bottom, double z0, double z1, int row, const Material& pane,
                double window_h) {
  const bool ground = row == 0;
  // The cornice covers the top of the wall: the top storey's windows stay below it.
  const double clear = z1 >= p.top - 1e-9 ? s.cornice : 0.0;
  const double sill = std::min(s.sill_z, std::max(0.3, z1 - z0 - window_h - 0.3));
  const double head = std::min(z0 + sill + window_h, z1 - clear - 0.25);
  std::vector<FacadeOpening> openings;
  std::vector<FacadeOpening> doors, balconies;  // with a step, with a balcony
  for (int i = 0; i < p.bays.count; ++i) {
    const auto k = static_cast<size_t>(i);
    const double cx = p.bays.x0(i) + 0.5 * p.bays.width;
    const double ww = std::min(s.window_w, p.bays.width - 0.5);
    FacadeOpening o{.x0 = cx - 0.5 * ww,
                    .x1 = cx + 0.5 * ww,
                    .z0 = z0 + sill,
                    .z1 = head,
                    .depth = s.recess,
                    .pane = &pane,
                    .column = p.column_base + i,
                    .row = row,
                    .sill = true};
    const bool door = ground && p.door[k];
    const bool balcony = !ground && p.balcony[k] && row < p.upper_floors;
    if (door) {
      const double dw = std::min(1.2, p.bays.width - 0.5);
      o = {.x0 = cx - 0.5 * dw,
           .x1 = cx + 0.5 * dw,
           .z0 = z0 + 0.16,
           .z1 = std::min(z0 + 2.3, z1 - 0.3),
           .depth = 0.25,
           .pane = &s.door,
           .column = o.column,
           .row = row,
           .sill = false};
    } else if (balcony) {
      o.z0 = z0;
      o.sill = false;
    }
    if (o.z1 - o.z0 < 0.5 || o.x1 - o.x0 < 0.3) {
      continue;  // no room for it: plain wall
    }
    openings.push_back(o);
    if (door) {
      doors.push_back(o);
    } else if (balcony) {
      balconies.push_back(o);
    }
  }
  const Material& wall = ground ? s.base : s.plaster;
  b.material(wall);
  cut_wall(b, length, bottom, z1, openings);
  for (const FacadeOpening& o : openings) {
    add_opening(b, o, s, wall);
  }
  b.material(s.trim);
  for (const FacadeOpening& o : doors) {  // a step up to each
    proud_box(b, {o.x0 - 0.2, -0.45, bottom}, {o.x1 + 0.2, 0.0, o.z0});
  }
  const double half = 0.5 * p.bays.width - 0.15;
  for (const FacadeOpening& o : balconies) {
    const double cx = 0.5 * (o.x0 + o.x1);
    add_balcony(b, cx - half, cx + half, z0, 1.1, s);
  }
}

/// The string course over the ground floor (in the trim), string courses at the floors,
/// pilasters, cornice and parapet.
void add_mouldings(MeshBuilder& b, const WallPlan& p, const FacadeStyle& s, double length) {
  const double g = p.ground_h;
  b.material(s.trim);
  if (p.upper_floors > 0) {
    proud_box(b, {0.0, -0.1, g - 0.12}, {length, 0.0, g + 0.08});  // over the ground floor
  }
  // String courses, pilasters and the cornice are rendered like the wall (their folds are no
  // anti-aliasing edges; the sun and shade draw them).
  b.material(s.plaster);
  if (s.ledges) {
    for (int k = 1; k < p.upper_floors; ++k) {
      const double z = g + k * s.floor_h;
      proud_box(b, {0.0, -0.06, z - 0.1}, {length, 0.0, z + 0.02});
    }
  }
  if (s.pilasters && p.upper_floors > 0) {
    const double half = std::min(0.2, 0.25 * (p.bays.width - s.window_w));
    for (int i = 0; i <= p.bays.count && half > 0.05; ++i) {
      const double x = p.bays.x0(i);
      proud_box(b, {x - half, -0.12, g + 0.08}, {x + half, 0.0, p.top - s.cornice});
    }
  }
  if (s.cornice > 0.0) {
    const double reach = 0.6 * s.cornice;
    proud_box(b, {-reach, -reach, p.top - s.cornice}, {length + reach, 0.0, p.top});
  }
  if (s.parapet > 0.0) {
    b.box({0.0, 0.0, p.top}, {length, 0.25, p.top + s.parapet});
    b.material(s.trim);
    b.box({-0.04, -0.04, p.top + s.parapet}, {length + 0.04, 0.29, p.top + s.parapet + 0.06});
  }
}

Material glazing_material(std::string name, Color frame, double w, double h, double mullions,
                          double transom, uint32_t seed) {
  Material m = materials::plain(std::move(name), Color{0.03, 0.035, 0.04}, 0.04);
  m.pattern = Pattern::kGlazing;
  m.params = {w, h, mullions, transom};
  m.secondary = frame;
  m.seed = seed;
  return m;
}

template <size_t N>
Color pick_colour(RandomStream& rng, const std::array<std::array<uint8_t, 3>, N>& palette) {
  const auto& c = palette[static_cast<size_t>(rng.uniform_int(0, static_cast<int64_t>(N) - 1))];
  return linear_rgb(c[0], c[1], c[2]);
}

/// The style's materials: walls, trim, frames, panes, doors, signs.
void draw_facade_materials(RandomStream& rng, const FacadeBrief& brief, FacadeStyle& s) {
  static constexpr std::array<std::array<uint8_t, 3>, 6> kStones = {{{70, 68, 66},
                                                                     {196, 186, 166},
                                                                     {120, 112, 104},
                                                                     {40, 40, 42},
                                                                     {168, 160, 150},
                                                                     {150, 96, 70}}};
  static constexpr std::array<std::array<uint8_t, 3>, 5> kTrims = {
      {{226, 222, 212}, {180, 176, 168}, {120, 116, 110}, {204, 190, 160}, {90, 88, 86}}};
  static constexpr std::array<std::array<uint8_t, 3>, 6> kFrames = {
      {{235, 235, 230}, {50, 52, 54}, {90, 60, 40}, {40, 70, 55}, {150, 150, 148}, {120, 40, 35}}};
  static constexpr std::array<std::array<uint8_t, 3>, 7> kSigns = {{{170, 30, 30},
                                                                    {30, 80, 60},
                                                                    {30, 50, 120},
                                                                    {220, 170, 40},
                                                                    {30, 30, 32},
                                                                    {230, 230, 225},
                                                                    {200, 90, 30}}};
  static constexpr std::array<std::array<uint8_t, 3>, 5> kAwnings = {
      {{150, 30, 30}, {30, 80, 60}, {40, 50, 110}, {200, 160, 60}, {60, 60, 62}}};
  const uint32_t seed = brief.seed;
  s.plaster = materials::plain("facade plaster", brief.wall, 0.85);
  s.plaster.pattern = Pattern::kPlaster;
  s.plaster.seed = seed;
  s.base = s.plaster;
  s.base.name = "facade ground floor";
  if (s.shops || rng.uniform01() < 0.5) {
    s.base.base_color = pick_colour(rng, kStones);
  } else {
    s.base.base_color = brief.wall * 0.8;
  }
  s.trim = materials::plain("facade trim", pick_colour(rng, kTrims), 0.8);
  // Balcony fronts: a solid parapet in the wall's colour, a painted panel or dark metal.
  const double railing = rng.uniform01();
  s.railing = railing < 0.45  ? materials::plain("balcony parapet", brief.wall * 0.95, 0.85)
              : railing < 0.7 ? materials::plain("balcony panel", linear_rgb(214, 214, 208), 0.6)
                              : materials::metal("balcony railing", linear_rgb(70, 72, 74), 0.5);
  const Color frame = pick_colour(rng, kFrames);
  const double mullions = static_cast<double>(rng.uniform_int(0, 2));
  const double transom = rng.uniform01() < 0.4 ? rng.uniform(0.22, 0.32) : 0.0;
  s.glazing =
      glazing_material("facade window", frame, s.window_w, s.window_h, mullions, transom, seed);
  s.top_glazing = glazing_material("facade top window", frame, s.window_w,
                                   s.window_h * s.top_window_scale, mullions, 0.0, seed);
  s.shop_glazing = glazing_material("facade shop window", pick_colour(rng, kFrames), s.bay, 2.6,
                                    0.0, 0.15, seed ^ 0x5409u);
  const bool dark_door = !s.shops && rng.uniform01() < 0.7;
  s.door = dark_door
               ? materials::plain("facade door", pick_colour(rng, kStones) * 0.6, 0.5)
               : glazing_material("facade glazed door", frame, 1.2, 2.3, 1.0, 0.0, seed ^ 0xD0u);
  for (int k = 0; k < 3; ++k) {
    s.fascia[k] =
        materials::plain("facade sign " + std::to_string(k), pick_colour(rng, kSigns), 0.6);
  }
  s.awning = materials::plain("facade awning", pick_colour(rng, kAwnings), 0.9);
}

}  // namespace

FacadeStyle draw_facade_style(RandomStream& rng, const FacadeBrief& brief) {
  FacadeStyle s;
  s.floor_h = brief.floor_h > 0.0 ? brief.floor_h : rng.uniform(2.9, 3.5);
  const double shop_draw = rng.uniform01();
  s.shops = brief.ground_h > 0.0 || (brief.ground_h < 0.0 && shop_draw < 0.6);
  s.ground_h = !s.shops ? s.floor_h : brief.ground_h > 0.0 ? brief.ground_h : rng.uniform(3.8, 4.6);
  s.bay = rng.uniform(2.4, 4.0);
  s.window_w = s.bay * rng.uniform(0.35, 0.62);
  s.window_h = s.floor_h * rng.uniform(0.4, 0.58);
  s.sill_z = std::min(rng.uniform(0.7, 1.0), s.floor_h - s.window_h - 0.3);
  const double top = rng.uniform01();
  s.top_window_scale = top < 0.35 ? rng.uniform(0.55, 0.8) : 1.0;
  s.first_window_scale = rng.uniform01() < 0.3 ? rng.uniform(1.08, 1.2) : 1.0;
  s.recess = rng.uniform(0.12, 0.3);
  s.ledges = rng.uniform01() < 0.45;
  s.pilasters = rng.uniform01() < 0.2;
  const double balconies = rng.uniform01();
  s.balconies = balconies < 0.3 ? rng.uniform(0.3, 1.0) : 0.0;
  const double cornice = rng.uniform(0.3, 0.7);
  const double parapet = rng.uniform(0.4, 1.0);
  const double roof_draw = rng.uniform01();
  s.cornice = brief.flat_roof && roof_draw < 0.7 ? cornice : 0.0;
  s.parapet = brief.flat_roof && roof_draw > 0.15 ? parapet : 0.0;
  draw_facade_materials(rng, brief, s);
  return s;
}

void add_facade_wall(MeshBuilder& b, const FacadeWall& wall, const FacadeStyle& s,
                     RandomStream& rng) {
  const Vec3 e = wall.b - wall.a;
  const double length = std::hypot(e.x, e.y);
  const Rigid outer = b.transform();
  b.transform(outer *
              rigid_from_pose(wall.a.x, wall.a.y, wall.a.z, std::atan2(e.y, e.x), 0.0, 0.0));
  const WallPlan p = plan_wall(length, wall.height, wall, s, rng);
  // The ground floor (its wall reaching 0.3 m below the ground), the upper storeys, the top one
  // up to the top of the wall.
  const double g = p.ground_h;
  if (s.shops && wall.street) {
    add_shop_fronts(b, p, s, length, rng);
  } else {
    add_storey(b, p, s, length, -0.3, 0.0, g, 0, s.glazing, s.window_h);
  }
  double z = g;
  for (int k = 1; k <= p.upper_floors; ++k) {
    const bool top = k == p.upper_floors;
    const double z1 = top ? p.top : z + s.floor_h;
    const double scale = top ? s.top_window_scale : k == 1 ? s.first_window_scale : 1.0;
    add_storey(b, p, s, length, z, z, z1, k, top ? s.top_glazing : s.glazing, s.window_h * scale);
    z = z1;
  }
  if (p.upper_floors == 0 && g < p.top) {
    b.material(s.plaster);
    wall_piece(b, 0.0, length, g, p.top);
  }
  add_mouldings(b, p, s, length);
  b.transform(outer);
}

}  // namespace corsa::sensors::detail
