#pragma once

// Symbols painted on the road (private): direction arrows, block-letter words and hatched
// areas, as flat convex polygons in a symbol frame whose x points the way the traffic reading
// it drives and whose y points to its left (metres). The world builder places them through an
// OpenDRIVE object's frame (CARLA's stencils) or along a road (Korean marking signals).

#include <string>
#include <string_view>
#include <vector>

#include "corsa/core/vec.h"
#include "corsa/sensors/material.h"
#include "mesh_builder.h"

namespace corsa::sensors::detail {

/// A flat convex polygon, counter-clockwise seen from above.
using PaintPolygon = std::vector<Vec2>;

/// The direction arrows of lane markings.
enum class ArrowShape {
  kStraight,
  kLeft,
  kRight,
  kStraightLeft,
  kStraightRight,
  kLeftRight,
  kUTurn,
};

/// An arrow filling the box [-length/2, length/2] along x by [-width/2, width/2] across: a
/// shaft from the box's back and one head per direction (a turn bends 90 degrees towards y;
/// a U-turn comes back along -x on the left).
std::vector<PaintPolygon> arrow_symbol(ArrowShape shape, double length, double width);

/// Block letters and digits, set in one line across the box (read left to right by the driver,
/// so from +y to -y) and stretched along x to fill it, as road words are. Knows A-Z, 0-9 and
/// space; false (and nothing added) when the text holds another character.
bool text_symbol(std::string_view text, double length, double width,
                 std::vector<PaintPolygon>& out);

/// The gap between two syllables of a Hangul word, as a fraction of a syllable's width.
inline constexpr double kHangulSyllableGap = 0.2;

/// Hangul words set as text_symbol sets letters: one line of syllables across the box (read
/// from +y to -y), each stretched along x over the box's length. The syllables are built from
/// the strokes of their letters; known are the initials ㄱ ㄴ ㄷ ㅁ ㅂ ㅅ ㅇ ㅈ ㅊ ㅎ, the finals
/// ㄱ ㄴ ㄷ ㅁ ㅂ ㅅ ㅇ and the vowels ㅏ ㅓ ㅗ ㅜ ㅡ ㅣ. False (and nothing added) for another
/// character.
bool hangul_symbol(std::u32string_view text, double length, double width,
                   std::vector<PaintPolygon>& out);

/// A hatched area: its outline (a border `stroke` wide) and diagonal stripes `stroke` wide
/// every `spacing` metres, at 45 degrees, clipped to the box; both diagonals when `cross`.
/// The stripe count grows with (length + width) / spacing: callers cap the size.
std::vector<PaintPolygon> hatch_symbol(double length, double width, double stroke, double spacing,
                                       bool cross);

/// Adds the polygons to `b` at `lift` metres above the frame's x-y plane.
void add_paint(MeshBuilder& b, const std::vector<PaintPolygon>& polygons, double lift = 0.012);

/// Yellow road paint (Korean no-stopping zones and centre areas).
Material yellow_road_paint();

}  // namespace corsa::sensors::detail
