// Generated parts of the world: buildings along streets (an option), guard rails and fences
// along motorways, and how a lit street looks at night against noon.

#include <catch2/catch.hpp>
#include <filesystem>
#include <set>

#include "corsa/sensors/camera_render.h"
#include "corsa/sensors/world.h"
#include "corsa/xodr/road_mesh.h"
#include "world_fixture.h"

using namespace corsa::sensors;

using corsa::test::build_world_scene;
using corsa::test::kXodrData;
using corsa::test::load_map;
using corsa::test::wide_camera;

namespace {

const std::filesystem::path kSource = CORSA_SOURCE_DIR;

/// The demo street (one straight 320 m road, sidewalks on both sides) without its models.
corsa::xodr::Map demo_street() { return load_map(kSource / "scenarios/demo/city_street.xodr"); }

/// The world with or without generated buildings, the scene ready for rendering (no entities).
std::unique_ptr<corsa::test::BuiltWorld> build(const corsa::xodr::Map& map, bool buildings,
                                               uint64_t seed = 3) {
  auto out = build_world_scene(map, seed, buildings);
  out->scene.set_entities({});
  return out;
}

/// A camera 1.5 m above lane `t` of road 0 at s, looking along the road.
CameraMotion on_road(const corsa::xodr::Map& map, size_t road, double s, double t) {
  const auto p = map.world_pose(road, s, t);
  CameraMotion motion;
  motion.world_from_body = rigid_from_pose(p.x, p.y, p.z + 1.5, p.h, 0.0, 0.0);
  return motion;
}

int count_class(const CameraImages& img, SemanticClass c) {
  int n = 0;
  for (const auto v : img.semantic) {
    n += v == static_cast<uint8_t>(c) ? 1 : 0;
  }
  return n;
}

double mean_luma(const CameraImages& img) {
  double sum = 0.0;
  for (size_t i = 0; i + 2 < img.rgb.size(); i += 3) {
    sum += 0.2126 * img.rgb[i] + 0.7152 * img.rgb[i + 1] + 0.0722 * img.rgb[i + 2];
  }
  return sum / static_cast<double>(img.rgb.size() / 3);
}

}  // namespace

TEST_CASE("generated buildings line a street when asked and none stand there otherwise",
          "[sensors][world][buildings]") {
  const auto map = demo_street();
  auto on = build(map, true);
  auto off = build(map, false);
  CHECK(off->report.buildings == 0);
  // 320 m on two sides with lots of 8-24 m frontage: a dozen or more buildings per side.
  CHECK(on->report.buildings >= 20);
  // No two alike: every building brings at least its own facade material.
  CHECK(on->scene.material_count() >= off->scene.material_count() + on->report.buildings);
  const CameraRenderer camera(wide_camera());
  RenderSettings settings;
  settings.outputs.semantic = true;
  const CameraMotion motion = on_road(map, 0, 60.0, -5.25);
  const CameraImages with = camera.render(on->scene, motion, settings);
  const CameraImages without = camera.render(off->scene, motion, settings);
  const int pixels = with.width * with.height;
  CHECK(count_class(with, SemanticClass::kBuilding) > pixels / 10);
  CHECK(count_class(without, SemanticClass::kBuilding) == 0);
  // They stand beside the street: the road ahead is still seen.
  CHECK(count_class(with, SemanticClass::kRoad) > pixels / 10);
}

TEST_CASE("generated buildings are the same for a seed and others for another",
          "[sensors][world][buildings][determinism]") {
  const auto map = demo_street();
  auto a = build(map, true, 5);
  auto b = build(map, true, 5);
  auto c = build(map, true, 6);
  CHECK(a->report.buildings == b->report.buildings);
  CHECK(a->scene.static_triangle_count() == b->scene.static_triangle_count());
  CHECK(a->scene.material_count() == b->scene.material_count());
  const CameraRenderer camera(wide_camera());
  RenderSettings settings;
  settings.outputs = {.semantic = true, .instance = true};
  const CameraMotion motion = on_road(map, 0, 100.0, 5.25);
  const CameraImages ia = camera.render(a->scene, motion, settings);
  const CameraImages ib = camera.render(b->scene, motion, settings);
  const CameraImages ic = camera.render(c->scene, motion, settings);
  CHECK(ia.semantic == ib.semantic);
  CHECK(ia.instance == ib.instance);
  CHECK(ia.semantic != ic.semantic);
}

