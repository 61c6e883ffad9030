// Korean road words: Hangul syllables built from the strokes of their letters (jamo), our own
// geometry (no font). A syllable is designed in a unit square (u across to the reader's right,
// v up the glyph) where the initial consonant, the vowel and the final consonant each take a
// box of the square, as printed Hangul sets them: a vertical vowel (ㅏ ㅓ ㅣ) to the right of
// the initial, a horizontal one (ㅗ ㅜ ㅡ) below it, a final consonant across the bottom. The
// square is then stretched to the syllable's place in the word, so the strokes thicken along
// the road as painted words do. Strokes are rectangles and parallelograms, the ring of ㅇ and
// ㅎ a band of quads between two ellipses: every polygon convex.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "road_symbols.h"

namespace corsa::sensors::detail {
namespace {

/// Stroke width in the unit square (before the stretch).
constexpr double kHangulStroke = 0.15;

/// A box of the unit square.
struct JamoBox {
  double u0, u1, v0, v1;
  double width() const { return u1 - u0; }
  double height() const { return v1 - v0; }
  double mid_u() const { return 0.5 * (u0 + u1); }
};

/// Collects strokes in the unit square and maps them into the symbol frame: u to -y (the
/// reader's right), v to +x (the way the reader drives).
class HangulPen {
 public:
  HangulPen(std::vector<PaintPolygon>& out, double x0, double length, double y_left, double width)
      : out_(out), x0_(x0), length_(length), y_left_(y_left), width_(width) {}

  void bar(double u0, double u1, double v0, double v1) {
    if (u1 - u0 > 1e-6 && v1 - v0 > 1e-6) {
      add({{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}});
    }
  }
  /// A stroke kHangulStroke wide from a to b (its ends square to the stroke).
  void slant(Vec2 a, Vec2 b) {
    const Vec2 d = b - a;
    const double len = std::hypot(d.x, d.y);
    if (len < 1e-9) {
      return;  // no direction to draw along
    }
    const Vec2 n{-d.y / len * 0.5 * kHangulStroke, d.x / len * 0.5 * kHangulStroke};
    add({a - n, b - n, b + n, a + n});
  }
  /// An elliptic ring inscribed in the box, kHangulStroke thick at its sides and 0.6 of that at
  /// its top and bottom, so that the stretch along the road leaves it an open ring.
  void ring(const JamoBox& b) {
    constexpr int kSegments = 20;
    const double cu = b.mid_u(), cv = 0.5 * (b.v0 + b.v1);
    const double ru = 0.5 * b.width(), rv = 0.5 * b.height();
    const double iu = std::max(0.01, ru - kHangulStroke);
    const double iv = std::max(0.01, rv - 0.6 * kHangulStroke);
    for (int k = 0; k < kSegments; ++k) {
      const double a0 = 2.0 * std::numbers::pi * k / kSegments;
      const double a1 = 2.0 * std::numbers::pi * (k + 1) / kSegments;
      add({{cu + ru * std::cos(a0), cv + rv * std::sin(a0)},
           {cu + ru * std::cos(a1), cv + rv * std::sin(a1)},
           {cu + iu * std::cos(a1), cv + iv * std::sin(a1)},
           {cu + iu * std::cos(a0), cv + iv * std::sin(a0)}});
    }
  }

 private:
  void add(const PaintPolygon& unit) {
    PaintPolygon p;
    for (const Vec2& q : unit) {
      p.push_back({x0_ + q.y * length_, y_left_ - q.x * width_});
    }
    // Counter-clockwise seen from above, whichever way the caller went round.
    double area = 0.0;
    for (size_t i = 0; i < p.size(); ++i) {
      area += cross(p[i], p[(i + 1) % p.size()]);
    }
    if (area < 0.0) {
      std::reverse(p.begin(), p.end());
    }
    out_.push_back(std::move(p));
  }

