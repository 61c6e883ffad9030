// Symbols painted on the road: Korean direction arrows and hatched areas given as signals, and
// the RoadRunner stencils of CARLA's maps (turn arrows, the word STOP) and its short-dash lines
// given as untyped objects.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <set>
#include <string>

#include "corsa/sensors/labels.h"
#include "corsa/sensors/world.h"
#include "markings_fixture.h"
#include "road_symbols.h"
#include "scene_data.h"

using namespace corsa::sensors;
using corsa::Vec2;
using corsa::test::down_at;
using corsa::test::marked_world;
using corsa::test::paint_at;
using corsa::test::street_with;

namespace {

/// The labels of the static object a ray straight down at (x, y) hits.
ObjectInfo object_at(const Scene& scene, double x, double y) {
  const RayHit hit = down_at(scene, x, y);
  REQUIRE(hit.instance_id >= kStaticInstanceBase);
  const std::vector<uint32_t> instance = {hit.instance_id};
  const std::vector<uint8_t> semantic = {static_cast<uint8_t>(hit.semantic)};
  const auto labels = static_object_labels(scene, instance, 1, semantic);
  REQUIRE(labels.size() == 1);
  return labels[0].info;
}

/// True when (x, y) lies in one of the symbol's convex counter-clockwise polygons.
bool in_symbol(const std::vector<detail::PaintPolygon>& symbol, double x, double y) {
  for (const detail::PaintPolygon& p : symbol) {
    bool inside = true;
    for (size_t i = 0; i < p.size() && inside; ++i) {
      const Vec2 a = p[i], b = p[(i + 1) % p.size()];
      inside = cross(b - a, Vec2{x, y} - a) >= 0.0;
    }
    if (inside) {
      return true;
    }
  }
  return false;
}

/// The distance from (x, y) to the nearest polygon edge of the symbol.
double word_edge_distance(const std::vector<detail::PaintPolygon>& symbol, double x, double y) {
  double best = 1e9;
  const Vec2 q{x, y};
  for (const detail::PaintPolygon& p : symbol) {
    for (size_t i = 0; i < p.size(); ++i) {
      const Vec2 a = p[i], b = p[(i + 1) % p.size()];
      const Vec2 d = b - a;
      const double f = std::clamp(dot(q - a, d) / std::max(dot(d, d), 1e-12), 0.0, 1.0);
      const Vec2 e = a + d * f - q;
      best = std::min(best, std::sqrt(dot(e, e)));
    }
  }
  return best;
}

}  // namespace

TEST_CASE("the arrow shapes keep to their box and point where their names say",
          "[sensors][world][markings]") {
  // 5 m x 1.8 m: the shaft 0.3 m wide, heads 1.2 m long (along x) or 0.72 m (across).
  using detail::ArrowShape;
  const auto u_turn = detail::arrow_symbol(ArrowShape::kUTurn, 5.0, 1.8);
  CHECK(in_symbol(u_turn, -2.0, -0.75));       // up the right leg from the back
  CHECK(in_symbol(u_turn, 2.3, 0.0));          // over the top of the bend
  CHECK(in_symbol(u_turn, -0.3, 0.45));        // the head on the left leg, pointing back
  CHECK_FALSE(in_symbol(u_turn, -2.0, 0.45));  // the left leg ends at its tip
  CHECK_FALSE(in_symbol(u_turn, 0.0, 0.0));    // nothing between the legs
  const auto both = detail::arrow_symbol(ArrowShape::kLeftRight, 5.0, 1.8);
  CHECK(in_symbol(both, -1.0, 0.0));        // the shaft in the middle
  CHECK(in_symbol(both, 2.05, 0.8));        // a head to the left
  CHECK(in_symbol(both, 2.05, -0.8));       // and one to the right
  CHECK_FALSE(in_symbol(both, 2.45, 0.0));  // no head ahead
  for (const auto& symbol : {u_turn, both}) {
    for (const auto& polygon : symbol) {
      for (const Vec2& p : polygon) {
        CHECK(std::abs(p.x) <= 2.5 + 1e-9);
        CHECK(std::abs(p.y) <= 0.9 + 1e-9);
      }
    }
  }
  // Block letters: an unknown character is refused, nothing added.
  std::vector<detail::PaintPolygon> text;
  CHECK_FALSE(detail::text_symbol("STOP!", 2.0, 2.0, text));
  CHECK(text.empty());
  CHECK(detail::text_symbol("STOP", 2.0, 2.0, text));
  CHECK(text.size() > 10);
}

