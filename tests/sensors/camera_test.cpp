#include <tbb/global_control.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "corsa/sensors/camera_render.h"
#include "corsa/sensors/labels.h"
#include "corsa/sensors/writers.h"
#include "fixtures.h"

using namespace corsa::sensors;
using corsa::test::box_entity;

namespace {

CameraIntrinsics vga() {
  CameraIntrinsics k;
  k.width = 640;
  k.height = 480;
  k.fov_deg = 90.0;
  return k;
}

/// A camera 1 m above the road looking along +x.
const Rigid kEye = rigid_from_pose(0.0, 0.0, 1.0, 0.0, 0.0, 0.0);

Scene road_with(std::vector<corsa::engine::EntitySnapshot> entities) {
  Scene scene;
  scene.add_road_mesh(corsa::test::flat_road());
  scene.commit();
  scene.set_entities(entities);
  return scene;
}

CameraImages render(const Scene& scene, const CameraRenderer& camera, CameraOutputs outputs,
                    const Lighting* lighting = nullptr, uint64_t seed = 1) {
  RenderSettings settings;
  settings.outputs = outputs;
  settings.lighting = lighting;
  settings.frame_seed = seed;
  CameraMotion motion;
  motion.world_from_body = kEye;
  return camera.render(scene, motion, settings);
}

}  // namespace

TEST_CASE("a box at a known distance gives the right depth and 2D box", "[sensors][camera]") {
  // Box 4 x 2 x 1.5 m centred 20 m ahead: its front face is the plane x = 18 m.
  const Scene scene = road_with({box_entity(7, "box", 20.0, 0.0, 4.0, 2.0, 1.5)});
  const CameraRenderer camera(vga());
  const CameraImages img = render(scene, camera, {.depth = true, .semantic = true});
  REQUIRE(camera.model().fx() == Approx(320.0));
  size_t box_pixels = 0;
  for (size_t i = 0; i < img.instance.size(); ++i) {
    if (img.instance[i] == 7) {
      ++box_pixels;
      REQUIRE(img.depth[i] == Approx(18.0).margin(1e-3));
      REQUIRE(img.semantic[i] == static_cast<uint8_t>(SemanticClass::kDynamic));
    }
  }
  // The face spans 2 m x 1.5 m at 18 m: (320 * 2 / 18) x (320 * 1.5 / 18) pixels.
  CHECK(static_cast<double>(box_pixels) == Approx(35.56 * 26.67).epsilon(0.06));

  const auto labels = camera_labels(scene, camera, kEye, img.instance);
  REQUIRE(labels.size() == 1);
  const ObjectLabel& l = labels[0];
  CHECK(l.track_id == 7);
  CHECK(l.semantic == SemanticClass::kDynamic);
  // Corners of the front face: u = 319.5 -+ 320 * 1 / 18, v = 239.5 + 320 * (1 - z) / 18.
  CHECK(l.box_2d.x_min == Approx(319.5 - 320.0 / 18.0).margin(1e-6));
  CHECK(l.box_2d.x_max == Approx(319.5 + 320.0 / 18.0).margin(1e-6));
  CHECK(l.box_2d.y_min == Approx(239.5 - 320.0 * 0.5 / 18.0).margin(1e-6));
  CHECK(l.box_2d.y_max == Approx(239.5 + 320.0 / 18.0).margin(1e-6));
  CHECK(l.box_2d_visible.x_min == Approx(l.box_2d.x_min).margin(1.0));
  CHECK(l.box_2d_visible.x_max == Approx(l.box_2d.x_max).margin(1.0));
  CHECK(l.box_2d_visible.y_min == Approx(l.box_2d.y_min).margin(1.0));
  CHECK(l.box_2d_visible.y_max == Approx(l.box_2d.y_max).margin(1.0));
  CHECK(l.truncation == 0.0);
  CHECK(l.occlusion == Approx(0.0).margin(0.01));
  // 3D box: centre 20 m ahead and 0.25 m below the camera (optical z forward, y down).
  CHECK(l.box_sensor.center.z == Approx(20.0));
  CHECK(l.box_sensor.center.x == Approx(0.0).margin(1e-9));
  CHECK(l.box_sensor.center.y == Approx(0.25));
  CHECK(l.box_world.center.x == Approx(20.0));
  CHECK(l.box_world.center.z == Approx(0.75));
  CHECK(l.distance == Approx(std::sqrt(400.0 + 0.0625)));
}

