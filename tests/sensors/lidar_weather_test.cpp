// The LiDAR as a spinning sensor on a moving car in weather: its own car masked, each point's
// firing time, the sensor and other entities moving during the sweep (and deskewed), early
// returns from fog (Hahner et al. 2021), rain drops and snowflakes (Kilic et al. 2021); and what
// snow and wind do to the camera.

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "corsa/sensors/environment.h"
#include "corsa/sensors/labels.h"
#include "corsa/sensors/lidar.h"
#include "fixtures.h"
#include "shading.h"

using namespace corsa::sensors;

namespace {

constexpr double kPi = std::numbers::pi;

/// One horizontal beam, 3600 firings per turn at 10 Hz.
LidarOptions flat_lidar() {
  LidarOptions o;
  o.channels = 1;
  o.lower_fov_deg = 0.0;
  o.upper_fov_deg = 0.0;
  o.points_per_second = 36000.0;
  o.rotation_frequency_hz = 10.0;
  o.range_m = 100.0;
  return o;
}

LidarOptions roof_lidar() {
  LidarOptions o;
  o.channels = 32;
  o.lower_fov_deg = -30.0;
  o.upper_fov_deg = 10.0;
  o.points_per_second = 300000.0;
  o.range_m = 100.0;
  return o;
}

Scene committed_scene(bool ground) {
  Scene scene;
  if (ground) {
    scene.add_road_mesh(corsa::test::flat_road());
  }
  scene.commit();
  return scene;
}

double range_of(const LidarPoint& p) { return std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z); }

/// Points with class none and instance 0 nearer than `within` m: the atmosphere's returns.
size_t early_returns(const PointCloud& cloud, double within) {
  size_t n = 0;
  for (const LidarPoint& p : cloud.points) {
    n += p.instance_id == 0 && p.semantic == SemanticClass::kUnlabeled && range_of(p) < within ? 1
                                                                                               : 0;
  }
  return n;
}

/// Road points at the same beam in both clouds: the mean of (weather intensity / clear
/// intensity) / e^(-2 alpha r), and the mean of the plain ratio; with how many points.
struct Dimming {
  double against_expected = 0.0;
  double ratio = 0.0;
  size_t points = 0;
};
Dimming road_dimming(const PointCloud& clear, const PointCloud& weather, double alpha) {
  Dimming d;
  for (size_t i = 0, j = 0; i < clear.points.size() && j < weather.points.size();) {
    const LidarPoint& a = clear.points[i];
    const LidarPoint& b = weather.points[j];
    const int order = (a.azimuth_index - b.azimuth_index) * 64 + (a.ring - b.ring);
    if (order < 0) {
      ++i;
    } else if (order > 0) {
      ++j;
    } else {
      if (b.semantic == SemanticClass::kRoad && a.semantic == SemanticClass::kRoad) {
        const double ratio = b.intensity / a.intensity;
        d.against_expected += ratio / std::exp(-2.0 * alpha * range_of(a));
        d.ratio += ratio;
        ++d.points;
      }
      ++i;
      ++j;
    }
  }
  if (d.points > 0) {
    d.against_expected /= static_cast<double>(d.points);
    d.ratio /= static_cast<double>(d.points);
  }
  return d;
}

}  // namespace

TEST_CASE("a roof LiDAR does not see its own car unless asked to", "[sensors][lidar][self]") {
  Scene scene = committed_scene(true);
  // The demo's sedan (box 4.7 x 1.85 x 1.5 m, centre 1.4 m ahead of the rear axle).
  corsa::engine::EntitySnapshot car = corsa::test::box_entity(1, "Ego", 0.0, 0.0, 4.7, 1.85, 1.5,
                                                              corsa::engine::EntityCategory::kCar);
  car.box.center_x = 1.4;
  scene.set_entities(std::vector{car});
  LidarScanInput input;
  input.world_from_sensor = rigid_from_pose(1.0, 0.0, 1.9, 0.0, 0.0, 0.0);  // the old demo mount
  input.carrier = entity_box(car);
  input.carrier_instance = 1;
  LidarOptions keep = roof_lidar();
  keep.keep_self_returns = true;
  const PointCloud kept = LidarSimulator(keep).scan(scene, input);
  const PointCloud masked = LidarSimulator(roof_lidar()).scan(scene, input);
  size_t self = 0;
  for (const LidarPoint& p : kept.points) {
    self += p.instance_id == 1 ? 1 : 0;
  }
  // 0.4 m above the roof with a -30 degree lower field of view, the steepest beams end on the
  // roof, bonnet and boot: about a tenth of the points of this flat scene (9.9% measured; the
  // roof, narrower and shorter than the box, lets the shallower beams pass).
  const double share = static_cast<double>(self) / static_cast<double>(kept.points.size());
  CHECK(share > 0.08);
  for (const LidarPoint& p : masked.points) {
    CHECK(p.instance_id != 1);
  }
  CHECK(masked.points.size() == kept.points.size() - self);  // those beams give no point
}