TEST_CASE("a Korean straight arrow signal is painted in each lane it serves, pointing its way",
          "[sensors][world][signals][markings][korea]") {
  // 537 for traffic towards +s: lanes -1 and -2, an arrow 5 m long centred on s 20; the shaft
  // 0.3 m wide, the head 1.2 m long and 0.9 m wide at the front.
  const auto map = street_with(
      R"(<signal id="up" s="20" t="-3.5" orientation="+" dynamic="no" country="KR" type="537" subtype="-1"/>)");
  auto world = marked_world(map);
  CHECK(world->report.markings == 1);
  CHECK(world->report.signs == 0);
  CHECK(world->warnings.empty());
  CHECK(paint_at(world->scene, 18.0, -1.75));        // the shaft, lane -1
  CHECK(paint_at(world->scene, 18.0, -5.25));        // the shaft, lane -2
  CHECK_FALSE(paint_at(world->scene, 18.0, -1.45));  // beside the shaft
  CHECK(paint_at(world->scene, 21.5, -1.45));        // the head is wider, at the front (+s)
  CHECK_FALSE(paint_at(world->scene, 17.3, -1.75));  // 5 m long, from s 17.5
  CHECK_FALSE(paint_at(world->scene, 20.0, 1.75));   // not the oncoming lane
  const ObjectInfo info = object_at(world->scene, 18.0, -1.75);
  CHECK(info.kind == "arrow");
  CHECK(info.type == "537");
  CHECK(info.signal_id == "up");
}

TEST_CASE("a Korean left-turn arrow for the other direction turns to that driver's left",
          "[sensors][world][signals][markings][korea]") {
  // 538 with orientation "-": lane 1, driven towards -s, so the driver's left is -t. The arrow
  // is 1.8 m across: the shaft 0.75 m right of the lane's centre (t 2.5), the bend 2.05 m
  // ahead of s 50 (s 47.95) reaching 0.9 m to the left (t 0.85).
  const auto map = street_with(
      R"(<signal id="left" s="50" t="1.75" orientation="-" dynamic="no" country="KOR" type="538" subtype="-1"/>)");
  auto world = marked_world(map);
  CHECK(world->report.markings == 1);
  CHECK(world->warnings.empty());
  CHECK(paint_at(world->scene, 50.0, 2.5));          // the shaft
  CHECK_FALSE(paint_at(world->scene, 50.0, 1.75));   // not the lane's centre
  CHECK(paint_at(world->scene, 47.95, 1.15));        // the head, towards -t
  CHECK_FALSE(paint_at(world->scene, 47.95, 2.9));   // nothing towards +t
  CHECK_FALSE(paint_at(world->scene, 52.2, 1.15));   // the back end has no head
  CHECK_FALSE(paint_at(world->scene, 50.0, -1.75));  // the other lanes are not its own
}

