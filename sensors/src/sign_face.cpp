// Traffic-sign faces and plates drawn from signed distance functions of their shape, border and
// symbol, antialiased over the pixel footprint (the smoothstep over one footprint is a box filter
// of the edge).

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "corsa/core/vec.h"
#include "surface.h"

namespace corsa::sensors::detail {
namespace {

double length(Vec2 p) { return std::hypot(p.x, p.y); }

/// Distance to a segment minus a half width: a stroke (negative inside).
double capsule(Vec2 p, Vec2 a, Vec2 b, double half_width) {
  const Vec2 pa{p.x - a.x, p.y - a.y};
  const Vec2 ba{b.x - a.x, b.y - a.y};
  const double h = std::clamp((pa.x * ba.x + pa.y * ba.y) / (ba.x * ba.x + ba.y * ba.y), 0.0, 1.0);
  return length({pa.x - ba.x * h, pa.y - ba.y * h}) - half_width;
}

/// Signed distance to a convex polygon given counter-clockwise (exact inside, a lower bound
/// outside: enough for antialiasing).
double convex(Vec2 p, const std::vector<Vec2>& poly) {
  double d = -1e9;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec2 a = poly[i];
    const Vec2 b = poly[(i + 1) % poly.size()];
    const double ex = b.x - a.x;
    const double ey = b.y - a.y;
    const double len = std::hypot(ex, ey);
    // Outward normal of a counter-clockwise edge: (ey, -ex).
    d = std::max(d, ((p.x - a.x) * ey - (p.y - a.y) * ex) / len);
  }
  return d;
}

double box(Vec2 p, double hx, double hy) {
  const double dx = std::fabs(p.x) - hx;
  const double dy = std::fabs(p.y) - hy;
  return std::max(dx, dy);
}

double shape_distance(SignShape shape, Vec2 p) {
  const double r2 = std::sqrt(2.0);
  switch (shape) {
    case SignShape::kCircle:
      return length(p) - 1.0;
    case SignShape::kSquare:
    case SignShape::kRectangle:
      return std::max(std::fabs(p.x), std::fabs(p.y)) - 1.0;
    case SignShape::kDiamond:
      return (std::fabs(p.x) + std::fabs(p.y) - 1.0) / r2;
    case SignShape::kOctagon:
      return std::max({std::fabs(p.x), std::fabs(p.y), (std::fabs(p.x) + std::fabs(p.y)) / r2}) -
             1.0;
    case SignShape::kTriangleUp:
      return convex(p, {{-1.0, -0.78}, {1.0, -0.78}, {0.0, 0.95}});
    case SignShape::kTriangleDown:
      return convex(p, {{-1.0, 0.78}, {0.0, -0.95}, {1.0, 0.78}});
  }
  return length(p) - 1.0;
}

// Seven-segment masks: bit 0 a (top), 1 b (top right), 2 c (bottom right), 3 d (bottom),
// 4 e (bottom left), 5 f (top left), 6 g (middle).
constexpr std::array<uint8_t, 10> kDigits = {0x3F, 0x06, 0x5B, 0x4F, 0x66,
                                             0x6D, 0x7D, 0x07, 0x7F, 0x6F};

/// One seven-segment glyph in a box of half sizes (w, h) centred at the origin.
double glyph(Vec2 p, uint8_t mask, double w, double h, double stroke) {
  const Vec2 tl{-w, h}, tr{w, h}, ml{-w, 0.0}, mr{w, 0.0}, bl{-w, -h}, br{w, -h};
  const std::array<std::array<Vec2, 2>, 7> seg = {
      {{tl, tr}, {tr, mr}, {mr, br}, {bl, br}, {ml, bl}, {tl, ml}, {ml, mr}}};
  double d = 1e9;
  for (int s = 0; s < 7; ++s) {
    if (mask & (1u << s)) {
      d = std::min(d, capsule(p, seg[s][0], seg[s][1], stroke));
    }
  }
  return d;
}

/// A row of glyphs centred in the face, each `h` high.
double text(Vec2 p, const std::vector<uint8_t>& masks, double h, double stroke) {
  const double w = 0.55 * h;
  const double pitch = 2.5 * w;  // glyph width (2 w) plus a gap
  const double total = pitch * static_cast<double>(masks.size()) - 0.5 * w;
  double d = 1e9;
  for (size_t i = 0; i < masks.size(); ++i) {
    const double cx = -0.5 * total + w + pitch * static_cast<double>(i);
    d = std::min(d, glyph({p.x - cx, p.y}, masks[i], w, 0.5 * h, stroke));
  }
  return d;
}

double symbol_distance(const SignFace& f, Vec2 p) {
  switch (f.symbol) {
    case SignSymbol::kNone:
      return 1e9;
    case SignSymbol::kNumber: {
      std::vector<uint8_t> masks;
      int n = std::max(0, f.number);
      do {
        masks.insert(masks.begin(), kDigits[n % 10]);
        n /= 10;
      } while (n > 0 && masks.size() < 6);
      const double h = f.aspect > 2.0 ? 1.25 : masks.size() <= 2 ? 0.9 : 0.6;
      return text(p, masks, h, 0.07 * h / 0.9);
    }
    case SignSymbol::kStopText: {
      // S T O P; the T is drawn as two strokes below.
      const double h = 0.55;
      const double w = 0.55 * h;
      const double pitch = 2.0 * w + 0.5 * w;
      const double x0 = -1.5 * pitch;
      double d = glyph({p.x - x0, p.y}, 0x6D, w, 0.5 * h, 0.05);
      d = std::min(d, capsule(p, {x0 + pitch - w, 0.5 * h}, {x0 + pitch + w, 0.5 * h}, 0.05));
      d = std::min(d, capsule(p, {x0 + pitch, 0.5 * h}, {x0 + pitch, -0.5 * h}, 0.05));
      d = std::min(d, glyph({p.x - x0 - 2 * pitch, p.y}, 0x3F, w, 0.5 * h, 0.05));
      d = std::min(d, glyph({p.x - x0 - 3 * pitch, p.y}, 0x73, w, 0.5 * h, 0.05));
      return d;
    }
    case SignSymbol::kBar:
      return box(p, 0.72, 0.17);
    case SignSymbol::kArrowUp:
    case SignSymbol::kArrowLeft:
    case SignSymbol::kArrowRight: {
      Vec2 q = p;
      if (f.symbol == SignSymbol::kArrowLeft) {
        q = {p.y, -p.x};
      } else if (f.symbol == SignSymbol::kArrowRight) {
        q = {-p.y, p.x};
      }
      const double shaft = capsule(q, {0.0, -0.6}, {0.0, 0.15}, 0.12);
      const double head = convex(q, {{-0.42, 0.1}, {0.42, 0.1}, {0.0, 0.68}});
      return std::min(shaft, head);
    }
    case SignSymbol::kExclamation:
      return std::min(capsule(p, {0.0, 0.0}, {0.0, 0.5}, 0.08), length({p.x, p.y + 0.32}) - 0.09);
    case SignSymbol::kPerson: {
      double d = length({p.x, p.y - 0.45}) - 0.12;
      d = std::min(d, capsule(p, {0.0, 0.3}, {0.02, -0.12}, 0.08));
      d = std::min(d, capsule(p, {0.02, -0.12}, {-0.22, -0.6}, 0.07));
      d = std::min(d, capsule(p, {0.02, -0.12}, {0.25, -0.58}, 0.07));
      d = std::min(d, capsule(p, {0.0, 0.2}, {-0.26, -0.02}, 0.06));
      return std::min(d, capsule(p, {0.0, 0.2}, {0.26, 0.05}, 0.06));
    }
    case SignSymbol::kDiagonal:
      return capsule(p, {-0.75, -0.75}, {0.75, 0.75}, 0.09);
    case SignSymbol::kInnerDiamond:
      return (std::fabs(p.x) + std::fabs(p.y) - 0.62) / std::sqrt(2.0);
    case SignSymbol::kCross:
      return std::min(capsule(p, {-0.6, -0.6}, {0.6, 0.6}, 0.1),
                      capsule(p, {-0.6, 0.6}, {0.6, -0.6}, 0.1));
  }
  return 1e9;
}

/// Coverage of the inside of a signed distance (negative inside) over a footprint `fw`.
double cover(double d, double fw) {
  const double t = std::clamp(0.5 - d / (2.0 * fw), 0.0, 1.0);
  return t;
}

}  // namespace

Color sign_face_color(const SignFace& f, double u, double v, double fw) {
  const Vec2 p{2.0 * u - 1.0, 2.0 * v - 1.0};
  const double w = 2.0 * fw;
  const double d = shape_distance(f.shape, p);
  // Symbols live inside the border, scaled to the inner face.
  const double inner = std::max(0.2, 1.0 - f.border_width - 0.06);
  const Vec2 q{p.x * f.aspect / inner, p.y / inner};
  const double s = symbol_distance(f, q) * inner;
  Color c = f.fill;
  c = mix(c, f.symbol_color, cover(s, w));
  // The border band: the outer border_width of the face.
  c = mix(c, f.border, 1.0 - cover(d + f.border_width, w));
  return c;
}

}  // namespace corsa::sensors::detail
