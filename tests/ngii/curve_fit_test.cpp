#include "corsa/ngii/curve_fit.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <iterator>
#include <random>
#include <variant>

#include "clothoid.h"

using corsa::ngii::CurveFit;
using corsa::ngii::fit_plan_view;
using corsa::ngii::fit_profile;
using corsa::ngii::Point2;
using corsa::ngii::ProfileSample;
using corsa::ngii::detail::Clothoid;
using corsa::ngii::detail::clothoid_at;

namespace {

/// A planView record as a clothoid (line and arc are special cases).
Clothoid as_clothoid(const corsa::xodr::Geometry& g) {
  Clothoid c{g.x, g.y, g.hdg, 0.0, 0.0};
  if (const auto* arc = std::get_if<corsa::xodr::ArcGeometry>(&g.shape)) {
    c.k0 = arc->curvature;
  } else if (const auto* spiral = std::get_if<corsa::xodr::SpiralGeometry>(&g.shape)) {
    c.k0 = spiral->curv_start;
    c.k1 = (spiral->curv_end - spiral->curv_start) / g.length;
  }
  return c;
}

/// Points of the fitted chain every `step` metres.
std::vector<Point2> sample(const CurveFit& fit, double step) {
  std::vector<Point2> out;
  for (const auto& g : fit.geometries) {
    const Clothoid c = as_clothoid(g);
    for (double s = 0.0; s < g.length; s += step) {
      const auto p = clothoid_at(c, s);
      out.push_back({p.x, p.y});
    }
  }
  return out;
}

double distance_to_polyline(const Point2& p, const std::vector<Point2>& line) {
  double best = 1e300;
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    const double dx = line[i + 1].x - line[i].x, dy = line[i + 1].y - line[i].y;
    const double len2 = dx * dx + dy * dy;
    double f = len2 > 0 ? ((p.x - line[i].x) * dx + (p.y - line[i].y) * dy) / len2 : 0.0;
    f = std::clamp(f, 0.0, 1.0);
    best = std::min(best, std::hypot(p.x - line[i].x - f * dx, p.y - line[i].y - f * dy));
  }
  return best;
}

/// Joints are continuous in position and heading.
void check_g1(const CurveFit& fit) {
  for (size_t i = 0; i + 1 < fit.geometries.size(); ++i) {
    const auto& g = fit.geometries[i];
    const auto end = clothoid_at(as_clothoid(g), g.length);
    const auto& next = fit.geometries[i + 1];
    CHECK(std::hypot(end.x - next.x, end.y - next.y) < 1e-9);
    CHECK(std::abs(std::remainder(end.theta - next.hdg, 2 * M_PI)) < 1e-9);
    CHECK(next.s == Approx(g.s + g.length));
  }
}

}  // namespace

TEST_CASE("a straight polyline becomes one line", "[ngii][fit]") {
  std::vector<Point2> points;
  for (int i = 0; i <= 100; ++i) {
    points.push_back({1000.0 + 0.8 * i, 2000.0 + 0.6 * i});
  }
  const CurveFit fit = fit_plan_view(points);
  REQUIRE(fit.geometries.size() == 1);
  CHECK(std::holds_alternative<corsa::xodr::LineGeometry>(fit.geometries[0].shape));
  CHECK(fit.length == Approx(100.0).epsilon(1e-9));
  CHECK(fit.geometries[0].hdg == Approx(std::atan2(0.6, 0.8)));
  CHECK(fit.max_error < 1e-6);
  CHECK(fit.kinks == 0);
}

TEST_CASE("a circular arc becomes one arc record", "[ngii][fit]") {
  const double radius = 40.0;
  std::vector<Point2> points;
  for (int i = 0; i <= 60; ++i) {  // 90 degrees in 1.5 degree steps
    const double a = i * M_PI / 120.0;
    points.push_back({radius * std::sin(a), radius - radius * std::cos(a)});
  }
  const CurveFit fit = fit_plan_view(points);
  REQUIRE(fit.geometries.size() == 1);
  const auto* arc = std::get_if<corsa::xodr::ArcGeometry>(&fit.geometries[0].shape);
  REQUIRE(arc != nullptr);
  CHECK(arc->curvature == Approx(1.0 / radius).epsilon(1e-3));
  CHECK(fit.length == Approx(radius * M_PI / 2).epsilon(1e-3));
  CHECK(fit.max_error < 0.01);
}