TEST_CASE("Hangul words are convex strokes inside their box, one syllable after another",
          "[sensors][world][markings][korea]") {
  // 천천히 4 m along and 2.9 m across: three syllables 0.853 m wide with 0.171 m between them.
  std::vector<detail::PaintPolygon> slow;
  REQUIRE(detail::hangul_symbol(U"\uCC9C\uCC9C\uD788", 4.0, 2.9, slow));
  CHECK(slow.size() > 20);
  double x_min = 1e9, x_max = -1e9, y_min = 1e9, y_max = -1e9;
  for (const auto& polygon : slow) {
    REQUIRE(polygon.size() >= 3);
    for (size_t i = 0; i < polygon.size(); ++i) {
      const Vec2 a = polygon[i], b = polygon[(i + 1) % polygon.size()];
      const Vec2 c = polygon[(i + 2) % polygon.size()];
      CHECK(cross(b - a, c - b) >= -1e-12);  // convex, counter-clockwise
      x_min = std::min(x_min, a.x);
      x_max = std::max(x_max, a.x);
      y_min = std::min(y_min, a.y);
      y_max = std::max(y_max, a.y);
    }
  }
  // The strokes fill the box: the syllables reach both ends along x and the left side (a
  // slanted stroke's square end may poke out by a few centimetres); on the right the last
  // syllable ends in ㅣ, 0.1 of a cell short of the side.
  CHECK(x_min == Approx(-2.0).margin(0.06));
  CHECK(x_max == Approx(2.0).margin(0.06));
  CHECK(y_max == Approx(1.45).margin(0.06));
  CHECK(y_min == Approx(-1.45 + 0.105 * 2.9 / 3.4).margin(0.01));
  // Read from +y to -y: the last syllable 히 ends in the long stroke of ㅣ, from end to end of
  // the box; the first, 천, has its final ㄴ's bar across the near end (-x) and nothing of it
  // reaches past the gap.
  const double unit = 2.9 / 3.4;
  const double i_bar = 1.45 - 2.0 * 1.2 * unit - 0.82 * unit;  // 히's ㅣ at u 0.82 of its cell
  CHECK(in_symbol(slow, -1.95, i_bar));
  CHECK(in_symbol(slow, 1.95, i_bar));
  CHECK(in_symbol(slow, -1.8, 1.45 - 0.5 * unit));       // 천's ㄴ bar, near end
  CHECK_FALSE(in_symbol(slow, 0.0, 1.45 - 1.1 * unit));  // the gap between 천 and 천
  // The unknown: a syllable with a vowel the tables lack is refused and adds nothing.
  std::vector<detail::PaintPolygon> other;
  CHECK_FALSE(detail::hangul_symbol(U"\uC815\uC560", 4.0, 2.0, other));  // 정애
  CHECK(other.empty());
  // Finals ㅈ ㅊ ㅎ would be squeezed unreadable into the final's low box: refused (낮 낯 낳),
  // while ㄱ as a final is known (낙).
  for (const char32_t* refused : {U"\uB0AE", U"\uB0AF", U"\uB0B3"}) {
    CHECK_FALSE(detail::hangul_symbol(refused, 4.0, 1.0, other));
    CHECK(other.empty());
  }
  CHECK(detail::hangul_symbol(U"\uB099", 4.0, 1.0, other));  // 낙
  other.clear();
  CHECK(detail::hangul_symbol(U"\uC815\uC9C0", 4.0, 2.2, other));  // 정지
}