TEST_CASE("an object hidden half behind another is labelled half occluded",
          "[sensors][camera][labels]") {
  auto target = box_entity(1, "target", 20.0, 0.0, 4.0, 2.0, 1.5);
  // The occluder covers y >= 0 (the left half of the target as seen from the camera).
  auto occluder = box_entity(2, "wall", 10.0, 1.5, 0.5, 3.0, 3.0);
  const Scene scene = road_with({target, occluder});
  const CameraRenderer camera(vga());
  const CameraImages img = render(scene, camera, {});
  const auto labels = camera_labels(scene, camera, kEye, img.instance);
  REQUIRE(labels.size() == 2);
  CHECK(labels[0].name == "target");
  CHECK(labels[0].occlusion == Approx(0.5).margin(0.04));
  CHECK(kitti_occlusion_level(labels[0].occlusion) >= 1);
  CHECK(labels[1].occlusion == Approx(0.0).margin(0.01));
  CHECK(labels[0].box_2d_visible.x_min == Approx(319.5).margin(1.0));
}

TEST_CASE("an object at the image edge is labelled truncated by the share outside",
          "[sensors][camera][labels]") {
  // 45 degrees to the right: the right image edge cuts the box.
  const Scene scene = road_with({box_entity(3, "edge", 18.0, -18.0, 2.0, 2.0, 1.5)});
  const CameraRenderer camera(vga());
  const CameraImages img = render(scene, camera, {});
  const auto labels = camera_labels(scene, camera, kEye, img.instance);
  REQUIRE(labels.size() == 1);
  // Pinhole projection of the eight corners, clipped to the image.
  double u0 = 1e9, u1 = -1e9, v0 = 1e9, v1 = -1e9;
  for (int i = 0; i < 8; ++i) {
    const double x = 18.0 + (i & 1 ? 1.0 : -1.0);
    const double y = -18.0 + (i & 2 ? 1.0 : -1.0);
    const double z = (i & 4 ? 1.5 : 0.0) - 1.0;
    const double u = 319.5 + 320.0 * (-y) / x;
    const double v = 239.5 + 320.0 * (-z) / x;
    u0 = std::min(u0, u), u1 = std::max(u1, u), v0 = std::min(v0, v), v1 = std::max(v1, v);
  }
  const double full = (u1 - u0) * (v1 - v0);
  const double inside = (std::min(u1, 639.5) - u0) * (v1 - v0);
  CHECK(labels[0].truncation == Approx(1.0 - inside / full).margin(1e-6));
  CHECK(labels[0].truncation > 0.2);
  CHECK(labels[0].box_2d.x_max == Approx(639.5));
}

