// Oriented boxes seen from above (corsa/engine/oriented_box.h), the one implementation behind
// collisions, the freespace distance conditions and the sweep metrics: distances between boxes,
// their lower bound, and the time until two moving boxes touch. The shortcuts of box_distance
// and the lower bound are checked against the plain computation on random boxes from a fixed
// seed.

#include <algorithm>
#include <array>
#include <bit>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <random>

#include "corsa/engine/oriented_box.h"
#include "geometry/angle.h"

using corsa::engine::OrientedBox;
using Approx = Catch::Detail::Approx;

namespace {

// A box and its velocity (m/s, map frame).
struct Moving {
  OrientedBox box;
  corsa::Vec2 velocity;
};

OrientedBox oriented_box(double x, double y, double h, double length, double width) {
  OrientedBox box;
  box.cx = x;
  box.cy = y;
  box.cos_h = std::cos(h);
  box.sin_h = std::sin(h);
  box.half_length = 0.5 * length;
  box.half_width = 0.5 * width;
  box.z_max = 1.5;
  return box;
}

// A 4 m x 2 m box centred at (x, y), heading h, moving at (vx, vy).
Moving box(double x, double y, double h = 0.0, double vx = 0.0, double vy = 0.0) {
  return {oriented_box(x, y, h, 4.0, 2.0), {vx, vy}};
}

// A 4.6 m x 1.8 m car centred at (x, y), heading h, moving at (vx, vy).
Moving moving(double x, double y, double h, double vx, double vy) {
  return {oriented_box(x, y, h, 4.6, 1.8), {vx, vy}};
}

double free_distance(const Moving& a, const Moving& b) {
  return corsa::engine::box_distance(a.box, b.box);
}

std::optional<double> time_to_contact(const Moving& a, const Moving& b) {
  return corsa::engine::time_to_contact(a.box, a.velocity, b.box, b.velocity);
}

// The plain computation: the least hypot over all 32 corner-edge pairs.
double reference_box_distance(const OrientedBox& a, const OrientedBox& b) {
  const auto corners = [](const OrientedBox& box) {
    const double lx = box.cos_h * box.half_length, ly = box.sin_h * box.half_length;
    const double wx = -box.sin_h * box.half_width, wy = box.cos_h * box.half_width;
    return std::array<corsa::Vec2, 4>{{{box.cx + lx + wx, box.cy + ly + wy},
                                       {box.cx - lx + wx, box.cy - ly + wy},
                                       {box.cx - lx - wx, box.cy - ly - wy},
                                       {box.cx + lx - wx, box.cy + ly - wy}}};
  };
  const auto point_segment = [](corsa::Vec2 p, corsa::Vec2 s0, corsa::Vec2 s1) {
    const double dx = s1.x - s0.x, dy = s1.y - s0.y;
    const double len2 = dx * dx + dy * dy;
    double t = len2 > 0.0 ? ((p.x - s0.x) * dx + (p.y - s0.y) * dy) / len2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    return std::hypot(p.x - (s0.x + t * dx), p.y - (s0.y + t * dy));
  };
  const auto ca = corners(a);
  const auto cb = corners(b);
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      best = std::min(best, point_segment(ca[i], cb[j], cb[(j + 1) % 4]));
      best = std::min(best, point_segment(cb[i], ca[j], ca[(j + 1) % 4]));
    }
  }
  return best;
}

}  // namespace

TEST_CASE("free-space distance is the gap between the boxes", "[engine][geometry]") {
  CHECK(free_distance(box(0, 0), box(10, 0)) == Approx(6.0));  // nose to tail
  CHECK(free_distance(box(0, 0), box(0, 5)) == Approx(3.0));   // side by side
  CHECK(free_distance(box(0, 0), box(3, 0)) == 0.0);           // overlapping
  // Corner to corner: gaps of 2 m in x and 1 m in y.
  CHECK(free_distance(box(0, 0), box(6, 3)) == Approx(std::sqrt(5.0)));
  // Rotated by 90 degrees: its half length now lies along y.
  CHECK(free_distance(box(0, 0), box(0, 6, std::numbers::pi / 2)) == Approx(3.0));
}

TEST_CASE("time to contact follows constant velocities", "[engine][geometry]") {
  // Rear-end: 6 m gap closing at 3 m/s.
  const auto rear = time_to_contact(box(0, 0, 0, 20), box(10, 0, 0, 17));
  REQUIRE(rear);
  CHECK(*rear == Approx(2.0));
  // Head-on: 16 m gap closing at 20 m/s.
  const auto head_on = time_to_contact(box(0, 0, 0, 10), box(20, 0, std::numbers::pi, -10));
  REQUIRE(head_on);
  CHECK(*head_on == Approx(0.8));
  // Overlapping now.
  CHECK(time_to_contact(box(0, 0), box(1, 0.5)) == 0.0);
}