TEST_CASE("Korean slow and stop word signals are Hangul paint in their lane, read its way",
          "[sensors][world][signals][markings][korea]") {
  // 519 (천천히) for traffic towards +s in lane -1 (t -3.5..0) and 521 (정지) for traffic
  // towards -s in lane 1 (t 0..3.5): 4 m along the road, centred on s and on the lane, kept
  // 0.3 m off the lines (천천히 2.9 m across, 정지 2.2 m).
  const auto map = street_with(
      R"(<signal id="slow" s="40" t="-1.75" orientation="+" dynamic="no" country="KR" type="519" subtype="-1"/>
         <signal id="stop" s="70" t="1.75" orientation="-" dynamic="no" country="KR" type="521" subtype="-1"/>)");
  auto world = marked_world(map);
  CHECK(world->report.markings == 2);
  CHECK(world->report.signs == 0);
  CHECK(world->warnings.empty());
  // Each mark is the word's symbol placed on its lane, turned to its driver: every sample
  // clear of a stroke's edge by 2 cm is paint exactly where the symbol is.
  struct Placed {
    std::u32string word;
    double s_mid, t_mid, across;
    int dir;
    const char* type;
    const char* signal_id;
    const char* text;  ///< the word in UTF-8
  };
  const Placed marks[] = {{U"\uCC9C\uCC9C\uD788", 40.0, -1.75, 2.9, 1, "519", "slow", "천천히"},
                          {U"\uC815\uC9C0", 70.0, 1.75, 2.2, -1, "521", "stop", "정지"}};
  for (const Placed& m : marks) {
    std::vector<detail::PaintPolygon> symbol;
    REQUIRE(detail::hangul_symbol(m.word, 4.0, m.across, symbol));
    int painted = 0, compared = 0;
    for (double ds = -2.3; ds <= 2.3; ds += 0.05) {
      for (double dt = -1.75; dt <= 1.75; dt += 0.05) {
        const double s = m.s_mid + ds, t = m.t_mid + dt;
        const double x = m.dir * ds, y = m.dir * dt;  // the symbol frame: x the driver's way
        if (word_edge_distance(symbol, x, y) < 0.02) {
          continue;
        }
        const bool want = in_symbol(symbol, x, y);
        CHECK(paint_at(world->scene, s, t) == want);
        painted += want ? 1 : 0;
        ++compared;
      }
    }
    CHECK(painted > compared / 10);
    // Nothing outside the lane's 4 m.
    CHECK_FALSE(paint_at(world->scene, m.s_mid + 2.1, m.t_mid));
    CHECK_FALSE(paint_at(world->scene, m.s_mid - 2.1, m.t_mid));
    // The paint is labelled as the signal's text, with the word: a point deep inside the first
    // stroke (the mean of its corners, clear of its edges) hits the signal's object.
    Vec2 inside{0.0, 0.0};
    for (const Vec2& p : symbol.front()) {
      inside = inside + p * (1.0 / static_cast<double>(symbol.front().size()));
    }
    REQUIRE(in_symbol(symbol, inside.x, inside.y));
    REQUIRE(word_edge_distance(symbol, inside.x, inside.y) > 0.02);
    const ObjectInfo info =
        object_at(world->scene, m.s_mid + m.dir * inside.x, m.t_mid + m.dir * inside.y);
    CHECK(info.kind == "text");
    CHECK(info.type == m.type);
    CHECK(info.signal_id == m.signal_id);
    CHECK(info.text == m.text);
  }
  CHECK_FALSE(paint_at(world->scene, 40.0, 1.75));   // not the oncoming lane
  CHECK_FALSE(paint_at(world->scene, 70.0, -1.75));  // nor the other way
}

TEST_CASE(
    "Korean words on a curve follow the lane: each stroke lies where the lane's s and t put "
    "it",
    "[sensors][world][signals][markings][korea]") {
  // The same two words on a road bending left with a radius of 20 m. A stroke is mapped from
  // the symbol's (x, y) to the road's (s, t); one mapped only at its corners would cut the
  // curve's chord, up to 0.1 m off the lane's offset over a 4 m stroke. Every sample clear of a
  // stroke's edge by 1 cm is paint exactly where the symbol is, at the pose of its (s, t).
  std::string text = corsa::test::street_text(
      R"(<signal id="slow" s="40" t="-1.75" orientation="+" dynamic="no" country="KR" type="519" subtype="-1"/>
         <signal id="stop" s="70" t="1.75" orientation="-" dynamic="no" country="KR" type="521" subtype="-1"/>)");
  REQUIRE(text.find("<line/>") != std::string::npos);
  text.replace(text.find("<line/>"), 7, R"(<arc curvature="0.05"/>)");
  const auto map = corsa::test::map_of(text);
  auto world = marked_world(map);
  CHECK(world->report.markings == 2);
  CHECK(world->warnings.empty());
  struct CurvedWord {
    std::u32string word;
    double s_mid, t_mid, across;
    int dir;
  };
  const CurvedWord marks[] = {{U"\uCC9C\uCC9C\uD788", 40.0, -1.75, 2.9, 1},
                              {U"\uC815\uC9C0", 70.0, 1.75, 2.2, -1}};
  for (const CurvedWord& m : marks) {
    std::vector<detail::PaintPolygon> symbol;
    REQUIRE(detail::hangul_symbol(m.word, 4.0, m.across, symbol));
    int painted = 0, compared = 0, wrong = 0;
    for (double ds = -2.3; ds <= 2.3; ds += 0.025) {
      for (double dt = -1.7; dt <= 1.7; dt += 0.025) {
        const double x = m.dir * ds, y = m.dir * dt;
        if (word_edge_distance(symbol, x, y) < 0.01) {
          continue;
        }
        const corsa::xodr::WorldPose p = map.world_pose(0, m.s_mid + ds, m.t_mid + dt);
        const bool want = in_symbol(symbol, x, y);
        wrong += paint_at(world->scene, p.x, p.y) == want ? 0 : 1;
        painted += want ? 1 : 0;
        ++compared;
      }
    }
    CHECK(wrong == 0);
    CHECK(painted > compared / 10);
  }
}

