// Image formation of the RGB camera: the daylight sky, the beam of a low-beam headlight, lit
// scenes at night, the bytes of a frame on any thread count at every quality, and a `fast`
// frame in rain that owes nothing to the frame before it.

#include <tbb/global_control.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "brdf.h"
#include "corsa/sensors/camera_render.h"
#include "fixtures.h"
#include "light_list.h"
#include "shading.h"

using namespace corsa::sensors;
using corsa::sensors::detail::luminance;
using corsa::test::box_entity;

namespace {

Lighting sun_at(double azimuth, double elevation) {
  corsa::engine::EnvironmentState env;
  env.sun_azimuth = azimuth;
  env.sun_elevation = elevation;
  return compute_lighting(env, {});
}

/// Luminous intensity of `light` towards `point` (irradiance facing it times distance squared).
double intensity_towards(const detail::Light& light, Vec3 point) {
  const detail::LightSample s = detail::illuminate(light, point);
  return luminance(s.irradiance) * s.distance * s.distance;
}

}  // namespace

TEST_CASE("a clear noon sky is blue overhead and a setting sun turns the horizon warm",
          "[sensors][camera][sky]") {
  const Lighting noon = sun_at(M_PI, 1.2);
  const Color zenith = noon.sky_model.radiance({0.0, 0.0, 1.0});
  CHECK(zenith.b > 1.2 * zenith.r);
  // The horizon is paler than the zenith on a clear day (more air, more haze).
  const Color horizon = noon.sky_model.radiance({0.0, 0.999, 0.045});
  CHECK(horizon.b / horizon.r < zenith.b / zenith.r);

  // Low over the horizon, beside and opposite the sun, a pale blue-white: bluer than neutral, never
  // pink or mauve (red above green), its chromaticity on the daylight locus.
  for (const double azimuth : {0.0, 0.5 * M_PI, M_PI}) {
    const Color low = noon.sky_model.radiance(
        normalized(Vec3{std::sin(azimuth) * 0.9995, -std::cos(azimuth) * 0.9995, 0.03}));
    const double X = 0.4124 * low.r + 0.3576 * low.g + 0.1805 * low.b;
    const double Y = 0.2126 * low.r + 0.7152 * low.g + 0.0722 * low.b;
    const double Z = 0.0193 * low.r + 0.1192 * low.g + 0.9505 * low.b;
    const double x = X / (X + Y + Z), y = Y / (X + Y + Z);
    INFO("azimuth from the sun " << azimuth << ": rgb " << low.r << ", " << low.g << ", " << low.b
                                 << "; xy " << x << ", " << y);
    CHECK(std::fabs(y - daylight_locus_y(x)) < 0.003);
    if (azimuth > 0.0) {  // under the sun the horizon is a brighter, whiter glare
      CHECK(low.g >= low.r);
      CHECK(low.b > low.g);
      CHECK(low.b < 1.35 * low.r);  // pale: far less saturated than the zenith
    }
  }

  const Lighting sunset = sun_at(M_PI, 0.02);
  const Vec3 towards{sunset.sun_direction.x, sunset.sun_direction.y, 0.05};
  const Color glow = sunset.sky_model.radiance(normalized(towards));
  CHECK(glow.r > glow.b);
  // Far less light than at noon, and the direct sun reddened by the long path through the air.
  CHECK(luminance(sunset.sky_light({0.0, 0.0, 1.0})) < 0.2 * luminance(noon.sky_light({0, 0, 1})));
  // Noon sunlight a little warmer than daylight white (about 5000-5500 K); at sunset it is
  // orange (a red-to-blue ratio of about twice the noon one, or more).
  const double noon_warmth = noon.sun.r / noon.sun.b;
  CHECK(noon_warmth > 1.0);
  CHECK(noon_warmth < 1.5);
  CHECK(sunset.sun.r / sunset.sun.b > 2.0 * noon_warmth);
}