TEST_CASE("no time to contact when the boxes never meet", "[engine][geometry]") {
  CHECK_FALSE(time_to_contact(box(0, 0, 0, 20), box(10, 0, 0, 25)));    // pulling away
  CHECK_FALSE(time_to_contact(box(0, 0, 0, 20), box(10, 3.5, 0, 10)));  // next lane
  CHECK_FALSE(time_to_contact(box(0, 0, 0, 10), box(10, 0, 0, 10)));    // same speed
  CHECK_FALSE(time_to_contact(box(10, 0, 0, 0), box(0, 0, 0, -5)));     // moving away behind
}

TEST_CASE("a crossing vehicle is a contact only if it arrives while the other is there",
          "[engine][geometry]") {
  // Crosses the ego's path 20 m ahead: the ego's box overlaps x=19..21 from 0.85 s to 1.15 s;
  // the crossing car (long axis along y, 11 m to the side, 10 m/s) overlaps y=-1..1 from 0.8 s
  // to 1.4 s. They first touch when both hold: 0.85 s.
  const auto meet = time_to_contact(box(0, 0, 0, 20), box(20, -11, std::numbers::pi / 2, 0, 10));
  REQUIRE(meet);
  CHECK(*meet == Approx(0.85));
  // Far to the side: it passes long after the ego.
  CHECK_FALSE(time_to_contact(box(0, 0, 0, 20), box(20, -100, std::numbers::pi / 2, 0, 10)));
}

TEST_CASE("an entity's box seen from above puts its centre ahead of its reference point",
          "[engine][geometry]") {
  corsa::engine::EntityInfo info;
  info.box = {1.5, 0.0, 0.8, 4.0, 2.0, 1.6};
  corsa::engine::EntityState state;
  state.pose.x = 10.0;
  state.pose.y = 5.0;
  state.pose.h = std::numbers::pi / 2;
  state.speed = 3.0;
  state.lateral_speed = 1.0;
  const OrientedBox f = corsa::engine::box_of(info.box, state.pose);
  const corsa::Vec2 velocity = corsa::engine::velocity_of(state);
  CHECK(f.cx == Approx(10.0).margin(1e-12));
  CHECK(f.cy == Approx(6.5));
  CHECK(velocity.x == Approx(-1.0));  // lateral speed to the left of a north-facing car
  CHECK(velocity.y == Approx(3.0));
  CHECK(f.half_length == 2.0);
  CHECK(f.half_width == 1.0);
}

TEST_CASE("the box distance equals the least distance over every corner-edge pair",
          "[engine][geometry]") {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> position(-30.0, 30.0);
  std::uniform_real_distribution<double> heading(-std::numbers::pi, std::numbers::pi);
  std::uniform_real_distribution<double> size(0.5, 6.0);
  int separated = 0;
  for (int i = 0; i < 20000; ++i) {
    const OrientedBox a = oriented_box(position(random), position(random), heading(random),
                                       size(random), size(random));
    // Every fourth pair parallel (ties between candidates), the rest at any angle.
    const double h = i % 4 == 0 ? std::atan2(a.sin_h, a.cos_h) : heading(random);
    const OrientedBox b =
        oriented_box(position(random), position(random), h, size(random), size(random));
    const double d = corsa::engine::box_distance(a, b);
    if (d > 0.0) {
      ++separated;
      REQUIRE(d == reference_box_distance(a, b));  // bit for bit
    }
  }
  CHECK(separated > 15000);
  // Far from the origin (UTM-sized coordinates) and nearly touching.
  for (int i = 0; i < 2000; ++i) {
    const double x = 3.0e5 + position(random), y = 4.1e6 + position(random);
    const OrientedBox a = oriented_box(x, y, heading(random), 4.5, 1.8);
    const double h = heading(random);
    const OrientedBox b =
        oriented_box(x + 4.6 * std::cos(h), y + 4.6 * std::sin(h), heading(random), 4.5, 1.8);
    const double d = corsa::engine::box_distance(a, b);
    if (d > 0.0) REQUIRE(d == reference_box_distance(a, b));
  }
  // Overlapping boxes are 0 apart.
  CHECK(corsa::engine::box_distance(oriented_box(0, 0, 0, 4, 2), oriented_box(1, 1, 0.3, 4, 2)) ==
        0.0);
}

