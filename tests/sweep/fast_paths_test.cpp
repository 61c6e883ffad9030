// The sweep's hot paths and their shortcuts: the trajectory CSV's fixed-decimal number text, the
// engine's box distance (hypot only of the candidates that can be nearest) and the metrics'
// broad phase. Each shortcut is checked against the plain computation it replaces, on random
// boxes from a fixed seed.

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <charconv>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>

#include "footprint.h"
#include "geometry/oriented_box.h"
#include "output/decimal_text.h"

namespace {

using corsa::engine::detail::OrientedBox;
using corsa::sweep::detail::Footprint;

std::string decimal(double value, int decimals) {
  char buffer[corsa::engine::detail::kDecimalTextMax];
  return std::string(buffer, corsa::engine::detail::write_decimal(buffer, value, decimals));
}

double read(const std::string& text) {
  double value = 0.0;
  std::from_chars(text.data(), text.data() + text.size(), value);
  return value;
}

// The distance box_distance computed before: the least hypot over all 32 corner-edge pairs.
double reference_box_distance(const OrientedBox& a, const OrientedBox& b) {
  const auto corners = [](const OrientedBox& box) {
    const double lx = box.cos_h * box.half_length, ly = box.sin_h * box.half_length;
    const double wx = -box.sin_h * box.half_width, wy = box.cos_h * box.half_width;
    return std::array<std::array<double, 2>, 4>{{{box.cx + lx + wx, box.cy + ly + wy},
                                                 {box.cx - lx + wx, box.cy - ly + wy},
                                                 {box.cx - lx - wx, box.cy - ly - wy},
                                                 {box.cx + lx - wx, box.cy + ly - wy}}};
  };
  const auto point_segment = [](const std::array<double, 2>& p, const std::array<double, 2>& s0,
                                const std::array<double, 2>& s1) {
    const double dx = s1[0] - s0[0], dy = s1[1] - s0[1];
    const double len2 = dx * dx + dy * dy;
    double t = len2 > 0.0 ? ((p[0] - s0[0]) * dx + (p[1] - s0[1]) * dy) / len2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    return std::hypot(p[0] - (s0[0] + t * dx), p[1] - (s0[1] + t * dy));
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

// The free distance the metrics computed before: the least over all 32 corner-edge pairs.
double reference_free_distance(const Footprint& a, const Footprint& b) {
  const auto point_segment = [](corsa::sweep::detail::Vec2 p, corsa::sweep::detail::Vec2 s0,
                                corsa::sweep::detail::Vec2 s1) {
    const double dx = s1.x - s0.x, dy = s1.y - s0.y;
    const double len2 = dx * dx + dy * dy;
    const double u =
        len2 > 0.0 ? std::clamp(((p.x - s0.x) * dx + (p.y - s0.y) * dy) / len2, 0.0, 1.0) : 0.0;
    const double ex = p.x - s0.x - u * dx, ey = p.y - s0.y - u * dy;
    return std::sqrt(ex * ex + ey * ey);
  };
  const auto ca = a.corners();
  const auto cb = b.corners();
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < 4; ++i) {
    for (size_t j = 0; j < 4; ++j) {
      best = std::min(best, point_segment(ca[i], cb[j], cb[(j + 1) % 4]));
      best = std::min(best, point_segment(cb[i], ca[j], ca[(j + 1) % 4]));
    }
  }
  return best;
}

std::string exact(double value) {
  char buffer[corsa::engine::detail::kDecimalTextMax];
  return std::string(buffer, corsa::engine::detail::write_exact(buffer, value));
}

std::string shortest(double value) {
  char buffer[64];
  return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, value).ptr);
}

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

Footprint footprint(double x, double y, double h, double vx, double vy) {
  Footprint f;
  f.center = {x, y};
  f.axis = {std::cos(h), std::sin(h)};
  f.half_length = 2.3;
  f.half_width = 0.9;
  f.velocity = {vx, vy};
  return f;
}

}  // namespace

TEST_CASE("trajectory numbers are rounded to fixed decimals without trailing zeros",
          "[sweep][output]") {
  CHECK(decimal(50.0, 6) == "50");
  CHECK(decimal(-5.625, 6) == "-5.625");
  CHECK(decimal(32.19999999999999, 6) == "32.2");
  CHECK(decimal(0.05, 6) == "0.05");
  CHECK(decimal(-0.0000504, 6) == "-0.00005");
  CHECK(decimal(1.125, 2) == "1.13");  // halves away from zero
  CHECK(decimal(-2.5, 0) == "-3");
  CHECK(decimal(0.9999999996, 9) == "1");  // the carry reaches the integer part
  CHECK(decimal(-0.0000004, 6) == "0");    // never "-0"
  CHECK(decimal(-0.0, 6) == "0");
  CHECK(decimal(3.14159265358979, 9) == "3.141592654");
  CHECK(decimal(-1e-9, 9) == "-0.000000001");
  CHECK(decimal(7.5, 0) == "8");
}