  std::vector<PaintPolygon>& out_;
  double x0_, length_, y_left_, width_;
};

/// ㅅ: a long stroke from the top middle down to the bottom left, and a shorter one from its
/// upper third down to the bottom right.
void hangul_siot(HangulPen& pen, const JamoBox& b) {
  const double h = 0.5 * kHangulStroke;
  const Vec2 top{b.mid_u(), b.v1 - h};
  const Vec2 left{b.u0 + h, b.v0 + h};
  pen.slant(top, left);
  const Vec2 branch = top + (left - top) * 0.3;
  pen.slant(branch, {b.u1 - h, b.v0 + h});
}

/// The consonants the painted words use, by their initial index (U+1100 order): ㄱ 0, ㄴ 2,
/// ㄷ 3, ㅁ 6, ㅂ 7, ㅅ 9, ㅇ 11, ㅈ 12, ㅊ 14, ㅎ 18. False for the others.
bool hangul_consonant(HangulPen& pen, int index, const JamoBox& b) {
  const double s = kHangulStroke;
  switch (index) {
    case 0:  // ㄱ
      pen.bar(b.u0, b.u1, b.v1 - s, b.v1);
      pen.bar(b.u1 - s, b.u1, b.v0, b.v1 - s);
      return true;
    case 2:  // ㄴ
      pen.bar(b.u0, b.u0 + s, b.v0 + s, b.v1);
      pen.bar(b.u0, b.u1, b.v0, b.v0 + s);
      return true;
    case 3:  // ㄷ
      pen.bar(b.u0, b.u1, b.v1 - s, b.v1);
      pen.bar(b.u0, b.u0 + s, b.v0 + s, b.v1 - s);
      pen.bar(b.u0, b.u1, b.v0, b.v0 + s);
      return true;
    case 6:  // ㅁ
      pen.bar(b.u0, b.u1, b.v1 - s, b.v1);
      pen.bar(b.u0, b.u0 + s, b.v0 + s, b.v1 - s);
      pen.bar(b.u1 - s, b.u1, b.v0 + s, b.v1 - s);
      pen.bar(b.u0, b.u1, b.v0, b.v0 + s);
      return true;
    case 7: {  // ㅂ
      const double mid = b.v0 + 0.5 * b.height();
      pen.bar(b.u0, b.u0 + s, b.v0 + s, b.v1);
      pen.bar(b.u1 - s, b.u1, b.v0 + s, b.v1);
      pen.bar(b.u0 + s, b.u1 - s, mid - 0.5 * s, mid + 0.5 * s);
      pen.bar(b.u0, b.u1, b.v0, b.v0 + s);
      return true;
    }
    case 9:  // ㅅ
      hangul_siot(pen, b);
      return true;
    case 11:  // ㅇ
      pen.ring(b);
      return true;
    case 12:  // ㅈ: a bar over ㅅ
      pen.bar(b.u0, b.u1, b.v1 - s, b.v1);
      hangul_siot(pen, {b.u0, b.u1, b.v0, b.v1 - s});
      return true;
    case 14: {  // ㅊ: a tick over ㅈ
      const double tick = 0.22 * b.height();
      pen.bar(b.mid_u() - 0.5 * s, b.mid_u() + 0.5 * s, b.v1 - tick, b.v1);
      pen.bar(b.u0, b.u1, b.v1 - tick - s, b.v1 - tick);
      hangul_siot(pen, {b.u0, b.u1, b.v0, b.v1 - tick - s});
      return true;
    }
    case 18: {  // ㅎ: a tick and a bar over ㅇ
      const double tick = 0.18 * b.height();
      const double inset = 0.1 * b.width();
      pen.bar(b.mid_u() - 0.5 * s, b.mid_u() + 0.5 * s, b.v1 - tick, b.v1);
      pen.bar(b.u0, b.u1, b.v1 - tick - s, b.v1 - tick);
      pen.ring({b.u0 + inset, b.u1 - inset, b.v0, b.v1 - tick - s - 0.06});
      return true;
    }
    default:
      return false;
  }
}

/// The final consonant's index (U+11A8 order, 1-based) as an initial index; -1 for one this
/// table lacks. ㅈ ㅊ ㅎ are not finals here: squeezed into the final's low box (0.3 of the
/// square) their bar, tick and ring would be boxes a few centimetres high, unreadable.
int hangul_final_as_initial(int final_index) {
  switch (final_index) {
    case 1:
      return 0;  // ㄱ
    case 4:
      return 2;  // ㄴ
    case 7:
      return 3;  // ㄷ
    case 16:
      return 6;  // ㅁ
    case 17:
      return 7;  // ㅂ
    case 19:
      return 9;  // ㅅ
    case 21:
      return 11;  // ㅇ
    default:
      return -1;
  }
}

enum class HangulVowelKind { kVertical, kHorizontal, kUnknown };

/// The vowels by their index (U+1161 order): ㅏ 0, ㅓ 4, ㅗ 8, ㅜ 13, ㅡ 18, ㅣ 20.
HangulVowelKind hangul_vowel_kind(int index) {
  switch (index) {
    case 0:
    case 4:
    case 20:
      return HangulVowelKind::kVertical;
    case 8:
    case 13:
    case 18:
      return HangulVowelKind::kHorizontal;
    default:
      return HangulVowelKind::kUnknown;
  }
}

/// Draws the vowel of index `index` (one hangul_vowel_kind knows) into the box.
void hangul_vowel(HangulPen& pen, int index, const JamoBox& b) {
  const double s = kHangulStroke;
  const double v_mid = b.v0 + 0.5 * b.height();
  switch (index) {
    case 0: {  // ㅏ: a long stroke with a short tick to the right
      const double u = b.u0 + 0.35 * b.width();
      pen.bar(u - 0.5 * s, u + 0.5 * s, b.v0, b.v1);
      pen.bar(u + 0.5 * s, b.u1, v_mid - 0.5 * s, v_mid + 0.5 * s);
      break;
    }
    case 4: {  // ㅓ: a long stroke with a short tick to the left
      const double u = b.u1 - 0.3 * b.width();
      pen.bar(u - 0.5 * s, u + 0.5 * s, b.v0, b.v1);
      pen.bar(b.u0, u - 0.5 * s, v_mid - 0.5 * s, v_mid + 0.5 * s);
      break;
    }
    case 20: {  // ㅣ
      const double u = b.u0 + 0.55 * b.width();
      pen.bar(u - 0.5 * s, u + 0.5 * s, b.v0, b.v1);
      break;
    }
    case 8: {  // ㅗ: a bar low in the box with a short tick up
      const double v = b.v0 + 0.3 * b.height();
      pen.bar(b.u0, b.u1, v - 0.5 * s, v + 0.5 * s);
      pen.bar(b.mid_u() - 0.5 * s, b.mid_u() + 0.5 * s, v + 0.5 * s, b.v1);
      break;
    }
    case 13: {  // ㅜ: a bar high in the box with a short tick down
      const double v = b.v1 - 0.3 * b.height();
      pen.bar(b.u0, b.u1, v - 0.5 * s, v + 0.5 * s);
      pen.bar(b.mid_u() - 0.5 * s, b.mid_u() + 0.5 * s, b.v0, v - 0.5 * s);
      break;
    }
    case 18: {  // ㅡ
      pen.bar(b.u0, b.u1, v_mid - 0.5 * s, v_mid + 0.5 * s);
      break;
    }
    default:
      // hangul_syllable draws only the vowels hangul_vowel_kind knows.
      throw std::logic_error("hangul_vowel called for a vowel it does not draw");
  }
}

/// Draws one precomposed syllable (U+AC00..U+D7A3) into the pen's unit square; false when it
/// is not one or uses a letter the tables lack.
bool hangul_syllable(HangulPen& pen, char32_t c) {
  if (c < 0xAC00 || c > 0xD7A3) {
    return false;
  }
  const int code = static_cast<int>(c - 0xAC00);
  const int initial = code / (21 * 28), medial = (code / 28) % 21, final_index = code % 28;
  const HangulVowelKind kind = hangul_vowel_kind(medial);
  const int final_initial = final_index == 0 ? -1 : hangul_final_as_initial(final_index);
  if (kind == HangulVowelKind::kUnknown || (final_index != 0 && final_initial < 0)) {
    return false;
  }
  const bool has_final = final_index != 0;
  JamoBox first, second, last{0.08, 0.92, 0.0, 0.3};
  if (kind == HangulVowelKind::kVertical) {
    first = has_final ? JamoBox{0.0, 0.56, 0.5, 1.0} : JamoBox{0.0, 0.56, 0.1, 0.9};
    second = has_final ? JamoBox{0.6, 1.0, 0.42, 1.0} : JamoBox{0.6, 1.0, 0.0, 1.0};
  } else {
    first = has_final ? JamoBox{0.15, 0.85, 0.62, 1.0} : JamoBox{0.12, 0.88, 0.42, 1.0};
    second = has_final ? JamoBox{0.0, 1.0, 0.34, 0.6} : JamoBox{0.0, 1.0, 0.0, 0.42};
  }
  if (!hangul_consonant(pen, initial, first)) {
    return false;
  }
  hangul_vowel(pen, medial, second);
  return !has_final || hangul_consonant(pen, final_initial, last);
}

}  // namespace

bool hangul_symbol(std::u32string_view text, double length, double width,
                   std::vector<PaintPolygon>& out) {
  if (text.empty()) {
    return true;
  }
  // Syllables side by side across the box with kHangulSyllableGap of one between them, each
  // stretched along x over the box's whole length.
  const double n = static_cast<double>(text.size());
  const double unit = width / (n + (n - 1.0) * kHangulSyllableGap);
  std::vector<PaintPolygon> glyphs;
  for (size_t i = 0; i < text.size(); ++i) {
    const double y_left = 0.5 * width - static_cast<double>(i) * (1.0 + kHangulSyllableGap) * unit;
    HangulPen pen(glyphs, -0.5 * length, length, y_left, unit);
    if (!hangul_syllable(pen, text[i])) {
      return false;
    }
  }
  out.insert(out.end(), glyphs.begin(), glyphs.end());
  return true;
}

}  // namespace corsa::sensors::detail