TEST_CASE("each LiDAR point carries its firing time; forward fires at the capture time",
          "[sensors][lidar][motion]") {
  Scene scene = committed_scene(true);
  LidarOptions o = roof_lidar();
  o.horizontal_fov_deg = 360.0;
  const LidarSimulator lidar(o);
  LidarScanInput input;
  input.world_from_sensor = rigid_from_pose(0.0, 0.0, 2.0, 0.7, 0.0, 0.0);
  const PointCloud cloud = lidar.scan(scene, input);
  REQUIRE(!cloud.points.empty());
  float lowest = 1.0f, highest = -1.0f;
  for (const LidarPoint& p : cloud.points) {
    const double azimuth = std::atan2(p.y, p.x);
    CHECK(p.time == Approx(azimuth / (2.0 * kPi * 10.0)).margin(1e-4));
    lowest = std::min(lowest, p.time);
    highest = std::max(highest, p.time);
  }
  CHECK(lowest == Approx(-0.05).margin(1e-3));  // half a turn at 10 Hz before
  CHECK(highest == Approx(0.05).margin(1e-3));  // and after
}

TEST_CASE("a moving LiDAR sees the world move during its sweep; deskew takes it out",
          "[sensors][lidar][motion]") {
  Scene scene = committed_scene(false);
  // Walls 20 m ahead of and behind the sensor (at the capture time), 40 m wide.
  scene.set_entities(std::vector{corsa::test::box_entity(1, "front", 20.5, 0.0, 1.0, 40.0, 10.0),
                                 corsa::test::box_entity(2, "back", -20.5, 0.0, 1.0, 40.0, 10.0)});
  LidarScanInput input;
  input.world_from_sensor = rigid_from_pose(0.0, 0.0, 1.5, 0.0, 0.0, 0.0);
  input.motion.velocity = {20.0, 0.0, 0.0};  // 72 km/h along x: 1 m in 50 ms
  input.motion.pivot = {0.0, 0.0, 0.0};
  const PointCloud raw = LidarSimulator(flat_lidar()).scan(scene, input);
  LidarOptions deskewed = flat_lidar();
  deskewed.deskew = true;
  const PointCloud fixed = LidarSimulator(deskewed).scan(scene, input);
  auto wall_x = [](const PointCloud& c, double azimuth, float time_sign) {
    for (const LidarPoint& p : c.points) {
      if (std::abs(std::remainder(std::atan2(p.y, p.x) - azimuth, 2.0 * kPi)) < 0.01 &&
          p.time * time_sign >= 0.0f) {
        return static_cast<double>(p.x);
      }
    }
    return 0.0;
  };
  // Forward fires at the capture: the front wall 20 m ahead.
  CHECK(wall_x(raw, 0.0, 1.0f) == Approx(20.0).margin(0.02));
  // Behind, just after the capture (+50 ms) the car is 1 m further: the wall 21 m back; just
  // before (-50 ms) 19 m: the seam of a rolling shutter.
  CHECK(wall_x(raw, kPi, 1.0f) == Approx(-21.0).margin(0.05));
  CHECK(wall_x(raw, kPi, -1.0f) == Approx(-19.0).margin(0.05));
  // Deskewed: in the sensor frame of the capture time, both 20 m back.
  CHECK(wall_x(fixed, kPi, 1.0f) == Approx(-20.0).margin(0.05));
  CHECK(wall_x(fixed, kPi, -1.0f) == Approx(-20.0).margin(0.05));
}