TEST_CASE("a city's night sky is a dark glow, brighter towards the horizon",
          "[sensors][camera][sky][night]") {
  const Lighting night = sun_at(M_PI, -0.4);
  const double zenith = luminance(night.sky_model.radiance({0.0, 0.0, 1.0})) * kNitsPerUnit;
  const double high =
      luminance(night.sky_model.radiance(normalized(Vec3{0.0, 1.0, 1.0}))) * kNitsPerUnit;
  const Color low_colour = night.sky_model.radiance(normalized(Vec3{0.0, 1.0, 0.05}));
  const double low = luminance(low_colour) * kNitsPerUnit;
  INFO("cd/m^2: zenith " << zenith << ", 45 degrees " << high << ", 3 degrees " << low);
  // A city centre's clear night sky: some 100 times the natural 0.17 mcd/m^2 overhead, several
  // times that in the light dome low over the horizon, warm from the street lamps.
  CHECK(zenith > 0.008);
  CHECK(zenith < 0.05);
  CHECK(high > zenith);
  CHECK(low > 4.0 * high);
  CHECK(low < 0.5);
  CHECK(low_colour.r > low_colour.b);
}

TEST_CASE("a street lamp lights a pool beneath it, over the street more than behind its pole",
          "[sensors][camera][lights]") {
  detail::Light lamp;
  lamp.position = {0.0, 0.0, 7.5};
  lamp.axis = {0.0, 0.0, -1.0};
  lamp.side = {0.0, -1.0, 0.0};                 // the arm reaches over the street towards -y
  lamp.intensity = Color{0.045, 0.045, 0.045};  // a 4,500 cd peak
  lamp.radius = 0.2;
  lamp.range = 60.0;
  lamp.pattern = detail::LightPattern::kStreetLamp;
  // Full cut-off: brightest 45-60 degrees from the vertical, nothing near the horizon.
  const double down = intensity_towards(lamp, {0.0, 0.0, 0.0});
  const double slant = intensity_towards(lamp, {7.5 * std::tan(55.0 * M_PI / 180.0), 0.0, 0.0});
  CHECK(slant > down);
  CHECK(slant < 1.5 * down);
  CHECK(intensity_towards(lamp, {7.5 * std::tan(80.0 * M_PI / 180.0), 0.0, 0.0}) == 0.0);
  // Lux on the road under the lamp and half-way to the next (30 m on): a pool several times
  // the light between (EN 13201's residential classes keep the minimum above a fifth).
  auto lux = [&](Vec3 p) {
    const detail::LightSample s = detail::illuminate(lamp, p);
    return luminance(s.irradiance) * s.direction.z * 100000.0;
  };
  const double pool = lux({0.0, 0.0, 0.0}) + 2.0 * lux({30.0, 0.0, 0.0});
  const double between = 2.0 * lux({15.0, 0.0, 0.0});
  INFO("lux under the lamp " << pool << ", half-way " << between);
  CHECK(pool > 3.0 * between);
  CHECK(between > 0.15 * pool);
  CHECK(pool > 40.0);
  CHECK(pool < 80.0);
  // 9 m across the street (to the far lane) far more than 9 m behind the pole (the houses).
  const double street = lux({0.0, -9.0, 0.0});
  const double house = lux({0.0, 9.0, 0.0});
  INFO("lux 9 m over the street " << street << ", 9 m behind " << house);
  CHECK(street > 5.0);
  CHECK(house < 0.4 * street);
  // A lamp on top of its pole (no arm) lights all round.
  lamp.side = {};
  CHECK(lux({0.0, 9.0, 0.0}) == Approx(lux({0.0, -9.0, 0.0})));
}

TEST_CASE("highlights past white keep their hue and burn out to white far above it",
          "[sensors][camera][tone]") {
  RgbOptions options;
  options.noise = false;
  options.vignetting = 0.0;
  detail::Exposure exposure;
  exposure.scale = 1.0;
  // Four pixels, exposed: a mid grey, a warm lit window 13 times white, a red lamp's halo and
  // a lamp's core 2,000 times white.
  const std::vector<float> linear = {0.18f, 0.18f, 0.18f, 13.0f,   9.0f,    5.0f,
                                     6.0f,  0.6f,  0.3f,  2000.0f, 1500.0f, 900.0f};
  for (const bool noise : {false, true}) {
    options.noise = noise;
    const std::vector<uint8_t> out = detail::develop(linear, 4, 1, options, exposure, 7);
    INFO("noise " << noise << ": window " << int(out[3]) << ", " << int(out[4]) << ", "
                  << int(out[5]) << "; halo " << int(out[6]) << ", " << int(out[7]) << ", "
                  << int(out[8]) << "; core " << int(out[9]) << ", " << int(out[10]) << ", "
                  << int(out[11]));
    // Mid grey stays grey and mid-tone.
    CHECK(std::abs(out[0] - out[1]) <= 2);
    CHECK(out[0] > 60);
    CHECK(out[0] < 160);
    // The window: its brightest channel at white, the others short of it, in their order (the
    // channels compressed one by one all come out at 255).
    CHECK(out[3] >= 250);
    CHECK(out[5] < 235);
    CHECK(out[3] > out[4]);
    CHECK(out[4] > out[5]);
    // The red halo stays red.
    CHECK(out[6] >= 245);
    CHECK(out[7] < 150);
    CHECK(out[8] < out[7]);
    // The core burns out.
    CHECK(out[9] == 255);
    CHECK(out[10] == 255);
    CHECK(out[11] == 255);
  }
}