TEST_CASE("a Korean word signal whose lanes are too narrow for it is left out with a warning",
          "[sensors][world][signals][markings][korea]") {
  // 519 (천천히) on lane -1 alone, here 1.2 m wide: kept 0.3 m off the lines its three
  // syllables would be 0.2 m wide, under the 0.3 m a syllable needs.
  std::string text = corsa::test::street_text(
      R"(<signal id="narrow" s="40" t="-0.6" orientation="+" dynamic="no" country="KR" type="519" subtype="-1">
           <validity fromLane="-1" toLane="-1"/></signal>)");
  const std::string wide = R"(<lane id="-1" type="driving"><width sOffset="0" a="3.5")";
  REQUIRE(text.find(wide) != std::string::npos);
  text.replace(text.find(wide), wide.size(),
               R"(<lane id="-1" type="driving"><width sOffset="0" a="1.2")");
  auto world = marked_world(corsa::test::map_of(text));
  CHECK(world->report.markings == 0);
  CHECK_FALSE(paint_at(world->scene, 40.0, -0.6));
  REQUIRE(world->warnings.size() == 1);
  CHECK(world->warnings[0].line > 0);
  CHECK_THAT(world->warnings[0].message, Catch::Contains("narrow"));
  CHECK_THAT(world->warnings[0].message, Catch::Contains("wide enough for its word"));
}

TEST_CASE("a Korean word signal is not painted in a biking lane it would otherwise cover",
          "[sensors][world][signals][markings][korea]") {
  // 521 (정지) for traffic towards +s covers lanes -1 and -2; here lane -2 is a biking lane:
  // the word is painted in lane -1 only.
  std::string text = corsa::test::street_text(
      R"(<signal id="stop" s="40" t="-1.75" orientation="+" dynamic="no" country="KR" type="521" subtype="-1"/>)");
  const std::string driving = R"(<lane id="-2" type="driving">)";
  REQUIRE(text.find(driving) != std::string::npos);
  text.replace(text.find(driving), driving.size(), R"(<lane id="-2" type="biking">)");
  auto world = marked_world(corsa::test::map_of(text));
  CHECK(world->report.markings == 1);
  CHECK(world->warnings.empty());
  std::vector<detail::PaintPolygon> symbol;
  REQUIRE(detail::hangul_symbol(U"\uC815\uC9C0", 4.0, 2.2, symbol));
  int in_lane = 0, in_biking_lane = 0;
  for (double ds = -1.9; ds <= 1.9; ds += 0.1) {
    for (double dt = -1.1; dt <= 1.1; dt += 0.1) {
      if (in_symbol(symbol, ds, dt) && word_edge_distance(symbol, ds, dt) > 0.02) {
        in_lane += paint_at(world->scene, 40.0 + ds, -1.75 + dt) ? 1 : 0;
        in_biking_lane += paint_at(world->scene, 40.0 + ds, -5.25 + dt) ? 1 : 0;
      }
    }
  }
  CHECK(in_lane > 50);
  CHECK(in_biking_lane == 0);
}

