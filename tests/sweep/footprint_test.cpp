#include "footprint.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

using corsa::sweep::detail::Footprint;
using corsa::sweep::detail::footprint_of;
using corsa::sweep::detail::free_distance;
using corsa::sweep::detail::time_to_contact;
using Approx = Catch::Detail::Approx;

namespace {

// A 4 m x 2 m box centred at (x, y), heading h, moving at (vx, vy).
Footprint box(double x, double y, double h = 0.0, double vx = 0.0, double vy = 0.0) {
  Footprint f;
  f.center = {x, y};
  f.axis = {std::cos(h), std::sin(h)};
  f.half_length = 2.0;
  f.half_width = 1.0;
  f.velocity = {vx, vy};
  return f;
}

}  // namespace

TEST_CASE("free-space distance is the gap between the boxes", "[sweep][metrics]") {
  CHECK(free_distance(box(0, 0), box(10, 0)) == Approx(6.0));  // nose to tail
  CHECK(free_distance(box(0, 0), box(0, 5)) == Approx(3.0));   // side by side
  CHECK(free_distance(box(0, 0), box(3, 0)) == 0.0);           // overlapping
  // Corner to corner: gaps of 2 m in x and 1 m in y.
  CHECK(free_distance(box(0, 0), box(6, 3)) == Approx(std::sqrt(5.0)));
  // Rotated by 90 degrees: its half length now lies along y.
  CHECK(free_distance(box(0, 0), box(0, 6, std::numbers::pi / 2)) == Approx(3.0));
}

TEST_CASE("time to contact follows constant velocities", "[sweep][metrics]") {
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

TEST_CASE("no time to contact when the boxes never meet", "[sweep][metrics]") {
  CHECK_FALSE(time_to_contact(box(0, 0, 0, 20), box(10, 0, 0, 25)));    // pulling away
  CHECK_FALSE(time_to_contact(box(0, 0, 0, 20), box(10, 3.5, 0, 10)));  // next lane
  CHECK_FALSE(time_to_contact(box(0, 0, 0, 10), box(10, 0, 0, 10)));    // same speed
  CHECK_FALSE(time_to_contact(box(10, 0, 0, 0), box(0, 0, 0, -5)));     // moving away behind
}

TEST_CASE("a crossing vehicle is a contact only if it arrives while the other is there",
          "[sweep][metrics]") {
  // Crosses the ego's path 20 m ahead: the ego's box overlaps x=19..21 from 0.85 s to 1.15 s;
  // the crossing car (long axis along y, 11 m to the side, 10 m/s) overlaps y=-1..1 from 0.8 s
  // to 1.4 s. They first touch when both hold: 0.85 s.
  const auto meet = time_to_contact(box(0, 0, 0, 20), box(20, -11, std::numbers::pi / 2, 0, 10));
  REQUIRE(meet);
  CHECK(*meet == Approx(0.85));
  // Far to the side: it passes long after the ego.
  CHECK_FALSE(time_to_contact(box(0, 0, 0, 20), box(20, -100, std::numbers::pi / 2, 0, 10)));
}

TEST_CASE("an entity's footprint puts the box centre ahead of its reference point",
          "[sweep][metrics]") {
  corsa::engine::EntityInfo info;
  info.box = {1.5, 0.0, 0.8, 4.0, 2.0, 1.6};
  corsa::engine::EntityState state;
  state.pose.x = 10.0;
  state.pose.y = 5.0;
  state.pose.h = std::numbers::pi / 2;
  state.speed = 3.0;
  state.lateral_speed = 1.0;
  const Footprint f = footprint_of(info, state);
  CHECK(f.center.x == Approx(10.0).margin(1e-12));
  CHECK(f.center.y == Approx(6.5));
  CHECK(f.velocity.x == Approx(-1.0));  // lateral speed to the left of a north-facing car
  CHECK(f.velocity.y == Approx(3.0));
  CHECK(f.half_length == 2.0);
  CHECK(f.half_width == 1.0);
}
