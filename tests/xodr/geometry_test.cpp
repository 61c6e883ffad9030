#include "corsa/xodr/geometry.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

using namespace corsa::xodr;

namespace {

/// Independent reference for a clothoid: Simpson integration of the heading θ(σ).
RefPoint integrate_spiral(double k0, double k1, double length, double ds) {
  const double c = (k1 - k0) / length;
  const int n = 20000;
  const double h = ds / n;
  double x = 0.0;
  double y = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double sigma = i * h;
    const double theta = k0 * sigma + 0.5 * c * sigma * sigma;
    const double w = (i == 0 || i == n) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    x += w * std::cos(theta);
    y += w * std::sin(theta);
  }
  return RefPoint{x * h / 3.0, y * h / 3.0, k0 * ds + 0.5 * c * ds * ds, k0 + c * ds};
}

Geometry make(GeometryShape shape, double length, double x = 10.0, double y = -5.0,
              double hdg = 0.4) {
  return Geometry{.x = x, .y = y, .hdg = hdg, .length = length, .shape = shape};
}

}  // namespace

TEST_CASE("a line runs along its heading", "[xodr][geometry][line]") {
  const RefPoint p = evaluate_geometry(make(LineGeometry{}, 100.0), 30.0);
  CHECK(p.x == Approx(10.0 + 30.0 * std::cos(0.4)).margin(1e-12));
  CHECK(p.y == Approx(-5.0 + 30.0 * std::sin(0.4)).margin(1e-12));
  CHECK(p.hdg == Approx(0.4));
  CHECK(p.curvature == 0.0);
}

TEST_CASE("an arc is a circle of radius 1/curvature", "[xodr][geometry][arc]") {
  SECTION("left turn, a quarter circle") {
    const double r = 50.0;
    const RefPoint p = evaluate_geometry(make(ArcGeometry{1.0 / r}, 100.0, 0.0, 0.0, 0.0),
                                         0.5 * std::numbers::pi * r);
    CHECK(p.x == Approx(r).margin(1e-10));
    CHECK(p.y == Approx(r).margin(1e-10));
    CHECK(p.hdg == Approx(0.5 * std::numbers::pi));
    CHECK(p.curvature == Approx(0.02));
  }
  SECTION("right turn: every point is at the radius from the centre") {
    const double k = -0.01;
    const Geometry g = make(ArcGeometry{k}, 200.0);
    // Centre is to the right of the start heading.
    const double cx = g.x + std::sin(g.hdg) / -k;
    const double cy = g.y - std::cos(g.hdg) / -k;
    for (double ds = 0.0; ds <= 200.0; ds += 25.0) {
      const RefPoint p = evaluate_geometry(g, ds);
      CHECK(std::hypot(p.x - cx, p.y - cy) == Approx(100.0).margin(1e-9));
      CHECK(p.hdg == Approx(g.hdg + k * ds).margin(1e-12));
    }
  }
  SECTION("a tiny curvature stays accurate (no 1 - cos cancellation)") {
    const RefPoint p = evaluate_arc(ArcGeometry{1e-9}, 100.0);
    CHECK(p.y == Approx(0.5 * 1e-9 * 100.0 * 100.0).epsilon(1e-9));
  }
}

TEST_CASE("spirals follow the clothoid for any start and end curvature",
          "[xodr][geometry][spiral]") {
  struct Case {
    double k0, k1, length;
  };
  const Case cases[] = {
      {0.0, 0.02, 50.0},        {0.01, 0.03, 80.0},     {0.02, -0.02, 60.0}, {-0.05, 0.0, 40.0},
      {0.3, 0.5, 100.0},        {0.1, 0.1000001, 30.0},  // nearly an arc: quadrature branch
      {-0.002, -0.0021, 500.0},
  };
  for (const Case& c : cases) {
    for (const double fraction : {0.0, 0.25, 0.5, 1.0}) {
      const double ds = fraction * c.length;
      const RefPoint ours = evaluate_spiral(SpiralGeometry{c.k0, c.k1}, c.length, ds);
      const RefPoint ref = integrate_spiral(c.k0, c.k1, c.length, ds);
      INFO("k0 " << c.k0 << " k1 " << c.k1 << " L " << c.length << " ds " << ds);
      CHECK(ours.x == Approx(ref.x).margin(1e-9));
      CHECK(ours.y == Approx(ref.y).margin(1e-9));
      CHECK(ours.hdg == Approx(ref.hdg).margin(1e-12));
      CHECK(ours.curvature == Approx(ref.curvature).margin(1e-15));
    }
  }
}