TEST_CASE("the tabulated sky reads within 1% of the evaluated one", "[sensors][camera][sky]") {
  for (const double elevation : {1.2, 0.3, 0.02, -0.05}) {
    const Lighting l = sun_at(0.7, elevation);
    for (int i = 0; i < 40; ++i) {
      for (int j = 0; j < 24; ++j) {
        const double az = i * 2.0 * M_PI / 40.0 + 0.013;
        const double el = (j + 0.5) * (M_PI / 2.0) / 24.0;
        const Vec3 d{std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
        const Color table = l.sky_model.radiance(d);
        const Color exact =
            l.sky_model.radiance_above(d.z, std::clamp(dot(d, l.sun_direction), -1.0, 1.0));
        INFO("sun elevation " << elevation << ", view azimuth " << az << ", elevation " << el);
        CHECK(luminance(table) == Approx(luminance(exact)).epsilon(0.01));
        CHECK(table.b / table.r == Approx(exact.b / exact.r).epsilon(0.01));
      }
    }
  }
}

TEST_CASE("a low beam lights the road ahead below its cut-off and little above or at the bumper",
          "[sensors][camera][lights]") {
  // A headlight 0.65 m above the road, facing +x with its left towards +y, aimed 1 degree down.
  detail::Light beam;
  beam.position = {0.0, 0.0, 0.65};
  beam.axis = normalized(Vec3{1.0, 0.0, -0.0175});
  beam.side = {0.0, 1.0, 0.0};
  beam.intensity = {0.12, 0.12, 0.12};
  beam.range = 80.0;
  beam.pattern = detail::LightPattern::kLowBeam;
  const double hot = intensity_towards(beam, {30.0, 0.0, 0.65 - 30.0 * 0.02});  // 1.1 deg down
  CHECK(hot > 0.8 * 0.12);
  // 2 degrees above the horizon (an oncoming driver's eyes, a tree crown): the cut-off.
  CHECK(intensity_towards(beam, {30.0, 0.0, 0.65 + 30.0 * 0.035}) < 0.05 * hot);
  // The road 2.5 m ahead of the lamp, 15 degrees down: a few per cent of the hot spot.
  CHECK(intensity_towards(beam, {2.5, 0.0, 0.0}) < 0.05 * hot);
  // 45 degrees to the side the beam has faded.
  CHECK(intensity_towards(beam, {20.0, 20.0, 0.0}) < 0.1 * hot);
  // Behind the lamp: nothing.
  CHECK(intensity_towards(beam, {-5.0, 0.0, 0.0}) == 0.0);
  // Beyond its range: nothing.
  CHECK(intensity_towards(beam, {90.0, 0.0, 0.0}) == 0.0);
}

TEST_CASE("at night a car's low beams light the road in front of it", "[sensors][camera][lights]") {
  // A car 20 m ahead facing the camera (heading pi): its beams light the road between.
  auto car = box_entity(3, "car", 20.0, 0.0, 4.5, 1.8, 1.5, corsa::engine::EntityCategory::kCar);
  car.pose.h = M_PI;
  Scene scene;
  scene.add_road_mesh(corsa::test::flat_road());
  scene.commit();
  scene.set_entities(std::vector<corsa::engine::EntitySnapshot>{car});
  CameraIntrinsics k;
  k.width = 320;
  k.height = 240;
  k.fov_deg = 60.0;
  const CameraRenderer camera(k);
  const Lighting night = sun_at(0.0, -0.4);
  REQUIRE(night.headlights);
  RenderSettings settings;
  settings.outputs.rgb = true;
  settings.lighting = &night;
  settings.rgb.noise = false;
  settings.rgb.auto_exposure = false;
  settings.rgb.iso = 3200.0;
  settings.rgb.shutter_speed_s = 1.0 / 60.0;
  CameraMotion motion;
  motion.world_from_body = rigid_from_pose(0.0, 0.0, 1.2, 0.0, 0.0, 0.0);
  const CameraImages lit = camera.render(scene, motion, settings);
  // The scenario switched the low beam off.
  car.lights_on = 0;
  car.lights_set = corsa::engine::light_bit(corsa::engine::VehicleLight::kLowBeam);
  scene.set_entities(std::vector<corsa::engine::EntitySnapshot>{car});
  const CameraImages dark = camera.render(scene, motion, settings);
  // Road 12 m ahead of the camera (8 m in front of the car): row 119.5 + f * 1.2 / 12.
  const double f = 160.0 / std::tan(M_PI / 6.0);
  const int row = static_cast<int>(119.5 + f * 1.2 / 12.0 + 0.5);
  auto green = [&](const CameraImages& img) {
    return static_cast<int>(img.rgb[3 * (static_cast<size_t>(row) * 320 + 160) + 1]);
  };
  CHECK(green(lit) > green(dark) + 30);
}

TEST_CASE("a LightStateAction's colour tints a low beam and its intensity scales it",
          "[sensors][camera][lights]") {
  using corsa::engine::light_bit;
  using corsa::engine::VehicleLight;
  auto car = box_entity(3, "car", 20.0, 0.0, 4.5, 1.8, 1.5, corsa::engine::EntityCategory::kCar);
  car.pose.h = M_PI;
  car.lights_on = car.lights_set = light_bit(VehicleLight::kLowBeam);
  Scene scene;
  scene.add_road_mesh(corsa::test::flat_road());
  scene.commit();
  CameraIntrinsics k;
  k.width = 160;
  k.height = 120;
  k.fov_deg = 60.0;
  const CameraRenderer camera(k);
  const Lighting night = sun_at(0.0, -0.4);
  RenderSettings settings;
  settings.outputs.rgb = true;
  settings.lighting = &night;
  settings.rgb.noise = false;
  settings.rgb.auto_exposure = false;
  settings.rgb.iso = 800.0;
  settings.rgb.shutter_speed_s = 1.0 / 60.0;
  CameraMotion motion;
  motion.world_from_body = rigid_from_pose(0.0, 0.0, 1.2, 0.0, 0.0, 0.0);
  auto render = [&](std::vector<corsa::engine::LightLook> looks) {
    car.light_looks = std::move(looks);
    scene.set_entities(std::vector<corsa::engine::EntitySnapshot>{car});
    return camera.render(scene, motion, settings);
  };
  // Road 12 m ahead of the camera (8 m in front of the car), in the beams.
  const double f = 80.0 / std::tan(M_PI / 6.0);
  const int row = static_cast<int>(59.5 + f * 1.2 / 12.0 + 0.5);
  auto road = [&](const CameraImages& img, int channel) {
    return static_cast<int>(img.rgb[3 * (static_cast<size_t>(row) * 160 + 80) + channel]);
  };
  const CameraImages plain = render({});
  corsa::engine::LightLook red{.light = VehicleLight::kLowBeam};
  red.colour_share = {1.0 / 0.2126, 0.0, 0.0};  // pure red at the lamp's own intensity
  const CameraImages tinted = render({red});
  corsa::engine::LightLook dim{.light = VehicleLight::kLowBeam};
  dim.lamp_colour_cd = 3000.0;  // a quarter of the renderer's 12,000 cd low beam
  const CameraImages dimmed = render({dim});
  INFO("road pixel: plain " << road(plain, 0) << "/" << road(plain, 1) << "/" << road(plain, 2)
                            << ", red " << road(tinted, 0) << "/" << road(tinted, 1) << "/"
                            << road(tinted, 2) << ", dimmed " << road(dimmed, 1));
  REQUIRE(road(plain, 1) > 40);
  // Red light: the road's red stays, its green and blue go dark.
  CHECK(road(tinted, 0) > road(tinted, 1) + 30);
  CHECK(road(tinted, 1) < road(plain, 1) / 3);
  CHECK(road(tinted, 2) < road(plain, 2) / 3);
  // A quarter of the intensity: clearly darker, still lit.
  CHECK(road(dimmed, 1) < road(plain, 1) - 20);
  // The same look with the lamp's own share reproduces the plain frame byte for byte.
  corsa::engine::LightLook same{.light = VehicleLight::kLowBeam};
  same.lamp_share = 1.0;
  CHECK(render({same}).rgb == plain.rgb);
}

TEST_CASE("a night frame with lamps is the same bytes on 1 and 2 threads at every quality",
          "[sensors][camera][determinism]") {
  auto car = box_entity(4, "car", 15.0, 2.0, 4.5, 1.8, 1.5, corsa::engine::EntityCategory::kCar);
  car.pose.h = M_PI;
  car.vx = -8.0;
  Scene scene;
  scene.add_road_mesh(corsa::test::flat_road());
  scene.commit();
  scene.set_entities(std::vector<corsa::engine::EntitySnapshot>{car});
  CameraIntrinsics k;
  k.width = 320;
  k.height = 240;
  const CameraRenderer camera(k);
  const Lighting night = sun_at(0.0, -0.4);
  for (const RenderQuality quality :
       {RenderQuality::kFast, RenderQuality::kDefault, RenderQuality::kHigh}) {
    auto run = [&](int threads) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      RenderSettings settings;
      settings.outputs = {.rgb = true, .depth = true};
      settings.lighting = &night;
      settings.rgb.quality = quality;
      settings.frame_seed = 11;
      CameraMotion motion;
      motion.world_from_body = rigid_from_pose(0.0, 0.0, 1.2, 0.0, 0.0, 0.0);
      motion.velocity = {8.0, 0.0, 0.0};
      return camera.render(scene, motion, settings);
    };
    INFO("quality " << render_quality_name(quality));
    const CameraImages a = run(1);
    const CameraImages b = run(2);
    CHECK(a.rgb == b.rgb);
    CHECK(a.depth == b.depth);
  }
}