TEST_CASE("entities move during the sweep: a car behind is caught at two places",
          "[sensors][lidar][motion]") {
  Scene scene = committed_scene(false);
  // A 4 m long box 10 m behind the still sensor, driving toward it at 10 m/s (a plain box, so
  // that its front face is exactly the box's: a generated car's nose lies a little inside).
  corsa::engine::EntitySnapshot car = corsa::test::box_entity(5, "car", -12.0, 0.0, 4.0, 2.0, 3.0);
  car.vx = 10.0;
  const double sweep = 0.1;  // s, one turn at 10 Hz
  scene.set_entities(std::vector{car}, sweep);
  LidarScanInput input;
  input.world_from_sensor = rigid_from_pose(0.0, 0.0, 1.5, 0.0, 0.0, 0.0);
  input.scene_motion_span = sweep;
  const PointCloud cloud = LidarSimulator(flat_lidar()).scan(scene, input);
  double early = 0.0, late = 0.0;  // the car's front face on either side of the seam
  size_t n_early = 0, n_late = 0;
  for (const LidarPoint& p : cloud.points) {
    if (p.instance_id != 5) {
      continue;
    }
    if (p.time > 0.0f) {
      late += p.x;
      ++n_late;
    } else {
      early += p.x;
      ++n_early;
    }
  }
  REQUIRE(n_early > 10);
  REQUIRE(n_late > 10);
  // Its front (at x = -10 at the capture) is 0.5 m nearer at +50 ms than at -50 ms... seen
  // within a few degrees of straight behind.
  CHECK(late / n_late - early / n_early == Approx(1.0).margin(0.05));
  // The same scene without motion: one face.
  scene.set_entities(std::vector{car});
  input.scene_motion_span = 0.0;
  for (const LidarPoint& p : LidarSimulator(flat_lidar()).scan(scene, input).points) {
    if (p.instance_id == 5) {
      CHECK(p.x == Approx(-10.0).margin(0.01));
    }
  }
}

TEST_CASE("fog gives early returns from its backscatter and dims what gets through",
          "[sensors][lidar][weather]") {
  Scene scene = committed_scene(true);
  const LidarSimulator lidar(roof_lidar());
  LidarScanInput input;
  input.world_from_sensor = rigid_from_pose(0.0, 0.0, 2.0, 0.0, 0.0, 0.0);
  input.frame_seed = 3;
  const PointCloud clear = lidar.scan(scene, input);
  CHECK(early_returns(clear, 10.0) == 0);
  input.weather.fog_extinction = fog_extinction(30.0);
  const PointCloud dense = lidar.scan(scene, input);
  input.weather.fog_extinction = fog_extinction(100.0);
  const PointCloud light = lidar.scan(scene, input);
  input.weather.fog_extinction = fog_extinction(300.0);
  const PointCloud haze = lidar.scan(scene, input);
  const size_t dense_early = early_returns(dense, 15.0);
  const size_t light_early = early_returns(light, 15.0);
  // Dense fog: the beams to the sky and to the far road come back from the fog itself, a shell
  // a few metres out; thinner fog: fewer; in 300 m fog its echo stays below the threshold.
  INFO(dense_early << " and " << light_early << " early returns of " << dense.rays);
  CHECK(dense_early > dense.points.size() / 3);
  CHECK(light_early > 0);
  CHECK(light_early < dense_early);
  CHECK(early_returns(haze, 15.0) == 0);
  for (const LidarPoint& p : dense.points) {
    if (p.instance_id == 0 && p.semantic == SemanticClass::kUnlabeled) {
      CHECK(range_of(p) > 1.4);
      CHECK(range_of(p) < 20.0);
    }
  }
  // What gets through to the road is dimmed by the two-way transmission e^(-2 alpha r).
  const Dimming dimming = road_dimming(clear, light, fog_extinction(100.0));
  REQUIRE(dimming.points > 100);
  CHECK(dimming.against_expected == Approx(1.0).margin(0.01));
}

TEST_CASE("rain drops and snowflakes near the sensor answer some beams; snow more than rain",
          "[sensors][lidar][weather]") {
  Scene scene = committed_scene(true);
  const LidarSimulator lidar(roof_lidar());
  LidarScanInput input;
  input.world_from_sensor = rigid_from_pose(0.0, 0.0, 2.0, 0.0, 0.0, 0.0);
  input.frame_seed = 8;
  input.weather.rain_rate = 10.0;
  const PointCloud rain = lidar.scan(scene, input);
  input.weather.rain_rate = 0.0;
  input.weather.snow_rate = 1.0;
  const PointCloud snow = lidar.scan(scene, input);
  const double beams = static_cast<double>(rain.rays);
  const double rain_share = static_cast<double>(early_returns(rain, 20.0)) / beams;
  const double snow_share = static_cast<double>(early_returns(snow, 20.0)) / beams;
  INFO("rain " << rain_share << ", snow " << snow_share);
  // A few drops in heavy rain (expected about 0.05% of the beams), many flakes in snow.
  CHECK(rain_share > 1e-4);
  CHECK(rain_share < 0.01);
  CHECK(snow_share > 0.05);
  CHECK(snow_share > 10.0 * rain_share);
  // Rain's extinction from Marshall and Palmer's drops (pi N0 / Lambda^3).
  CHECK(rain_extinction(10.0) == Approx(3.65e-4 * std::pow(10.0, 0.63)).epsilon(0.01));
  // Same seed, same drops.
  input.weather.snow_rate = 0.0;
  input.weather.rain_rate = 10.0;
  CHECK(lidar.scan(scene, input).points.size() == rain.points.size());
}

