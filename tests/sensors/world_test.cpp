// The world beyond the road: ground to the horizon, roadside props, signals and objects.

#include "corsa/sensors/world.h"

#include <tbb/global_control.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <map>

#include "corsa/sensors/camera_render.h"
#include "corsa/sensors/labels.h"
#include "corsa/xodr/road_mesh.h"
#include "world_fixture.h"

using namespace corsa::sensors;

using corsa::test::build_world_scene;
using corsa::test::kXodrData;
using corsa::test::load_map;
using corsa::test::wide_camera;

TEST_CASE("on Town04 the ground reaches the horizon and the junction shows lights and poles",
          "[sensors][world]") {
  const auto map = load_map(kXodrData / "Town04.xodr");
  auto built = build_world_scene(map, 3);
  CHECK(built->report.ground_triangles > 10000);
  CHECK(built->report.traffic_lights == 43);  // every signal of the map is a traffic light
  CHECK(built->report.trees + built->report.bushes > 200);
  // The junction of signals 1614-1617, seen from road 1 (the Town04 scenario's Ego).
  const auto pose = map.world_pose(*map.find_road("1"), 52.0, -8.75);
  const Rigid eye = rigid_from_pose(pose.x, pose.y, pose.z + 1.5, pose.h, 0.0, 0.0);
  built->scene.set_entities({});
  const CameraRenderer camera(wide_camera());
  RenderSettings settings;
  settings.outputs.semantic = true;
  CameraMotion motion;
  motion.world_from_body = eye;
  const CameraImages img = camera.render(built->scene, motion, settings);
  std::map<int, int> count;
  int sky_below = 0;
  for (int row = 0; row < img.height; ++row) {
    for (int col = 0; col < img.width; ++col) {
      const int c = img.semantic[static_cast<size_t>(row) * img.width + col];
      ++count[c];
      // The camera looks level: below the centre row every ray goes down.
      sky_below += row > img.height / 2 && c == static_cast<int>(SemanticClass::kSky) ? 1 : 0;
    }
  }
  CHECK(sky_below == 0);
  CHECK(count[static_cast<int>(SemanticClass::kTrafficLight)] > 20);
  CHECK(count[static_cast<int>(SemanticClass::kPole)] > 20);
  CHECK(count[static_cast<int>(SemanticClass::kVegetation)] > 100);
  CHECK(count[static_cast<int>(SemanticClass::kTerrain)] > 1000);
  // Static labels: the lights in view carry their signal id and this frame's state.
  const std::vector<corsa::engine::SignalSnapshot> states = {{"1615", "on;off;off"},
                                                             {"1614", "off;off;on"}};
  built->scene.set_signals(states);
  const auto labels = static_object_labels(built->scene, img.instance, img.width, img.semantic);
  int lights = 0;
  for (const auto& l : labels) {
    if (l.info.kind == "traffic_light") {
      ++lights;
      CHECK(!l.info.signal_id.empty());
      if (l.info.signal_id == "1615") {
        CHECK(l.state == "on;off;off");
      }
    }
  }
  CHECK(lights >= 2);
}

TEST_CASE("the world is the same for the same seed and other plants for another",
          "[sensors][world][determinism]") {
  const auto map = load_map(kXodrData / "fabriksgatan.xodr");
  auto a = build_world_scene(map, 5);
  auto b = build_world_scene(map, 5);
  auto c = build_world_scene(map, 6);
  CHECK(a->scene.static_triangle_count() == b->scene.static_triangle_count());
  CHECK(a->report.trees == b->report.trees);
  CHECK(a->report.bushes == b->report.bushes);
  CHECK(a->scene.static_triangle_count() != c->scene.static_triangle_count());
}

TEST_CASE("signals of types Corsa does not draw become generic signs with one warning",
          "[sensors][world][signals]") {
  // SampleDatabase has German signs and a few types outside the catalogue.
  const auto map = load_map(kXodrData / "SampleDatabase.xodr");
  auto built = build_world_scene(map, 3);
  CHECK(built->report.signs + built->report.traffic_lights > 0);
  std::map<std::string, int> per_message;
  for (const auto& w : built->warnings) {
    ++per_message[w.message];
    CHECK(w.line > 0);  // located at the signal or object
  }
  for (const auto& [message, n] : per_message) {
    INFO(message);
    CHECK(n == 1);
  }
}

TEST_CASE("a camera frame of a built world is the same bytes on 1 and 2 threads",
          "[sensors][world][determinism]") {
  const auto map = load_map(kXodrData / "Town04.xodr");
  auto built = build_world_scene(map, 3);
  built->scene.set_entities({});
  const auto pose = map.world_pose(*map.find_road("1"), 40.0, -8.75);
  const CameraRenderer camera(wide_camera());
  corsa::engine::EnvironmentState env;
  env.sun_azimuth = 2.0;
  env.sun_elevation = 0.9;
  const Lighting day = compute_lighting(env, {});
  auto render = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    RenderSettings settings;
    settings.outputs = {.rgb = true, .depth = true, .semantic = true};
    settings.lighting = &day;
    settings.frame_seed = 9;
    CameraMotion motion;
    motion.world_from_body = rigid_from_pose(pose.x, pose.y, pose.z + 1.5, pose.h, 0.0, 0.0);
    return camera.render(built->scene, motion, settings);
  };
  const CameraImages one = render(1);
  const CameraImages two = render(2);
  CHECK(one.rgb == two.rgb);
  CHECK(one.semantic == two.semantic);
  CHECK(one.instance == two.instance);
}