TEST_CASE("a Korean no-stopping zone with a size is a yellow cross-hatched box",
          "[sensors][world][signals][markings][korea]") {
  // 524, 6 m along and 3 m across centred on (70, -3.5): a 0.2 m border, stripes 0.2 m wide
  // every 2 m in both diagonals through the centre. 531 without a size is left out, warned.
  const auto map = street_with(
      R"(<signal id="box" s="70" t="-3.5" orientation="none" dynamic="no" country="KR" type="524" subtype="-1" length="6" width="3"/>
         <signal id="island" s="30" t="0" orientation="none" dynamic="no" country="KR" type="531" subtype="-1"/>)");
  auto world = marked_world(map);
  CHECK(world->report.markings == 1);
  CHECK(paint_at(world->scene, 67.1, -3.5));         // the border at the back
  CHECK(paint_at(world->scene, 70.0, -4.9));         // the border at the side
  CHECK(paint_at(world->scene, 70.0, -3.5));         // both diagonals cross at the centre
  CHECK_FALSE(paint_at(world->scene, 70.5, -3.5));   // between the stripes
  CHECK_FALSE(paint_at(world->scene, 70.0, -5.15));  // 3 m across
  CHECK_FALSE(paint_at(world->scene, 73.2, -3.5));   // 6 m along
  const RayHit hit = down_at(world->scene, 70.0, -3.5);
  CHECK(hit.semantic == SemanticClass::kLaneMarking);
  const ObjectInfo info = object_at(world->scene, 70.0, -3.5);
  CHECK(info.kind == "no_stopping_zone");
  REQUIRE(world->warnings.size() == 1);
  CHECK(world->warnings[0].line > 0);
  CHECK_THAT(world->warnings[0].message, Catch::Contains("gives no length and width"));
  CHECK_FALSE(paint_at(world->scene, 30.0, 0.0));
}

TEST_CASE("CARLA's turn-arrow and STOP stencils are paint in their lane, read the lane's way",
          "[sensors][world][objects][markings]") {
  // As Town04 writes them: untyped objects named after the RoadRunner stencil, the box 3.06 x
  // 3.15 m (length and width as the exporter gives them), heading 0 in lane -1. The left arrow
  // is 3.15 m long and 1.89 m across: its shaft at t -2.54, its head 1.1 m ahead reaching to
  // t -0.8. STOP is 2.87 m along and 2.27 m across, letters in cells 0.099 m wide: the T's stem
  // at t -3.2, the O hollow at t -3.8 with its left side at t -3.6.
  const auto map = street_with(
      "",
      R"(<object id="1933" type="-1" name="Stencil_ArrowType4L" s="20" t="-1.75" zOffset="0" hdg="0" orientation="-" length="3.0568" width="3.1478" pitch="0" roll="0"/>
         <object id="1993" type="-1" name="Stencil_STOP" s="60" t="-3.5" zOffset="0" hdg="0" orientation="-" length="2.2740" width="2.8653" pitch="0" roll="0"/>
         <object id="9" type="-1" name="Stencil_BIKE" s="80" t="-1.75" zOffset="0" hdg="0" orientation="-" length="2" width="1" pitch="0" roll="0"/>
         <object id="10" type="-1" name="Stencil_BIKE" s="85" t="-1.75" zOffset="0" hdg="0" orientation="-" length="2" width="1" pitch="0" roll="0"/>)");
  auto world = marked_world(map);
  CHECK(world->report.signs == 0);
  CHECK(paint_at(world->scene, 19.0, -2.54));        // the shaft
  CHECK_FALSE(paint_at(world->scene, 19.0, -1.4));   // left of the shaft, behind the bend
  CHECK(paint_at(world->scene, 21.1, -1.15));        // the head, pointing left (+t)
  CHECK_FALSE(paint_at(world->scene, 21.1, -3.0));   // nothing to the right
  CHECK_FALSE(paint_at(world->scene, 21.7, -2.54));  // 3.15 m long
  const ObjectInfo arrow = object_at(world->scene, 19.0, -2.54);
  CHECK(arrow.kind == "road_mark");
  CHECK(arrow.type == "Stencil_ArrowType4L");
  CHECK(arrow.subtype == "arrow_left");
  CHECK(paint_at(world->scene, 60.0, -3.5 + 0.297));  // the T's stem
  CHECK(paint_at(world->scene, 60.0, -3.5 - 0.098));  // the O's left side
  CHECK_FALSE(paint_at(world->scene, 60.0, -3.796));  // inside the O
  CHECK_FALSE(paint_at(world->scene, 61.5, -3.5));    // 2.87 m along
  const ObjectInfo stop = object_at(world->scene, 60.0, -3.5 + 0.297);
  CHECK(stop.text == "STOP");
  CHECK(stop.subtype == "text");
  // An unknown stencil: not painted, one located warning for its name.
  CHECK(down_at(world->scene, 80.0, -1.75).semantic == SemanticClass::kRoad);
  REQUIRE(world->warnings.size() == 1);
  CHECK(world->warnings[0].line > 0);
  CHECK_THAT(world->warnings[0].message, Catch::Contains("Stencil_BIKE"));
}