TEST_CASE(
    "rain and snow dim what gets through by e^(-2 alpha r); the harder it falls, the more "
    "early returns",
    "[sensors][lidar][weather]") {
  Scene scene = committed_scene(true);
  const LidarSimulator lidar(roof_lidar());
  LidarScanInput input;
  input.world_from_sensor = rigid_from_pose(0.0, 0.0, 2.0, 0.0, 0.0, 0.0);
  input.frame_seed = 5;
  const PointCloud clear = lidar.scan(scene, input);
  // The road's returns, beam by beam, against clear air: dimmed by the two-way transmission of
  // the precipitation's extinction (Marshall-Palmer drops for rain, Rasmussen et al.'s dry
  // snow; both checked against their papers' formulas in this file).
  auto dimming = [&](double rain_rate, double snow_rate) {
    input.weather.rain_rate = rain_rate;
    input.weather.snow_rate = snow_rate;
    return road_dimming(clear, lidar.scan(scene, input),
                        rain_extinction(rain_rate) + snow_extinction(snow_rate));
  };
  for (const auto& [rain_rate, snow_rate] :
       {std::pair{10.0, 0.0}, std::pair{50.0, 0.0}, std::pair{0.0, 1.0}, std::pair{0.0, 5.0}}) {
    const Dimming d = dimming(rain_rate, snow_rate);
    INFO("rain " << rain_rate << " mm/h, snow " << snow_rate << " mm/h: " << d.points
                 << " road points, mean intensity ratio " << d.ratio << ", against e^(-2 alpha r) "
                 << d.against_expected);
    REQUIRE(d.points > 100);
    CHECK(d.ratio < 0.97);                                  // visibly dimmer than in clear air
    CHECK(d.against_expected == Approx(1.0).margin(1e-3));  // float intensities
  }
  // 1 mm/h of snow (0.8 km visual range) dims the road more than 10 mm/h of rain (7 km).
  CHECK(dimming(0.0, 1.0).ratio < dimming(10.0, 0.0).ratio);
  // Early returns (within 20 m) grow with the rate: more drops and flakes, and bigger ones.
  auto early = [&](double rain_rate, double snow_rate) {
    input.weather.rain_rate = rain_rate;
    input.weather.snow_rate = snow_rate;
    return early_returns(lidar.scan(scene, input), 20.0);
  };
  const size_t rain_2 = early(2.0, 0.0), rain_10 = early(10.0, 0.0), rain_50 = early(50.0, 0.0);
  const size_t snow_02 = early(0.0, 0.2), snow_1 = early(0.0, 1.0), snow_5 = early(0.0, 5.0);
  INFO("rain 2 / 10 / 50 mm/h: " << rain_2 << " / " << rain_10 << " / " << rain_50
                                 << "; snow 0.2 / 1 / 5 mm/h: " << snow_02 << " / " << snow_1
                                 << " / " << snow_5 << " early returns of " << clear.rays);
  CHECK(rain_2 < rain_10);
  CHECK(rain_10 < rain_50);
  CHECK(snow_02 < snow_1);
  CHECK(snow_1 < snow_5);
}