TEST_CASE("line, clothoid and arc are recovered within the tolerance with few records",
          "[ngii][fit][spiral]") {
  // Truth: 50 m line, 40 m clothoid 0 -> 1/30, 30 m arc, digitised every 1.3 m.
  std::vector<Point2> truth;
  const Clothoid line{0, 0, 0.3, 0, 0};
  for (double s = 0; s < 50.0; s += 0.1) {
    const auto p = clothoid_at(line, s);
    truth.push_back({p.x, p.y});
  }
  const auto e1 = clothoid_at(line, 50.0);
  const Clothoid spiral{e1.x, e1.y, e1.theta, 0.0, (1.0 / 30.0) / 40.0};
  for (double s = 0; s < 40.0; s += 0.1) {
    const auto p = clothoid_at(spiral, s);
    truth.push_back({p.x, p.y});
  }
  const auto e2 = clothoid_at(spiral, 40.0);
  const Clothoid arc{e2.x, e2.y, e2.theta, 1.0 / 30.0, 0.0};
  for (double s = 0; s <= 30.0; s += 0.1) {
    const auto p = clothoid_at(arc, s);
    truth.push_back({p.x, p.y});
  }
  std::vector<Point2> vertices;
  for (size_t i = 0; i < truth.size(); i += 13) {
    vertices.push_back(truth[i]);
  }
  vertices.push_back(truth.back());
  const CurveFit fit = fit_plan_view(vertices);
  CHECK(fit.geometries.size() <= 5);
  CHECK(fit.max_error <= 0.05);
  CHECK(fit.kinks == 0);
  CHECK(fit.length == Approx(120.0).margin(0.2));
  check_g1(fit);
  for (const Point2& p : sample(fit, 0.5)) {
    CHECK(distance_to_polyline(p, truth) < 0.05);
  }
}

TEST_CASE("noisy survey points give far fewer records than vertices", "[ngii][fit]") {
  // A 300 m S-bend (two opposite arcs of radius 150 m) with +-2 cm noise every 2 m.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> noise(-0.02, 0.02);
  std::vector<Point2> points;
  const Clothoid first{0, 0, 0, 1.0 / 150.0, 0};
  const auto mid = clothoid_at(first, 150.0);
  const Clothoid second{mid.x, mid.y, mid.theta, -1.0 / 150.0, 0};
  for (double s = 0; s <= 300.0; s += 2.0) {
    const auto p = s <= 150.0 ? clothoid_at(first, s) : clothoid_at(second, s - 150.0);
    points.push_back({p.x + noise(rng), p.y + noise(rng)});
  }
  const CurveFit fit = fit_plan_view(points);
  CHECK(fit.geometries.size() < points.size() / 10);
  CHECK(fit.max_error <= 0.05);
  CHECK(fit.kinks == 0);
  check_g1(fit);
}

TEST_CASE("a tighter tolerance follows the points more closely", "[ngii][fit]") {
  std::vector<Point2> points;
  for (double s = 0; s <= 100.0; s += 1.0) {
    points.push_back({s, 0.3 * std::sin(s / 8.0)});
  }
  corsa::ngii::CurveFitOptions options;
  options.tolerance = 0.01;
  const CurveFit fine = fit_plan_view(points, options);
  options.tolerance = 0.2;
  const CurveFit coarse = fit_plan_view(points, options);
  CHECK(fine.max_error <= 0.01);
  CHECK(coarse.max_error <= 0.2);
  CHECK(fine.geometries.size() > coarse.geometries.size());
}