TEST_CASE("CARLA's short-dash line objects are short white dashes along their outline",
          "[sensors][world][objects][markings]") {
  // As Town04 writes them in its junctions: an untyped object named after the RoadRunner
  // marking style, its open outline the line itself (here 10 m: 5 m along the road, then 5 m
  // turning left at 37 degrees). Six dashes of 0.61 m every 1.83 m, centred: the first from
  // 0.12 m to 0.73 m along the line, the fourth 0.61-1.22 m into the bent leg.
  const auto map = street_with(
      "",
      R"(<object id="1775" type="-1" name="DashedShortSingleWhite" s="40" t="-1.75" zOffset="0" hdg="0" orientation="+" length="9" width="3" pitch="0" roll="0">
           <outline><cornerLocal u="-5" v="0" z="0"/><cornerLocal u="0" v="0" z="0"/><cornerLocal u="4" v="3" z="0"/></outline>
         </object>)");
  auto world = marked_world(map);
  CHECK(world->warnings.empty());
  CHECK(world->report.objects == 1);
  CHECK(paint_at(world->scene, 35.4, -1.75));         // the first dash
  CHECK(paint_at(world->scene, 35.4, -1.75 + 0.06));  // 0.15 m wide
  CHECK_FALSE(paint_at(world->scene, 35.4, -1.75 + 0.1));
  CHECK_FALSE(paint_at(world->scene, 36.3, -1.75));      // the gap
  CHECK(paint_at(world->scene, 37.25, -1.75));           // the second dash
  CHECK_FALSE(paint_at(world->scene, 34.8, -1.75));      // before the first
  CHECK(paint_at(world->scene, 40.732, -1.75 + 0.549));  // the fourth, along the bend
  CHECK_FALSE(paint_at(world->scene, 43.0, -1.75));      // the bounding box is not painted
  const ObjectInfo dash = object_at(world->scene, 35.4, -1.75);
  CHECK(dash.kind == "road_mark");
  CHECK(dash.type == "DashedShortSingleWhite");
  CHECK(dash.subtype == "dashed_short");
  // All dashes are one labelled object.
  CHECK(down_at(world->scene, 35.4, -1.75).instance_id ==
        down_at(world->scene, 40.732, -1.75 + 0.549).instance_id);
}

