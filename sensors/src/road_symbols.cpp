// Symbols painted on the road: arrows built from strokes and triangular heads, block letters
// from a 5 x 7 cell font (each run of filled cells in a row is one rectangle), hatched areas as
// stripes clipped to their box (Sutherland-Hodgman against the box's four edges).

#include "road_symbols.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "corsa/sensors/material.h"
#include "world_props.h"

namespace corsa::sensors::detail {
namespace {

PaintPolygon counter_clockwise(PaintPolygon p) {
  double area = 0.0;
  for (size_t i = 0; i < p.size(); ++i) {
    area += cross(p[i], p[(i + 1) % p.size()]);
  }
  if (area < 0.0) {
    std::reverse(p.begin(), p.end());
  }
  return p;
}

/// A straight stroke `w` wide from a to b, lengthened by w/2 at the ends marked as joints so
/// that bends have no notch.
PaintPolygon stroke(Vec2 a, Vec2 b, double w, bool joint_a, bool joint_b) {
  const double len = norm(b - a);
  const Vec2 d = len > 1e-9 ? (b - a) * (1.0 / len) : Vec2{1.0, 0.0};
  const Vec2 n{-d.y * 0.5 * w, d.x * 0.5 * w};
  if (joint_a) {
    a = a - d * (0.5 * w);
  }
  if (joint_b) {
    b = b + d * (0.5 * w);
  }
  return counter_clockwise({a - n, b - n, b + n, a + n});
}

/// An arrow head: its tip, pointing along the unit `dir`, `length` long and `width` wide.
PaintPolygon head(Vec2 tip, Vec2 dir, double length, double width) {
  const Vec2 base = tip - dir * length;
  const Vec2 n{-dir.y * 0.5 * width, dir.x * 0.5 * width};
  return counter_clockwise({tip, base + n, base - n});
}

/// Sizes shared by the arrow shapes.
struct ArrowSizes {
  double shaft;        ///< stroke width
  double head_length;  ///< of a head pointing along x
  double head_width;   ///< of a head pointing along x
  double turn_length;  ///< of a head pointing across (along y)
  double turn_width;   ///< of a head pointing across, measured along x
};

ArrowSizes arrow_sizes(double length, double width) {
  ArrowSizes z;
  z.shaft = std::clamp(0.1 * std::max(length, width), 0.1, 0.3);
  z.head_length = std::min(0.3 * length, 4.0 * z.shaft);
  z.head_width = std::min(width, 3.0 * z.shaft);
  z.turn_length = std::min(0.4 * width, 3.0 * z.shaft);
  z.turn_width = std::min(0.35 * length, 3.0 * z.shaft);
  return z;
}

/// A shaft from the back of the box up to a branch at `branch_x`, turning to `side` (+1 left,
/// -1 right) and ending in a head at the box's edge.
void add_turn(std::vector<PaintPolygon>& out, const ArrowSizes& z, double width, double shaft_y,
              double branch_x, int side) {
  const double tip_y = side * 0.5 * width;
  out.push_back(
      stroke({branch_x, shaft_y}, {branch_x, tip_y - side * z.turn_length}, z.shaft, true, false));
  out.push_back(
      head({branch_x, tip_y}, {0.0, static_cast<double>(side)}, z.turn_length, z.turn_width));
}

void add_straight(std::vector<PaintPolygon>& out, const ArrowSizes& z, double length,
                  double shaft_y) {
  out.push_back(stroke({-0.5 * length, shaft_y}, {0.5 * length - z.head_length, shaft_y}, z.shaft,
                       false, false));
  out.push_back(head({0.5 * length, shaft_y}, {1.0, 0.0}, z.head_length, z.head_width));
}

void add_u_turn(std::vector<PaintPolygon>& out, const ArrowSizes& z, double length, double width) {
  // Up on the right, over a half circle, back down on the left to a head pointing -x.
  const double y_r = -0.5 * width + 0.5 * z.shaft;
  const double y_l = 0.5 * width - 0.5 * z.head_width;
  const double radius = 0.5 * (y_l - y_r);
  const double x_c = 0.5 * length - radius - 0.5 * z.shaft;
  const double y_c = 0.5 * (y_l + y_r);
  out.push_back(stroke({-0.5 * length, y_r}, {x_c, y_r}, z.shaft, false, true));
  // 9-degree steps: the notches on the outside of the bend stay under 1.2 cm, and the
  // segments are not lengthened there, so the bend keeps within the box.
  constexpr int kSteps = 20;
  Vec2 prev{x_c, y_r};
  for (int i = 1; i <= kSteps; ++i) {
    const double a = std::numbers::pi * i / kSteps;
    const Vec2 p{x_c + radius * std::sin(a), y_c - radius * std::cos(a)};
    out.push_back(stroke(prev, p, z.shaft, false, false));
    prev = p;
  }
  const double tip_x = x_c - 0.55 * length;
  out.push_back(stroke({x_c, y_l}, {tip_x + z.head_length, y_l}, z.shaft, true, false));
  out.push_back(head({tip_x, y_l}, {-1.0, 0.0}, z.head_length, z.head_width));
}

}  // namespace

std::vector<PaintPolygon> arrow_symbol(ArrowShape shape, double length, double width) {
  std::vector<PaintPolygon> out;
  const ArrowSizes z = arrow_sizes(length, width);
  const double back = -0.5 * length;
  // A turn-only arrow branches near the front; a straight arrow with a turn branches half way.
  const double front_branch = 0.5 * length - 0.5 * z.turn_width;
  const double mid_branch = 0.5 * length - z.head_length - 0.5 * z.turn_width - 0.15 * length;
  switch (shape) {
    case ArrowShape::kStraight:
      add_straight(out, z, length, 0.0);
      break;
    case ArrowShape::kLeft:
    case ArrowShape::kRight: {
      const int side = shape == ArrowShape::kLeft ? 1 : -1;
      const double y = -side * (0.5 * width - 0.5 * z.shaft);
      out.push_back(stroke({back, y}, {front_branch, y}, z.shaft, false, true));
      add_turn(out, z, width, y, front_branch, side);
      break;
    }
    case ArrowShape::kStraightLeft:
    case ArrowShape::kStraightRight: {
      const int side = shape == ArrowShape::kStraightLeft ? 1 : -1;
      const double y = -side * (0.5 * width - 0.5 * z.head_width);
      add_straight(out, z, length, y);
      add_turn(out, z, width, y, mid_branch, side);
      break;
    }
    case ArrowShape::kLeftRight:
      out.push_back(stroke({back, 0.0}, {front_branch, 0.0}, z.shaft, false, true));
      add_turn(out, z, width, 0.0, front_branch, 1);
      add_turn(out, z, width, 0.0, front_branch, -1);
      break;
    case ArrowShape::kUTurn:
      add_u_turn(out, z, length, width);
      break;
  }
  return out;
}

namespace {

/// 5 x 7 cell glyphs, top row first ('#' filled).
struct Glyph {
  char c;
  std::array<const char*, 7> rows;
};

// clang-format off
constexpr Glyph kGlyphs[] = {
  {'A', {" ### ", "#   #", "#   #", "#####", "#   #", "#   #", "#   #"}},
  {'B', {"#### ", "#   #", "#   #", "#### ", "#   #", "#   #", "#### "}},
  {'C', {" ####", "#    ", "#    ", "#    ", "#    ", "#    ", " ####"}},
  {'D', {"#### ", "#   #", "#   #", "#   #", "#   #", "#   #", "#### "}},
  {'E', {"#####", "#    ", "#    ", "#### ", "#    ", "#    ", "#####"}},
  {'F', {"#####", "#    ", "#    ", "#### ", "#    ", "#    ", "#    "}},
  {'G', {" ####", "#    ", "#    ", "#  ##", "#   #", "#   #", " ####"}},
  {'H', {"#   #", "#   #", "#   #", "#####", "#   #", "#   #", "#   #"}},
  {'I', {"#####", "  #  ", "  #  ", "  #  ", "  #  ", "  #  ", "#####"}},
  {'J', {"  ###", "   # ", "   # ", "   # ", "   # ", "#  # ", " ##  "}},
  {'K', {"#   #", "#  # ", "# #  ", "##   ", "# #  ", "#  # ", "#   #"}},
  {'L', {"#    ", "#    ", "#    ", "#    ", "#    ", "#    ", "#####"}},
  {'M', {"#   #", "## ##", "# # #", "# # #", "#   #", "#   #", "#   #"}},
  {'N', {"#   #", "##  #", "# # #", "#  ##", "#   #", "#   #", "#   #"}},
  {'O', {" ### ", "#   #", "#   #", "#   #", "#   #", "#   #", " ### "}},
  {'P', {"#### ", "#   #", "#   #", "#### ", "#    ", "#    ", "#    "}},
  {'Q', {" ### ", "#   #", "#   #", "#   #", "# # #", "#  # ", " ## #"}},
  {'R', {"#### ", "#   #", "#   #", "#### ", "# #  ", "#  # ", "#   #"}},
  {'S', {" ####", "#    ", "#    ", " ### ", "    #", "    #", "#### "}},
  {'T', {"#####", "  #  ", "  #  ", "  #  ", "  #  ", "  #  ", "  #  "}},
  {'U', {"#   #", "#   #", "#   #", "#   #", "#   #", "#   #", " ### "}},
  {'V', {"#   #", "#   #", "#   #", "#   #", "#   #", " # # ", "  #  "}},
  {'W', {"#   #", "#   #", "#   #", "# # #", "# # #", "## ##", "#   #"}},
  {'X', {"#   #", "#   #", " # # ", "  #  ", " # # ", "#   #", "#   #"}},
  {'Y', {"#   #", "#   #", " # # ", "  #  ", "  #  ", "  #  ", "  #  "}},
  {'Z', {"#####", "    #", "   # ", "  #  ", " #   ", "#    ", "#####"}},
  {'0', {" ### ", "#   #", "#  ##", "# # #", "##  #", "#   #", " ### "}},
  {'1', {"  #  ", " ##  ", "  #  ", "  #  ", "  #  ", "  #  ", " ### "}},
  {'2', {" ### ", "#   #", "    #", "   # ", "  #  ", " #   ", "#####"}},
  {'3', {"#####", "   # ", "  #  ", "   # ", "    #", "#   #", " ### "}},
  {'4', {"   # ", "  ## ", " # # ", "#  # ", "#####", "   # ", "   # "}},
  {'5', {"#####", "#    ", "#### ", "    #", "    #", "#   #", " ### "}},
  {'6', {"  ## ", " #   ", "#    ", "#### ", "#   #", "#   #", " ### "}},
  {'7', {"#####", "    #", "   # ", "  #  ", " #   ", " #   ", " #   "}},
  {'8', {" ### ", "#   #", "#   #", " ### ", "#   #", "#   #", " ### "}},
  {'9', {" ### ", "#   #", "#   #", " ####", "    #", "   # ", " ##  "}},
  {' ', {"     ", "     ", "     ", "     ", "     ", "     ", "     "}},
};
// clang-format on

const Glyph* find_glyph(char c) {
  const char upper = (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c;
  for (const Glyph& g : kGlyphs) {
    if (g.c == upper) {
      return &g;
    }
  }
  return nullptr;
}

PaintPolygon rect(double x0, double x1, double y0, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

/// The convex polygon clipped to the half-plane dot(n, p) <= c.
PaintPolygon clip(const PaintPolygon& poly, Vec2 n, double c) {
  PaintPolygon out;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec2 a = poly[i], b = poly[(i + 1) % poly.size()];
    const double da = dot(n, a) - c, db = dot(n, b) - c;
    if (da <= 0.0) {
      out.push_back(a);
    }
    if ((da < 0.0) != (db < 0.0) && std::abs(da - db) > 1e-12) {
      out.push_back(a + (b - a) * (da / (da - db)));
    }
  }
  return out;
}

}  // namespace

bool text_symbol(std::string_view text, double length, double width,
                 std::vector<PaintPolygon>& out) {
  std::vector<const Glyph*> glyphs;
  for (char c : text) {
    const Glyph* g = find_glyph(c);
    if (g == nullptr) {
      return false;
    }
    glyphs.push_back(g);
  }
  if (glyphs.empty()) {
    return true;
  }
  // Cells of 5 columns and a one-column gap between letters, across the box; 7 rows along it.
  const double units = 6.0 * static_cast<double>(glyphs.size()) - 1.0;
  const double cell_y = width / units, cell_x = length / 7.0;
  for (size_t i = 0; i < glyphs.size(); ++i) {
    for (int r = 0; r < 7; ++r) {
      const char* row = glyphs[i]->rows[static_cast<size_t>(r)];
      const double x1 = 0.5 * length - r * cell_x;
      for (int c = 0; c < 5;) {
        if (row[c] != '#') {
          ++c;
          continue;
        }
        int e = c;
        while (e < 5 && row[e] == '#') {
          ++e;
        }
        const double y_left = 0.5 * width - (6.0 * static_cast<double>(i) + c) * cell_y;
        const double y_right = 0.5 * width - (6.0 * static_cast<double>(i) + e) * cell_y;
        out.push_back(rect(x1 - cell_x, x1, y_right, y_left));
        c = e;
      }
    }
  }
  return true;
}

std::vector<PaintPolygon> hatch_symbol(double length, double width, double stroke_w, double spacing,
                                       bool cross_hatch) {
  std::vector<PaintPolygon> out;
  const double hx = 0.5 * length, hy = 0.5 * width;
  out.push_back(rect(-hx, hx, -hy, -hy + stroke_w));
  out.push_back(rect(-hx, hx, hy - stroke_w, hy));
  out.push_back(rect(-hx, -hx + stroke_w, -hy, hy));
  out.push_back(rect(hx - stroke_w, hx, -hy, hy));
  const double reach = length + width;
  const double s = std::sqrt(0.5);
  const int families = cross_hatch ? 2 : 1;
  for (int f = 0; f < families; ++f) {
    const Vec2 n = f == 0 ? Vec2{s, -s} : Vec2{s, s};  // across the stripes
    const Vec2 d{-n.y, n.x};                           // along them
    const int k_max = static_cast<int>(std::ceil(reach / spacing));
    for (int k = -k_max; k <= k_max; ++k) {
      const double c = k * spacing;
      PaintPolygon band = counter_clockwise(
          {n * (c - 0.5 * stroke_w) - d * reach, n * (c - 0.5 * stroke_w) + d * reach,
           n * (c + 0.5 * stroke_w) + d * reach, n * (c + 0.5 * stroke_w) - d * reach});
      band = clip(band, {1.0, 0.0}, hx);
      band = clip(band, {-1.0, 0.0}, hx);
      band = clip(band, {0.0, 1.0}, hy);
      band = clip(band, {0.0, -1.0}, hy);
      if (band.size() >= 3) {
        out.push_back(counter_clockwise(band));
      }
    }
  }
  return out;
}

void add_paint(MeshBuilder& b, const std::vector<PaintPolygon>& polygons, double lift) {
  std::vector<Vec3> points;
  for (const PaintPolygon& p : polygons) {
    points.clear();
    for (const Vec2& v : p) {
      points.push_back({v.x, v.y, lift});
    }
    b.polygon(points, {});
  }
}

Material yellow_road_paint() {
  Material m = road_paint();  // the same worn paint, in yellow
  m.name = "yellow road paint";
  m.base_color = linear_rgb(226, 178, 40);
  return m;
}

}  // namespace corsa::sensors::detail