TEST_CASE("the fast preset leaves out motion blur and default keeps it",
          "[sensors][camera][quality]") {
  auto car = box_entity(4, "car", 12.0, 2.0, 4.5, 1.8, 1.5, corsa::engine::EntityCategory::kCar);
  car.vx = -10.0;
  Scene scene;
  scene.add_road_mesh(corsa::test::flat_road());
  scene.commit();
  scene.set_entities(std::vector<corsa::engine::EntitySnapshot>{car});
  CameraIntrinsics k;
  k.width = 320;
  k.height = 240;
  const CameraRenderer camera(k);
  const Lighting noon = sun_at(M_PI, 1.2);
  auto frame = [&](RenderQuality quality, double speed) {
    RenderSettings settings;
    settings.outputs = {.rgb = true, .depth = true, .semantic = true};
    settings.lighting = &noon;
    settings.rgb.quality = quality;
    settings.rgb.auto_exposure = false;
    settings.rgb.shutter_speed_s = 0.02;  // a long exposure: blur of several pixels
    settings.frame_seed = 3;
    CameraMotion motion;
    motion.world_from_body = rigid_from_pose(0.0, 0.0, 1.2, 0.0, 0.0, 0.0);
    motion.velocity = {speed, 0.0, 0.0};
    return camera.render(scene, motion, settings);
  };
  // The car moves in both frames; only the camera's own speed differs. Without blur the
  // frame is that instant's, whatever moves.
  const CameraImages fast_moving = frame(RenderQuality::kFast, 15.0);
  const CameraImages fast_still = frame(RenderQuality::kFast, 0.0);
  CHECK(fast_moving.rgb == fast_still.rgb);
  const CameraImages default_moving = frame(RenderQuality::kDefault, 15.0);
  const CameraImages default_still = frame(RenderQuality::kDefault, 0.0);
  CHECK(default_moving.rgb != default_still.rgb);
  // Labels and depth never depend on the preset or the blur.
  CHECK(fast_moving.semantic == default_moving.semantic);
  CHECK(fast_moving.depth == default_moving.depth);
}