TEST_CASE("CARLA's broken yellow line objects are yellow dashes of the US centre line",
          "[sensors][world][objects][markings]") {
  // As Town04 writes its one: an untyped object named after the RoadRunner marking style, its
  // open outline the line (here 30 m along the road's centre). Three dashes of 3.05 m every
  // 12.19 m (MUTCD broken line: 10 ft paint, 30 ft gap), centred: 1.285-4.335 m,
  // 13.475-16.525 m and 25.665-28.715 m along the line, 0.125 m wide.
  const auto map = street_with(
      "",
      R"(<object id="1696" type="-1" name="DashedSingleYellow" s="40" t="0" zOffset="0" hdg="0" orientation="+" length="30" width="0" pitch="0" roll="0">
           <outline><cornerLocal u="-15" v="0" z="0"/><cornerLocal u="0" v="0" z="0"/><cornerLocal u="15" v="0" z="0"/></outline>
         </object>)");
  auto world = marked_world(map);
  CHECK(world->warnings.empty());
  CHECK(world->report.objects == 1);
  CHECK_FALSE(paint_at(world->scene, 26.2, 0.0));  // before the first dash
  CHECK(paint_at(world->scene, 26.4, 0.0));        // the first dash
  CHECK(paint_at(world->scene, 29.2, 0.0));
  CHECK(paint_at(world->scene, 27.0, 0.05));  // 0.125 m wide
  CHECK_FALSE(paint_at(world->scene, 27.0, 0.08));
  CHECK_FALSE(paint_at(world->scene, 29.5, 0.0));  // the 9.14 m gap
  CHECK_FALSE(paint_at(world->scene, 38.3, 0.0));
  CHECK(paint_at(world->scene, 38.6, 0.0));  // the second dash
  CHECK(paint_at(world->scene, 53.6, 0.0));  // the third
  CHECK_FALSE(paint_at(world->scene, 53.9, 0.0));
  const ObjectInfo dash = object_at(world->scene, 38.6, 0.0);
  CHECK(dash.kind == "road_mark");
  CHECK(dash.type == "DashedSingleYellow");
  CHECK(dash.subtype == "dashed");
  // All dashes are one labelled object, in yellow paint.
  CHECK(down_at(world->scene, 26.4, 0.0).instance_id ==
        down_at(world->scene, 53.6, 0.0).instance_id);
  const uint32_t id = down_at(world->scene, 38.6, 0.0).instance_id;
  size_t found = 0;
  for (const auto& geometry : world->scene.data().static_geometries) {
    if (geometry.instance_id == id) {
      ++found;
      CHECK(world->scene.material(geometry.material_of(0)).name == "yellow road paint");
    }
  }
  CHECK(found == 1);
}

TEST_CASE("on Town04 the turn arrows ahead of a junction show as lane_marking in the image",
          "[sensors][world][objects][markings]") {
  // Road 23's two lanes carry a left and a right turn arrow at s 97 (objects 1933 and 1937);
  // a camera 1.5 m up in lane -3 at s 89 looks along the road at them.
  const auto map = corsa::test::load_map(corsa::test::kXodrData / "Town04.xodr");
  WorldOptions options;
  options.seed = 3;
  options.vegetation = false;
  options.street_lights = false;
  auto built = corsa::test::build_world_scene(map, options);
  for (const auto& w : built->warnings) {
    CHECK_THAT(w.message, !Catch::Contains("Stencil_"));
    CHECK_THAT(w.message, !Catch::Contains("DashedShortSingleWhite"));
    CHECK_THAT(w.message, !Catch::Contains("DashedSingleYellow"));
  }
  const size_t road = *map.find_road("23");
  const auto arrow_pose = map.world_pose(road, 96.0, -1.75 - 0.79);  // object 1933's shaft
  const RayHit hit = down_at(built->scene, arrow_pose.x, arrow_pose.y);
  CHECK(hit.semantic == SemanticClass::kLaneMarking);
  const auto pose = map.world_pose(road, 89.0, -5.25);
  const Rigid eye = rigid_from_pose(pose.x, pose.y, pose.z + 1.5, pose.h, 0.0, 0.0);
  built->scene.set_entities({});
  const CameraRenderer camera(corsa::test::wide_camera());
  RenderSettings settings;
  settings.outputs.semantic = true;
  CameraMotion motion;
  motion.world_from_body = eye;
  const CameraImages img = camera.render(built->scene, motion, settings);
  // Paint on the road 6.5-10 m ahead (a 240 px focal length, 1.5 m up): the arrows (no lane line
  // crosses there except the broken one between the lanes); its labels name the stencils.
  std::set<std::string> stencils;
  int paint = 0;
  for (int row = img.height / 2 + 35; row < img.height / 2 + 55; ++row) {
    for (int col = 0; col < img.width; ++col) {
      const size_t i = static_cast<size_t>(row) * img.width + col;
      paint += img.semantic[i] == static_cast<uint8_t>(SemanticClass::kLaneMarking) ? 1 : 0;
    }
  }
  const auto labels = static_object_labels(built->scene, img.instance, img.width, img.semantic);
  for (const auto& l : labels) {
    if (l.info.kind == "road_mark") {
      stencils.insert(l.info.type);
    }
  }
  CHECK(paint > 150);
  CHECK(stencils.count("Stencil_ArrowType4L") == 1);
  CHECK(stencils.count("Stencil_ArrowType4R") == 1);
}