TEST_CASE("a vehicle's label gives its lights as the frame draws them; a walker has none",
          "[sensors][camera][labels][lights]") {
  using corsa::engine::light_bit;
  using corsa::engine::LightMode;
  using corsa::engine::VehicleLight;
  // A car 15 m ahead seen from behind, backing up at 1 m/s with its reversing lights switched
  // off by the scenario, braking, its right indicator flashing in its on phase; a walker beside.
  auto car = box_entity(4, "car", 15.0, 0.0, 4.5, 1.8, 1.5, corsa::engine::EntityCategory::kCar);
  car.speed = -1.0;
  car.lights_on = light_bit(VehicleLight::kBrake) | light_bit(VehicleLight::kIndicatorRight);
  car.lights_flashing = light_bit(VehicleLight::kIndicatorRight);
  car.lights_set = light_bit(VehicleLight::kReversing);
  corsa::engine::LightSettingView reversing_off;
  reversing_off.light = VehicleLight::kReversing;
  reversing_off.mode = LightMode::kOff;
  car.light_settings.push_back(reversing_off);
  auto walker =
      box_entity(5, "walker", 10.0, 3.0, 0.5, 0.6, 1.8, corsa::engine::EntityCategory::kPedestrian);
  const Scene scene = road_with({car, walker});
  const CameraRenderer camera(vga());
  const CameraImages img = render(scene, camera, {});
  corsa::engine::EnvironmentState midnight;
  midnight.sun_elevation = -0.4;
  midnight.sun_azimuth = 0.0;
  const Lighting night = compute_lighting(midnight, {});
  REQUIRE(night.headlights);

  const auto day = camera_labels(scene, camera, kEye, img.instance);
  REQUIRE(day.size() == 2);
  REQUIRE(day[0].lights);
  CHECK(!day[1].lights);
  const auto& lights = day[0].lights->lights;
  REQUIRE(lights.size() == 3);
  CHECK(lights[0].light == VehicleLight::kBrake);
  CHECK(lights[0].mode == LightMode::kOn);
  CHECK(lights[1].light == VehicleLight::kIndicatorRight);
  CHECK(lights[1].mode == LightMode::kFlashing);
  CHECK(lights[1].lit);
  CHECK(!lights[1].set);
  CHECK(lights[2].light == VehicleLight::kReversing);
  CHECK(lights[2].set);
  CHECK(!lights[2].lit);
  const std::string text = labels_json(day, true);
  CHECK_THAT(text,
             Catch::Contains("\"lights\": {\"brakeLights\": {\"mode\": \"on\", \"lit\": true}, "
                             "\"indicatorRight\": {\"mode\": \"flashing\", \"lit\": true}, "
                             "\"reversingLights\": {\"mode\": \"off\", \"lit\": false, \"set\": "
                             "true}}, \"lamps\": [\"brake\", \"indicator_right\"]}"));
  // One "lights" member: the car's; the walker's label line has none.
  CHECK(text.find("\"lights\"") == text.rfind("\"lights\""));

  // At night the renderer lights the low beam (with the tail lamps) that nobody set.
  const auto dark = camera_labels(scene, camera, kEye, img.instance, 0, &night);
  REQUIRE(dark[0].lights);
  REQUIRE(dark[0].lights->lights.size() == 4);
  const LightLabel& beam = dark[0].lights->lights[0];
  CHECK(beam.light == VehicleLight::kLowBeam);
  CHECK(beam.mode == LightMode::kOn);
  CHECK(beam.lit);
  CHECK(!beam.set);
  const uint32_t lamps = dark[0].lights->lamps;
  for (const LightRole role :
       {LightRole::kHeadlight, LightRole::kTail, LightRole::kBrake, LightRole::kIndicatorRight}) {
    CHECK((lamps >> static_cast<unsigned>(role) & 1u) == 1u);
  }
  CHECK((lamps >> static_cast<unsigned>(LightRole::kReversing) & 1u) == 0u);
  CHECK((lamps >> static_cast<unsigned>(LightRole::kIndicatorLeft) & 1u) == 0u);
}

TEST_CASE("a camera inside its own vehicle does not see it", "[sensors][camera]") {
  auto ego = box_entity(1, "ego", 0.0, 0.0, 4.5, 1.8, 1.5, corsa::engine::EntityCategory::kCar);
  const Scene scene = road_with({ego});
  const CameraRenderer camera(vga());
  RenderSettings settings;
  settings.outputs.depth = true;
  settings.carrier = entity_box(ego);
  CameraMotion motion;
  motion.world_from_body = kEye;  // 1 m up, inside the box
  const CameraImages img = camera.render(scene, motion, settings);
  for (uint32_t id : img.instance) {
    REQUIRE(id != 1);
  }
  // Ground ahead of the bonnet is seen (row 304 looks 64.5 px below the horizon: depth
  // 320 / 64.5 m); ground under the vehicle (bottom row, 1.34 m ahead) stays hidden by it.
  CHECK(img.depth[304 * 640 + 320] == Approx(320.0 / 64.5).epsilon(1e-4));
  CHECK(img.depth[479 * 640 + 320] == 0.0f);
}

TEST_CASE("lens distortion moves pixels as OpenCV's model says", "[sensors][camera]") {
  CameraIntrinsics k = vga();
  k.k1 = -0.2;
  k.k2 = 0.05;
  k.p1 = 0.001;
  k.p2 = -0.002;
  const CameraModel model(k);
  for (double u : {10.0, 200.0, 319.5, 600.0}) {
    for (double v : {5.0, 239.5, 470.0}) {
      const Vec3 r = model.ray({u, v});
      const auto back = model.project(r * 7.0);
      REQUIRE(back);
      CHECK(back->u == Approx(u).margin(1e-6));
      CHECK(back->v == Approx(v).margin(1e-6));
    }
  }
  // Barrel distortion (k1 < 0) pulls an off-axis point towards the centre.
  const auto p = model.project({0.5, 0.0, 1.0});
  CHECK(p->u < 319.5 + 320.0 * 0.5);
}