TEST_CASE("numbers beyond exact scaling fall back to the shortest round-trip text",
          "[sweep][output]") {
  CHECK(decimal(1e20, 6) == "1e+20");
  CHECK(decimal(-2.5e10, 6) == "-2.5e+10");
  CHECK(decimal(std::numeric_limits<double>::infinity(), 6) == "inf");
  CHECK(decimal(std::nan(""), 9) == "nan");
  // Just below the limit the text is still the rounded fixed-decimal one.
  CHECK(decimal(8.9e9 + 0.25, 6) == "8900000000.25");
}

TEST_CASE("trajectory times are exact: the shortest text of every step's time", "[sweep][output]") {
  CHECK(exact(0.0) == "0");
  CHECK(exact(0.49) == "0.49");
  CHECK(exact(0.1 + 0.2) == "0.30000000000000004");  // off the 9-decimal grid: to_chars
  CHECK(exact(1e-12) == "1e-12");
  CHECK(exact(1e12 / 3.0) == shortest(1e12 / 3.0));
  for (int k = 1; k < 200000; ++k) {
    // Times as a fixed step gives them (tick / steps per second), and as a product that may be
    // off the decimal grid (tick * dt): each reads back exactly, and matches to_chars.
    for (const double t : {k / 100.0, k * 0.01, k / 60.0, k * 0.001}) {
      const std::string text = exact(t);
      REQUIRE(read(text) == t);
      if (t >= 0.001) REQUIRE(text == shortest(t));
    }
  }
}

TEST_CASE("fixed-decimal text reads back within half a unit of its last place", "[sweep][output]") {
  std::mt19937_64 random(20261122);
  std::uniform_real_distribution<double> value(-5000.0, 5000.0);
  std::uniform_int_distribution<int> places(0, 9);
  for (int i = 0; i < 20000; ++i) {
    const double v = value(random) / std::pow(10.0, places(random));
    const int decimals = places(random);
    const std::string text = decimal(v, decimals);
    REQUIRE(text.find('e') == std::string::npos);
    const double half_unit = 0.5 * std::pow(10.0, -decimals);
    CHECK(std::fabs(read(text) - v) <= half_unit * (1.0 + 1e-9) + 1e-12 * std::fabs(v));
    CHECK(text.back() != '.');
    CHECK((text.find('.') == std::string::npos || text.back() != '0'));
  }
}

TEST_CASE("the box distance equals the least distance over every corner-edge pair",
          "[sweep][geometry]") {
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
    const double d = corsa::engine::detail::box_distance(a, b);
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
    const double d = corsa::engine::detail::box_distance(a, b);
    if (d > 0.0) REQUIRE(d == reference_box_distance(a, b));
  }
  // Overlapping boxes are 0 apart.
  CHECK(corsa::engine::detail::box_distance(oriented_box(0, 0, 0, 4, 2),
                                            oriented_box(1, 1, 0.3, 4, 2)) == 0.0);
}

TEST_CASE("the metrics' broad phase never exceeds the exact free distance or contact time",
          "[sweep][metrics]") {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> position(-40.0, 40.0);
  std::uniform_real_distribution<double> heading(-std::numbers::pi, std::numbers::pi);
  std::uniform_real_distribution<double> velocity(-30.0, 30.0);
  for (int i = 0; i < 20000; ++i) {
    const Footprint a = footprint(position(random), position(random), heading(random),
                                  velocity(random), velocity(random));
    const Footprint b = footprint(position(random), position(random), heading(random),
                                  velocity(random), velocity(random));
    const double bound = corsa::sweep::detail::free_distance_bound(a, b);
    const double distance = corsa::sweep::detail::free_distance(a, b);
    REQUIRE(bound < distance);
    if (distance > 0.0) REQUIRE(distance == reference_free_distance(a, b));  // bit for bit
    if (const auto ttc = corsa::sweep::detail::time_to_contact(a, b); ttc && bound > 0.0) {
      const double speed = std::hypot(b.velocity.x - a.velocity.x, b.velocity.y - a.velocity.y);
      REQUIRE(bound / speed < *ttc);
    }
  }
  // Far apart, the bound is close to the real gap: centres 100 m apart, half diagonals 2.47 m.
  const double far = corsa::sweep::detail::free_distance_bound(footprint(0, 0, 0, 0, 0),
                                                               footprint(100, 0, 0, 0, 0));
  CHECK(far == Approx(100.0 - 2.0 * std::hypot(2.3, 0.9)).margin(1e-5));
}