TEST_CASE("a spiral with equal end curvatures is an arc", "[xodr][geometry][spiral]") {
  const RefPoint spiral = evaluate_spiral(SpiralGeometry{0.01, 0.01}, 100.0, 70.0);
  const RefPoint arc = evaluate_arc(ArcGeometry{0.01}, 70.0);
  CHECK(spiral.x == Approx(arc.x).margin(1e-12));
  CHECK(spiral.y == Approx(arc.y).margin(1e-12));
}

TEST_CASE("poly3 is parametrised by arc length", "[xodr][geometry][poly3]") {
  SECTION("a straight slope") {
    const RefPoint p = evaluate_poly3(Poly3Geometry{0.0, 0.1, 0.0, 0.0}, 10.0);
    CHECK(p.x == Approx(10.0 / std::sqrt(1.01)).margin(1e-10));
    CHECK(p.y == Approx(1.0 / std::sqrt(1.01)).margin(1e-10));
    CHECK(p.hdg == Approx(std::atan(0.1)));
  }
  SECTION("a parabola: the point lies on v(u) and the arc length to it is ds") {
    const Poly3Geometry poly{0.0, 0.0, 0.01, 0.0};
    const double ds = 40.0;
    const RefPoint p = evaluate_poly3(poly, ds);
    CHECK(p.y == Approx(0.01 * p.x * p.x).margin(1e-10));
    // ∫0^u sqrt(1 + (0.02 x)²) dx in closed form.
    const double a = 0.02 * p.x;
    const double length = (a * std::sqrt(1.0 + a * a) + std::asinh(a)) / (2.0 * 0.02);
    CHECK(length == Approx(ds).margin(1e-9));
    CHECK(p.curvature == Approx(0.02 / std::pow(1.0 + a * a, 1.5)).margin(1e-12));
  }
}

TEST_CASE("paramPoly3 with pRange normalized and arcLength describe the same curve",
          "[xodr][geometry][paramPoly3]") {
  const double length = 80.0;
  ParamPoly3Geometry normalized;
  normalized.bu = length;
  normalized.cv = 6.0;
  normalized.dv = -2.0;
  normalized.range = ParamRange::kNormalized;
  ParamPoly3Geometry arc = normalized;  // p' = p * length
  arc.range = ParamRange::kArcLength;
  arc.bu = 1.0;
  arc.cv = 6.0 / (length * length);
  arc.dv = -2.0 / (length * length * length);
  for (const double ds : {0.0, 10.0, 40.0, 80.0}) {
    const RefPoint a = evaluate_param_poly3(normalized, length, ds);
    const RefPoint b = evaluate_param_poly3(arc, length, ds);
    CHECK(a.x == Approx(b.x).margin(1e-10));
    CHECK(a.y == Approx(b.y).margin(1e-10));
    CHECK(a.hdg == Approx(b.hdg).margin(1e-12));
    CHECK(a.curvature == Approx(b.curvature).margin(1e-12));
  }
  const RefPoint end = evaluate_param_poly3(normalized, length, length);
  CHECK(end.x == Approx(length));
  CHECK(end.y == Approx(4.0));
}

TEST_CASE("geometry kinds have their OpenDRIVE names", "[xodr][geometry]") {
  CHECK(std::string(geometry_kind_name(LineGeometry{})) == "line");
  CHECK(std::string(geometry_kind_name(SpiralGeometry{})) == "spiral");
  CHECK(std::string(geometry_kind_name(ParamPoly3Geometry{})) == "paramPoly3");
}