TEST_CASE("the distance's lower bound never exceeds the exact distance or contact time",
          "[engine][geometry]") {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> position(-40.0, 40.0);
  std::uniform_real_distribution<double> heading(-std::numbers::pi, std::numbers::pi);
  std::uniform_real_distribution<double> velocity(-30.0, 30.0);
  for (int i = 0; i < 20000; ++i) {
    const Moving a = moving(position(random), position(random), heading(random), velocity(random),
                            velocity(random));
    const Moving b = moving(position(random), position(random), heading(random), velocity(random),
                            velocity(random));
    const double bound = corsa::engine::box_distance_lower_bound(a.box, b.box);
    const double distance = free_distance(a, b);
    REQUIRE(bound < distance);
    if (distance > 0.0) REQUIRE(distance == reference_box_distance(a.box, b.box));  // bit for bit
    if (const auto ttc = time_to_contact(a, b); ttc && bound > 0.0) {
      const double speed = std::hypot(b.velocity.x - a.velocity.x, b.velocity.y - a.velocity.y);
      REQUIRE(bound / speed < *ttc);
    }
  }
  // Far apart, the bound is close to the real gap: centres 100 m apart, half diagonals 2.47 m.
  const double far = corsa::engine::box_distance_lower_bound(moving(0, 0, 0, 0, 0).box,
                                                             moving(100, 0, 0, 0, 0).box);
  CHECK(far == Approx(100.0 - 2.0 * std::hypot(2.3, 0.9)).margin(1e-5));
}

// remainder_full_turn answers without the library for the angles near the range it wraps to:
// every answer must have the bits std::remainder(angle, 2 pi) has, at the edges of its shortcuts
// (+-pi, +-2 pi, +-3 pi, +-4 pi and their neighbours), for signed zeros and the non-finite, and
// over random angles of both signs.
TEST_CASE("remainder_full_turn gives std::remainder's bits", "[engine][geometry]") {
  using corsa::engine::detail::remainder_full_turn;
  constexpr double kTurn = 2.0 * std::numbers::pi;
  int checked = 0;
  int differing = 0;
  double first_differing = 0.0;
  const auto same = [&](double angle) {
    const double expected = std::remainder(angle, kTurn);
    const double got = remainder_full_turn(angle);
    ++checked;
    if (std::bit_cast<uint64_t>(got) != std::bit_cast<uint64_t>(expected) && differing++ == 0) {
      first_differing = angle;
    }
  };
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (const double special : {0.0, -0.0, kInf, -kInf, std::numeric_limits<double>::quiet_NaN(),
                               std::numeric_limits<double>::denorm_min(), 1e300, -1e300}) {
    same(special);
  }
  for (const double edge : {0.5 * kTurn, kTurn, 1.5 * kTurn, 2.0 * kTurn, 2.5 * kTurn}) {
    for (const double sign : {1.0, -1.0}) {
      double below = sign * edge;
      double above = sign * edge;
      same(below);
      for (int k = 0; k < 64; ++k) {
        below = std::nextafter(below, -kInf);
        above = std::nextafter(above, kInf);
        same(below);
        same(above);
      }
    }
  }
  std::mt19937_64 random(20261128);
  std::uniform_real_distribution<double> wide(-6.0 * kTurn, 6.0 * kTurn);
  std::uniform_real_distribution<double> small(-1e-3, 1e-3);
  for (int k = 0; k < 200000; ++k) {
    same(wide(random));
    same(small(random));
  }
  INFO("the first angle that differs: " << first_differing);
  CHECK(differing == 0);
  CHECK(checked > 400000);
}

// ReachPositionCondition (conditions/reach_position_condition.cpp) answers "farther than the
// tolerance" without hypot when one axis alone is farther: that rests on hypot(dx, dy) never
// falling below max(|dx|, |dy|), which a rounding within an ulp of the exact length cannot do.
// Checked on the library at hand where it is tightest: one axis far shorter than the other (the
// exact length a hair above the longer), equal axes, and random pairs.
TEST_CASE("hypot is never below the longer axis", "[engine][geometry]") {
  std::mt19937_64 random(1128);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<double> exponent(-30.0, 30.0);
  int below = 0;
  const auto check = [&](double dx, double dy) {
    below += std::hypot(dx, dy) < std::max(std::abs(dx), std::abs(dy)) ? 1 : 0;
  };
  for (int k = 0; k < 200000; ++k) {
    const double a = unit(random) * std::exp2(exponent(random));
    const double b = unit(random) * std::exp2(exponent(random));
    check(a, b);
    check(a, a * 1e-9);
    check(a, a);
    check(std::nextafter(a, 0.0), a);
  }
  CHECK(below == 0);
}