TEST_CASE("a right-angle corner is reported as a kink and still followed", "[ngii][fit]") {
  const std::vector<Point2> points = {{0, 0}, {10, 0}, {20, 0}, {20, 10}, {20, 20}};
  const CurveFit fit = fit_plan_view(points);
  CHECK(fit.kinks >= 1);
  CHECK(fit.max_error <= 0.05);
  CHECK(fit.length == Approx(40.0).margin(0.5));
}

TEST_CASE("duplicate vertices are ignored", "[ngii][fit]") {
  const std::vector<Point2> points = {{0, 0}, {0, 0}, {5, 0}, {5, 0}, {10, 0}};
  const CurveFit fit = fit_plan_view(points);
  REQUIRE(fit.geometries.size() == 1);
  CHECK(fit.length == Approx(10.0));
}

TEST_CASE("profiles are fitted by few C1 cubics within the tolerance", "[ngii][fit][profile]") {
  SECTION("a constant is one constant piece") {
    std::vector<ProfileSample> samples;
    for (int i = 0; i <= 50; ++i) {
      samples.push_back({i * 2.0, 3.25});
    }
    const auto fit = fit_profile(samples, 0.01);
    REQUIRE(fit.pieces.size() == 1);
    CHECK(fit.pieces[0].a == Approx(3.25));
    CHECK(fit.pieces[0].b == 0.0);
    CHECK(fit.pieces[0].c == 0.0);
    CHECK(fit.pieces[0].d == 0.0);
  }
  SECTION("a cubic is one piece") {
    std::vector<ProfileSample> samples;
    for (int i = 0; i <= 40; ++i) {
      const double s = 10.0 + i;
      const double x = s - 10.0;
      samples.push_back({s, 30.0 + 0.02 * x - 0.001 * x * x + 1e-5 * x * x * x});
    }
    const auto fit = fit_profile(samples, 0.01);
    REQUIRE(fit.pieces.size() == 1);
    CHECK(fit.pieces[0].s == 10.0);
    CHECK(fit.pieces[0].b == Approx(0.02));
    CHECK(fit.max_error < 1e-9);
  }
  SECTION("a widening lane is followed within the tolerance, continuously, kinks kept") {
    std::vector<ProfileSample> samples;
    for (int i = 0; i <= 100; ++i) {
      const double s = i;
      samples.push_back({s, s < 40 ? 0.0 : std::min(3.0, (s - 40) * 0.15)});
    }
    const auto fit = fit_profile(samples, 0.02);
    CHECK(fit.max_error <= 0.02);
    // Constant, ramp, constant: the slope breaks are joints with a free slope.
    CHECK(fit.pieces.size() == 3);
    for (size_t i = 0; i + 1 < fit.pieces.size(); ++i) {
      const auto& a = fit.pieces[i];
      const auto& b = fit.pieces[i + 1];
      CHECK(a.value(b.s) == Approx(b.a).margin(1e-9));
    }
    for (double s = 0.0; s <= 100.0; s += 0.25) {
      const double truth = s < 40 ? 0.0 : std::min(3.0, (s - 40) * 0.15);
      const auto& piece = *std::prev(
          std::upper_bound(fit.pieces.begin(), fit.pieces.end(), s,
                           [](double v, const corsa::xodr::Poly3& p) { return v < p.s; }));
      CHECK(std::abs(piece.value(s) - truth) <= 0.02);
    }
  }
  SECTION("noisy samples give few pieces that do not ring between samples") {
    std::vector<ProfileSample> samples;
    for (int i = 0; i <= 400; ++i) {
      samples.push_back({i * 1.0, 3.3 + ((i * 7919) % 13 - 6) * 0.003});  // +-1.8 cm
    }
    const auto fit = fit_profile(samples, 0.02);
    CHECK(fit.max_error <= 0.02);
    CHECK(fit.pieces.size() < 20);
    for (const auto& piece : fit.pieces) {
      for (double ds = 0.0; ds < 2.0; ds += 0.1) {
        CHECK(std::abs(piece.value(piece.s + ds) - 3.3) < 0.04);
      }
    }
  }
}