TEST_CASE("RGB shading has sunlit ground brighter than its shadow and night darker than day",
          "[sensors][camera][rgb]") {
  const Scene scene = road_with({box_entity(1, "block", 12.0, 0.0, 2.0, 6.0, 6.0)});
  const CameraRenderer camera(vga());
  corsa::engine::EnvironmentState env;
  env.sun_azimuth = M_PI / 2.0 * 3.0;  // sun in the west (-x): the shadow falls towards +x
  env.sun_elevation = 0.5;
  Lighting day = compute_lighting(env, {});
  RenderSettings settings;
  const CameraImages img = render(scene, camera, {.rgb = true}, &day);
  REQUIRE(img.rgb.size() == 640u * 480u * 3u);
  auto luma = [&](const CameraImages& im, int col, int row) {
    const uint8_t* p = &im.rgb[3 * (static_cast<size_t>(row) * 640 + col)];
    return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
  };
  // Ground at 5 m ahead (row 239.5 + 320 / 5 = 303.5) is in the sun; the box's own east side
  // is not visible, but ground beyond it in its shadow is hidden too, so compare the box's lit
  // west face against a night render instead.
  const double lit_ground = luma(img, 320, 304);
  env.sun_elevation = -0.3;  // night
  Lighting night = compute_lighting(env, {});
  CHECK(night.headlights);
  const CameraImages dark = render(scene, camera, {.rgb = true}, &night);
  CHECK(luma(dark, 320, 304) < 0.2 * lit_ground);

  // A shadow: the sun behind the camera-facing block casts its shadow towards the camera.
  env.sun_azimuth = M_PI / 2.0;  // east (+x), behind the block
  env.sun_elevation = 0.6;
  Lighting backlit = compute_lighting(env, {});
  const CameraImages shadowed = render(scene, camera, {.rgb = true}, &backlit);
  // Ground 6 m ahead lies in the block's shadow (6 m tall, sun 34 degrees high: the shadow
  // reaches 8.8 m towards the camera over |y| < 3 m); 4.1 m to the left it is sunlit.
  const int row = 239 + static_cast<int>(320.0 / 6.0);
  const double in_shadow = luma(shadowed, 300, row);  // y = 0.37 m
  const double sunlit = luma(shadowed, 100, row);     // y = 4.1 m
  CHECK(in_shadow < 0.8 * sunlit);
}

TEST_CASE("fog pulls distant pixels towards the fog colour", "[sensors][camera][weather]") {
  const Scene scene = road_with({});
  const CameraRenderer camera(vga());
  corsa::engine::EnvironmentState env;
  env.sun_azimuth = 1.0;
  env.sun_elevation = 0.8;
  env.fog_visual_range = 30.0;
  const Lighting fog = compute_lighting(env, {});
  CHECK(fog.fog_extinction == Approx(std::log(50.0) / 30.0));
  RenderSettings settings;
  const CameraImages img = render(scene, camera, {.rgb = true}, &fog);
  auto pixel = [&](int row) { return img.rgb[3 * (static_cast<size_t>(row) * 640 + 320)]; };
  // Road 100 m ahead (row 242.7) is almost pure fog, like the sky; road 1.5 m ahead is not.
  const double far = pixel(243);
  const double sky = pixel(100);
  CHECK(std::fabs(far - sky) < 6.0);
  CHECK(std::fabs(static_cast<double>(pixel(460)) - sky) > 15.0);
}

TEST_CASE("a camera frame is the same bytes for the same seed on 1 and 2 threads",
          "[sensors][camera][determinism]") {
  auto car = box_entity(4, "car", 15.0, 2.0, 4.5, 1.8, 1.5, corsa::engine::EntityCategory::kCar);
  car.vx = 10.0;
  const Scene scene = road_with({car});
  CameraIntrinsics k = vga();
  k.k1 = -0.1;
  const CameraRenderer camera(k);
  corsa::engine::EnvironmentState env;
  env.precipitation = corsa::engine::PrecipitationType::kRain;
  env.precipitation_intensity = 8.0;
  const Lighting rain = compute_lighting(env, {});
  auto run = [&](int threads, uint64_t seed) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    RenderSettings settings;
    settings.outputs = {.rgb = true, .depth = true, .semantic = true};
    settings.lighting = &rain;
    settings.rgb.shutter_speed_s = 0.02;  // motion blur on
    settings.frame_seed = seed;
    CameraMotion motion;
    motion.world_from_body = kEye;
    motion.velocity = {5.0, 0.0, 0.0};
    return camera.render(scene, motion, settings);
  };
  const CameraImages a = run(1, 5);
  const CameraImages b = run(2, 5);
  CHECK(a.rgb == b.rgb);
  CHECK(a.depth == b.depth);
  CHECK(a.semantic == b.semantic);
  CHECK(a.instance == b.instance);
  CHECK(run(2, 6).rgb != a.rgb);  // another seed, other noise and streaks
}