TEST_CASE("motorways get guard rails and fences at their outer edges, town streets none",
          "[sensors][world][rails]") {
  // Town04's highway loop is limited to 55-65 mph (88-105 km/h); its town part to 30-35 mph.
  const auto town04 = load_map(kXodrData / "Town04.xodr");
  auto built = build(town04, false);
  CHECK(built->report.guard_rails > 100);
  CHECK(built->report.fences > 50);
  // A camera on the outermost right lane of a long 65 mph road sees the rail on its right.
  size_t road = town04.road_count();
  for (size_t r = 0; r < town04.road_count(); ++r) {
    const auto& rd = town04.road(r);
    if (!rd.in_junction() && rd.length > 150.0 && !rd.types.empty() && rd.types.front().max_speed &&
        *rd.types.front().max_speed > 29.0) {
      road = r;
      break;
    }
  }
  REQUIRE(road < town04.road_count());
  const double s = 0.5 * town04.road(road).length;
  std::vector<corsa::xodr::LaneSpan> spans;
  town04.lane_spans(road, s, spans);
  const corsa::xodr::LaneSpan* outer = nullptr;
  for (const auto& span : spans) {
    const auto& lanes = town04.road(road).lane_sections[town04.section_index(road, s)].lanes;
    for (const auto& lane : lanes) {
      if (lane.id == span.id && span.id < 0 && lane.type == corsa::xodr::LaneType::kDriving &&
          (outer == nullptr || span.id < outer->id)) {
        outer = &span;
      }
    }
  }
  REQUIRE(outer != nullptr);
  const CameraRenderer camera(wide_camera());
  RenderSettings settings;
  settings.outputs.semantic = true;
  const CameraImages img = camera.render(
      built->scene, on_road(town04, road, s, 0.5 * (outer->t_inner + outer->t_outer)), settings);
  CHECK(count_class(img, SemanticClass::kGuardRail) > 200);
  // The demo street is a town street: no rails.
  const auto street = demo_street();
  CHECK(build(street, false)->report.guard_rails == 0);
}

TEST_CASE("a lit street at night is far darker than at noon under auto exposure",
          "[sensors][camera][night]") {
  const auto map = demo_street();
  auto built = build(map, true);
  const CameraRenderer camera(wide_camera());
  auto render = [&](double sun_elevation) {
    corsa::engine::EnvironmentState env;
    env.sun_azimuth = 2.0;
    env.sun_elevation = sun_elevation;
    const Lighting light = compute_lighting(env, {});
    RenderSettings settings;
    settings.outputs.rgb = true;
    settings.outputs.semantic = true;
    settings.lighting = &light;
    settings.rgb.noise = false;
    settings.frame_seed = 4;
    return camera.render(built->scene, on_road(map, 0, 60.0, -5.25), settings);
  };
  const CameraImages noon = render(1.2);
  const CameraImages night = render(-0.4);
  const double noon_luma = mean_luma(noon);
  const double night_luma = mean_luma(night);
  INFO("mean 8-bit luma: noon " << noon_luma << ", night " << night_luma);
  // Measured: 134 at noon, 52 at night (117 under the exposure that lifted night towards day).
  CHECK(night_luma < 0.45 * noon_luma);
  // The night sky is black, not a dim grey.
  double sky = 0.0;
  int sky_pixels = 0;
  for (size_t i = 0; i < night.semantic.size(); ++i) {
    if (night.semantic[i] == static_cast<uint8_t>(SemanticClass::kSky)) {
      sky += night.rgb[3 * i + 1];
      ++sky_pixels;
    }
  }
  REQUIRE(sky_pixels > 100);
  CHECK(sky / sky_pixels < 20.0);
  // ... nor black: the city's glow, brighter in the sky's lowest rows than in its highest.
  CHECK(sky / sky_pixels > 3.0);
  const int width = wide_camera().width;
  std::vector<std::pair<int, double>> rows;  // (row, mean green) of rows with 20+ sky pixels
  for (int row = 0; row < wide_camera().height; ++row) {
    double sum = 0.0;
    int n = 0;
    for (int col = 0; col < width; ++col) {
      const size_t i = static_cast<size_t>(row) * width + col;
      if (night.semantic[i] == static_cast<uint8_t>(SemanticClass::kSky)) {
        sum += night.rgb[3 * i + 1];
        ++n;
      }
    }
    if (n >= 20) {
      rows.emplace_back(row, sum / n);
    }
  }
  REQUIRE(rows.size() >= 20);
  double top = 0.0, bottom = 0.0;
  for (size_t k = 0; k < 10; ++k) {
    top += rows[k].second / 10.0;
    bottom += rows[rows.size() - 1 - k].second / 10.0;
  }
  INFO("sky green, highest 10 rows " << top << ", lowest 10 " << bottom);
  CHECK(bottom > top + 1.0);
}