TEST_CASE("the fast preset develops without sensor noise and default adds it",
          "[sensors][camera][quality]") {
  Scene scene;
  scene.add_road_mesh(corsa::test::flat_road());
  scene.commit();
  CameraIntrinsics k;
  k.width = 160;
  k.height = 120;
  const CameraRenderer camera(k);
  const Lighting noon = sun_at(M_PI, 1.2);
  // The noise is the only part of a still frame without rain that the frame seed changes: at a
  // high gain it shows in every channel of every pixel.
  auto frame = [&](RenderQuality quality, uint64_t seed) {
    RenderSettings settings;
    settings.outputs.rgb = true;
    settings.lighting = &noon;
    settings.rgb.quality = quality;
    settings.rgb.auto_exposure = false;
    settings.rgb.iso = 1600.0;
    settings.rgb.shutter_speed_s = 1.0 / 4000.0;
    settings.frame_seed = seed;
    CameraMotion motion;
    motion.world_from_body = rigid_from_pose(0.0, 0.0, 1.2, 0.0, 0.0, 0.0);
    return camera.render(scene, motion, settings).rgb;
  };
  const std::vector<uint8_t> fast_a = frame(RenderQuality::kFast, 3);
  CHECK(fast_a == frame(RenderQuality::kFast, 4));
  const std::vector<uint8_t> default_a = frame(RenderQuality::kDefault, 3);
  const std::vector<uint8_t> default_b = frame(RenderQuality::kDefault, 4);
  size_t differing = 0;
  for (size_t i = 0; i < default_a.size(); ++i) {
    differing += default_a[i] != default_b[i] ? 1 : 0;
  }
  CHECK(differing > default_a.size() / 4);
  // A flat patch of the fast frame (the road straight ahead, whose texture is averaged over
  // the distant pixels, and the sky above the horizon) changes smoothly: neighbours along a
  // sky row differ by at most one level.
  const auto at = [&](int row, int col, int c) {
    return static_cast<int>(fast_a[3 * (static_cast<size_t>(row) * k.width + col) + c]);
  };
  for (int col = 40; col < 120; ++col) {
    for (int c = 0; c < 3; ++c) {
      INFO("sky row 10, column " << col << ", channel " << c);
      CHECK(std::abs(at(10, col + 1, c) - at(10, col, c)) <= 1);
    }
  }
}

