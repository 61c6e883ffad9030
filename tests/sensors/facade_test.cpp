// Facades in real geometry (sensors/src/facade.h): buildings that bring only a colour get
// recessed windows, the same look for the same seed, another for another building; the panes'
// pattern varies per window and lights rooms only at night.

#include "facade.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <set>
#include <vector>

#include "corsa/sensors/buildings.h"
#include "corsa/sensors/scene.h"
#include "surface.h"

using namespace corsa::sensors;

namespace {

/// A 20 x 12 m block 15 m high at x0 (its street wall along y = 0, facing -y), one colour.
StaticMesh block_at(double x0) {
  Footprint f;
  f.name = "block";
  f.height = 15.0;
  f.ring = {{x0, 0.0}, {x0 + 20.0, 0.0}, {x0 + 20.0, 12.0}, {x0, 12.0}};
  f.color = Rgb8{200, 190, 170};
  return extrude_footprint(f);
}

/// Depths (m behind the wall's plane, negative in front) seen by horizontal rays towards +y at
/// 5-13 m up, every 5 cm along the wall from x0; hits of other objects fail the test.
struct WallScan {
  std::vector<double> depth;
  std::set<uint32_t> instances;
  std::set<SemanticClass> classes;
};

WallScan scan_wall(const Scene& scene, double x0) {
  WallScan s;
  for (double z = 5.0; z <= 13.0; z += 0.1) {
    for (double x = x0 + 0.5; x <= x0 + 19.5; x += 0.05) {
      const auto hit = scene.intersect({x, -10.0, z}, {0.0, 1.0, 0.0}, 30.0);
      REQUIRE(hit);
      s.depth.push_back(hit->distance - 10.0);
      s.instances.insert(hit->instance_id);
      s.classes.insert(hit->semantic);
    }
  }
  return s;
}

}  // namespace

TEST_CASE("a building that brings only a colour gets windows recessed behind its wall",
          "[sensors][buildings][facade]") {
  Scene scene(SceneOptions{.origin = {}, .seed = 7});
  const uint32_t id = scene.add_static_mesh(block_at(0.0));
  scene.commit();
  const WallScan s = scan_wall(scene, 0.0);
  // Every part of the facade is the building: its class and its instance id.
  CHECK(s.classes == std::set<SemanticClass>{SemanticClass::kBuilding});
  CHECK(s.instances == std::set<uint32_t>{id});
  size_t wall = 0, recessed = 0, proud = 0;
  double deepest = 0.0;
  for (const double d : s.depth) {
    if (std::fabs(d) < 1e-3) {
      ++wall;
    } else if (d > 0.0) {
      ++recessed;
      deepest = std::max(deepest, d);
      // The panes sit one recess deep: 12-30 cm (reveals are seen edge-on from straight ahead).
      CHECK(d >= 0.12 - 1e-3);
      CHECK(d <= 0.3 + 1e-3);
    } else {
      ++proud;  // sills, string courses, pilasters, balconies, the cornice
    }
  }
  INFO("wall " << wall << ", recessed " << recessed << ", proud " << proud);
  CHECK(wall > s.depth.size() / 4);
  CHECK(recessed > s.depth.size() / 10);
  // One recess depth for the building: no hole deeper than its panes.
  CHECK(deepest <= 0.3 + 1e-3);
}

TEST_CASE("a facade is the same for a seed and differs between buildings",
          "[sensors][buildings][facade][determinism]") {
  const auto scans = [](uint64_t seed) {
    Scene scene(SceneOptions{.origin = {}, .seed = seed});
    scene.add_static_mesh(block_at(0.0));
    scene.add_static_mesh(block_at(40.0));
    scene.commit();
    return std::pair{scan_wall(scene, 0.0).depth, scan_wall(scene, 40.0).depth};
  };
  const auto [a, b] = scans(7);
  const auto [a_again, b_again] = scans(7);
  CHECK(a == a_again);
  CHECK(b == b_again);
  // Two buildings of one footprint and colour: windows, recesses and mouldings differ.
  size_t differ = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    differ += std::fabs(a[i] - b[i]) > 1e-6 ? 1 : 0;
  }
  CHECK(differ > a.size() / 10);
  // Another run seed, another street.
  const auto [a_other, b_other] = scans(8);
  CHECK(a_other != a);
}

TEST_CASE("facade styles vary window sizes, recesses and storeys with the stream",
          "[sensors][buildings][facade]") {
  std::set<double> widths, recesses;
  int shops = 0, balconies = 0, cornices = 0, top_floors = 0;
  for (uint64_t seed = 1; seed <= 40; ++seed) {
    corsa::RandomStream rng(seed);
    detail::FacadeBrief brief;
    brief.wall = {0.5, 0.45, 0.4};
    brief.floor_h = 0.0;
    brief.ground_h = -1.0;
    const detail::FacadeStyle s = detail::draw_facade_style(rng, brief);
    widths.insert(s.window_w);
    recesses.insert(s.recess);
    shops += s.shops ? 1 : 0;
    balconies += s.balconies > 0.0 ? 1 : 0;
    cornices += s.cornice > 0.0 ? 1 : 0;
    top_floors += s.top_window_scale < 1.0 ? 1 : 0;
    CHECK(s.window_h + s.sill_z <= s.floor_h - 0.3 + 1e-9);  // a lintel above every window
    CHECK(s.window_w < s.bay);
  }
  CHECK(widths.size() == 40);
  CHECK(recesses.size() == 40);
  // Each choice taken by some buildings and not by all.
  for (const int n : {shops, balconies, cornices, top_floors}) {
    CHECK(n > 0);
    CHECK(n < 40);
  }
}

TEST_CASE("window panes vary per window and light rooms only at night",
          "[sensors][buildings][facade][materials]") {
  Material m = materials::plain("pane", {0.03, 0.035, 0.04}, 0.04);
  m.pattern = Pattern::kGlazing;
  m.params = {1.2, 1.5, 1.0, 0.0};
  m.secondary = {0.8, 0.8, 0.8};
  m.seed = 11;
  std::set<double> looks;
  int lit = 0;
  for (int col = 0; col < 20; ++col) {
    for (int row = 0; row < 5; ++row) {
      detail::TexturePoint p;
      p.normal = {0.0, -1.0, 0.0};
      p.footprint = 0.001;
      p.u = col + 0.1;  // 12 cm in from the left: glass, or a curtain drawn there
      p.v = row + 0.5;
      const detail::SurfaceSample day = detail::sample_surface(m, p);
      CHECK(day.emission.r == 0.0);
      CHECK(day.roughness < 0.1);  // glass, which reflects the sky
      looks.insert(day.albedo.r);
      p.darkness = 1.0;
      lit += detail::sample_surface(m, p).emission.r > 0.0 ? 1 : 0;
      // The frame at the pane's edge is the frame colour, rough.
      p.u = col + 0.01;
      const detail::SurfaceSample frame = detail::sample_surface(m, p);
      CHECK(frame.albedo.r == Approx(0.8));
      CHECK(frame.roughness > 0.5);
    }
  }
  CHECK(looks.size() > 20);  // rooms of varying darkness, curtains, blinds
  CHECK(lit > 10);           // some rooms lit at night, not all
  CHECK(lit < 60);
}