TEST_CASE(
    "dry snow of 1 mm/h water equivalent leaves about 0.8 km of visual range, less the "
    "harder it snows",
    "[sensors][weather]") {
  // Rasmussen et al. 1999, Eq. 13 in the paper's cgs units: S = 1.3 C3 Vt / Vis with S the
  // liquid-equivalent rate (cm/s), C3 = 0.017 g/cm^2 and Vt = 100 cm/s for dry aggregates, Vis
  // in cm; 1.3 = 3.912 / 3, so sigma = 3 S / (C3 Vt) per cm.
  auto rasmussen = [](double mm_per_h) {
    const double s_cm_per_s = mm_per_h / 10.0 / 3600.0;
    return 3.0 * s_cm_per_s / (0.017 * 100.0) * 100.0;  // 1/m
  };
  for (const double rate : {0.2, 1.0, 2.0, 5.0}) {
    CHECK(snow_extinction(rate) == Approx(rasmussen(rate)).epsilon(1e-9));
  }
  const auto visual_range = [](double rate) { return 3.912 / snow_extinction(rate); };
  // 1 mm/h: 0.80 km (the melted-drop extinction of Gunn and Marshall's flakes, 7.2e-4 1/m,
  // gave 5.4 km, the range of light rain).
  CHECK(visual_range(1.0) > 500.0);
  CHECK(visual_range(1.0) < 1500.0);
  // 2 mm/h: the paper's Fig. 10 reads 0.3 km for dry snow, its Eq. 13 gives 0.40 km.
  CHECK(visual_range(2.0) > 300.0);
  CHECK(visual_range(2.0) < 450.0);
  CHECK(visual_range(5.0) < visual_range(1.0) / 4.0);
  CHECK(visual_range(0.2) > 3000.0);  // light snow
  // Snow obscures far more than rain of the same water: 1 mm/h of rain leaves 10 km.
  CHECK(snow_extinction(1.0) > 10.0 * rain_extinction(1.0));
  // The LiDAR's flakes are the same aggregates: Gunn and Marshall's (1958) melted diameters
  // N(D) = 3800 R^-0.87 e^(-2.55 R^-0.48 D) made flakes of density C3 / D_f
  // (D_f^2 = rho_w D^3 / C3, never below D), each removing twice its cross-section, give
  // Rasmussen's extinction within a few percent at 1 mm/h (numerical integral, D in mm).
  const double c3 = 0.017 * 10.0;  // g/cm^2 -> kg/m^2
  double integral = 0.0;           // 1/m
  const double step = 1e-4;        // mm
  for (double d = 0.5 * step; d < 30.0; d += step) {
    const double flake_mm = std::max(d, std::sqrt(1000.0 / c3 * 1e-3 * d * d * d));
    const double n = 3800.0 * std::exp(-2.55 * d);  // 1/(m^3 mm)
    integral += 2.0 * 0.25 * kPi * (flake_mm * 1e-3) * (flake_mm * 1e-3) * n * step;
  }
  CHECK(integral == Approx(snow_extinction(1.0)).epsilon(0.05));
}

TEST_CASE("snow falls in the camera image and the wind slants rain and snow across the view",
          "[sensors][camera][weather]") {
  corsa::engine::EnvironmentState env;
  env.precipitation = corsa::engine::PrecipitationType::kSnow;
  env.precipitation_intensity = 1.0;
  const Lighting snow = compute_lighting(env, {});
  CHECK(snow.snow_extinction > 0.0);
  CHECK(snow.extinction() > 0.0);  // haze in the image too
  // The camera and the LiDAR see the same air: the size distributions' extinction.
  CHECK(snow.snow_extinction == snow_extinction(1.0));
  CHECK(snow.extinction() == Approx(snow.fog_extinction + snow_extinction(1.0)));
  const int w = 640, h = 360;
  const double fx = 500.0, exposure_s = 1.0 / 30.0;
  // A grey linear image of a scene far beyond the drops and flakes.
  constexpr float kGrey = 0.05f;
  const std::vector<float> grey(static_cast<size_t>(w) * h * 3, kGrey);
  const std::vector<float> far(static_cast<size_t>(w) * h, 1e4f);
  auto drawn = [&](const Lighting& l, double lateral_wind) {
    std::vector<float> image = grey;
    corsa::sensors::detail::draw_precipitation(image, far, w, h, fx, l, lateral_wind, exposure_s,
                                               42);
    return image;
  };
  const auto calm = drawn(snow, 0.0);
  CHECK(calm != grey);  // flakes
  // Which way the trails lean: changed pixels whose lower-right neighbour changed too, less
  // those whose lower-left one did (positive: down and to the right, downwind of a wind
  // blowing to the right of the view).
  auto lean = [&](const std::vector<float>& image) {
    auto changed = [&](int x, int y) {
      return x >= 0 && x < w && y < h && image[3 * (static_cast<size_t>(y) * w + x)] != kGrey;
    };
    long right = 0, left = 0;
    for (int y = 0; y + 1 < h; ++y) {
      for (int x = 0; x < w; ++x) {
        if (changed(x, y)) {
          right += changed(x + 1, y + 1) && !changed(x, y + 1) ? 1 : 0;
          left += changed(x - 1, y + 1) && !changed(x, y + 1) ? 1 : 0;
        }
      }
    }
    return right - left;
  };
  CHECK(lean(drawn(snow, 3.0)) > 0);  // flakes fall at 1 m/s: a light wind slants them
  CHECK(lean(drawn(snow, -3.0)) < 0);
  env.precipitation = corsa::engine::PrecipitationType::kRain;
  env.precipitation_intensity = 10.0;
  const Lighting rain = compute_lighting(env, {});
  CHECK(lean(drawn(rain, 8.0)) > 0);
  CHECK(lean(drawn(rain, -8.0)) < 0);
  CHECK(std::abs(lean(drawn(rain, 0.0))) < lean(drawn(rain, 8.0)));
}