TEST_CASE("a fast frame in rain draws its streaks by each pixel's own distance",
          "[sensors][camera][quality]") {
  // `fast` composites in the tile and keeps only each pixel's distance for the rain's depth
  // test, in buffers kept from frame to frame: every pixel must be written anew, the sky too.
  auto car = box_entity(4, "car", 6.0, 0.0, 4.5, 1.8, 1.5, corsa::engine::EntityCategory::kCar);
  Scene scene;
  scene.add_road_mesh(corsa::test::flat_road());
  scene.commit();
  scene.set_entities(std::vector<corsa::engine::EntitySnapshot>{car});
  CameraIntrinsics k;
  k.width = 320;
  k.height = 240;
  corsa::engine::EnvironmentState env;
  env.sun_azimuth = M_PI;
  env.sun_elevation = 0.8;
  env.precipitation = corsa::engine::PrecipitationType::kRain;
  env.precipitation_intensity = 25.0;
  const Lighting rain = compute_lighting(env, {});
  Lighting no_streaks = rain;  // the same light and air, nothing drawn over the image
  no_streaks.rain_intensity = 0.0;
  auto frame = [&](const CameraRenderer& camera, const Lighting& light, RenderQuality quality,
                   double heading) {
    RenderSettings settings;
    settings.outputs = {.rgb = true, .semantic = true};
    settings.lighting = &light;
    settings.rgb.quality = quality;
    settings.frame_seed = 5;
    CameraMotion motion;
    motion.world_from_body = rigid_from_pose(0.0, 0.0, 1.2, heading, 0.0, 0.0);
    return camera.render(scene, motion, settings);
  };
  const CameraRenderer used(k);
  frame(used, rain, RenderQuality::kDefault, 0.0);  // the car and its distances in the buffers
  const CameraImages after = frame(used, rain, RenderQuality::kFast, M_PI);  // looking away
  const CameraRenderer fresh(k);
  CHECK(after.rgb == frame(fresh, rain, RenderQuality::kFast, M_PI).rgb);
  // Streaks cross the sky (infinitely far: every streak is in front of it).
  const CameraImages dry = frame(fresh, no_streaks, RenderQuality::kFast, M_PI);
  size_t sky = 0, streaked_sky = 0;
  for (size_t px = 0; px < after.semantic.size(); ++px) {
    if (after.semantic[px] == static_cast<uint8_t>(SemanticClass::kSky)) {
      ++sky;
      bool changed = false;
      for (int c = 0; c < 3; ++c) {
        changed = changed || after.rgb[3 * px + c] != dry.rgb[3 * px + c];
      }
      streaked_sky += changed ? 1 : 0;
    }
  }
  CHECK(sky > after.semantic.size() / 4);
  CHECK(streaked_sky > 50);
}
