#include "corsa/sensors/lidar.h"

#include <tbb/global_control.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <set>

#include "corsa/sensors/environment.h"
#include "fixtures.h"

using namespace corsa::sensors;

namespace {

LidarOptions downward_lidar() {
  LidarOptions o;
  o.channels = 16;
  o.lower_fov_deg = -30.0;
  o.upper_fov_deg = -5.0;
  o.points_per_second = 100000.0;
  o.rotation_frequency_hz = 10.0;
  o.range_m = 100.0;
  return o;
}

Scene plane_scene() {
  Scene scene;
  scene.add_road_mesh(corsa::test::flat_road());
  scene.commit();
  return scene;
}

const double kHeight = 2.0;
const Rigid kMount = rigid_from_pose(0.0, 0.0, kHeight, 0.3, 0.0, 0.0);

}  // namespace

TEST_CASE("a LiDAR over a flat plane measures h / sin(elevation) within the noise",
          "[sensors][lidar]") {
  Scene scene = plane_scene();
  LidarOptions o = downward_lidar();
  o.noise_stddev_m = 0.02;
  const LidarSimulator lidar(o);
  const PointCloud cloud = lidar.scan(scene, kMount, 0.0, 42);
  REQUIRE(cloud.points.size() == cloud.rays);
  double sum = 0.0, sum2 = 0.0;
  for (const auto& p : cloud.points) {
    const double range = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    const double expected = kHeight / std::sin(-lidar.elevation(p.ring));
    const double error = range - expected;
    REQUIRE(std::fabs(error) < 5.0 * 0.02 + 1e-3);
    sum += error;
    sum2 += error * error;
    CHECK(p.semantic == SemanticClass::kRoad);
  }
  const double n = static_cast<double>(cloud.points.size());
  CHECK(std::fabs(sum / n) < 0.002);                         // unbiased
  CHECK(std::sqrt(sum2 / n) == Approx(0.02).epsilon(0.05));  // the configured noise
}

TEST_CASE("a noiseless LiDAR point lies on the plane under the sensor", "[sensors][lidar]") {
  Scene scene = plane_scene();
  const LidarSimulator lidar(downward_lidar());
  const PointCloud cloud = lidar.scan(scene, kMount, 0.0, 1);
  REQUIRE_FALSE(cloud.points.empty());
  for (const auto& p : cloud.points) {
    REQUIRE(p.z == Approx(-kHeight).margin(1e-4));
    const double range = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    REQUIRE(range == Approx(kHeight / std::sin(-lidar.elevation(p.ring))).epsilon(1e-5));
    REQUIRE(p.intensity > 0.0f);
  }
}

TEST_CASE("channel and azimuth counts follow the LiDAR options", "[sensors][lidar]") {
  Scene scene = plane_scene();
  LidarOptions o = downward_lidar();
  o.channels = 24;
  o.points_per_second = 360000.0;
  o.rotation_frequency_hz = 5.0;
  o.horizontal_fov_deg = 120.0;
  const LidarSimulator lidar(o);
  REQUIRE(lidar.azimuth_steps() == 3000);  // 360000 / (24 * 5)
  const PointCloud cloud = lidar.scan(scene, kMount, 0.0, 1);
  CHECK(cloud.rays == 24u * 3000u);
  CHECK(cloud.points.size() == cloud.rays);
  std::set<int> rings, steps;
  double min_az = 1e9, max_az = -1e9;
  for (const auto& p : cloud.points) {
    rings.insert(p.ring);
    steps.insert(p.azimuth_index);
    const double az = std::atan2(p.y, p.x) * 180.0 / M_PI;
    min_az = std::min(min_az, az);
    max_az = std::max(max_az, az);
  }
  CHECK(rings.size() == 24);
  CHECK(steps.size() == 3000);
  CHECK(min_az == Approx(-60.0).margin(0.05));
  CHECK(max_az == Approx(60.0).margin(0.05));
  CHECK(lidar.elevation(0) == Approx(-30.0 * M_PI / 180.0));
  CHECK(lidar.elevation(23) == Approx(-5.0 * M_PI / 180.0));
}

TEST_CASE("beyond the range a LiDAR returns nothing", "[sensors][lidar]") {
  Scene scene = plane_scene();
  LidarOptions o = downward_lidar();
  o.range_m = 10.0;  // beams below asin(2 / 10) = 11.5 degrees reach the ground
  const LidarSimulator lidar(o);
  const PointCloud cloud = lidar.scan(scene, kMount, 0.0, 1);
  size_t expected = 0;
  for (int ch = 0; ch < o.channels; ++ch) {
    if (kHeight / std::sin(-lidar.elevation(ch)) <= 10.0) {
      expected += static_cast<size_t>(lidar.azimuth_steps());
    }
  }
  CHECK(cloud.points.size() == expected);
  CHECK(expected > 0);
  CHECK(expected < cloud.rays);
}

TEST_CASE("fog thins LiDAR returns by the two-way transmission", "[sensors][lidar][weather]") {
  Scene scene = plane_scene();
  const LidarSimulator lidar(downward_lidar());
  const PointCloud clear = lidar.scan(scene, kMount, 0.0, 7);
  // 400 m visual range: thick enough to thin the returns, too thin for the fog's own echo to
  // reach the detection threshold (fog of 300 m and less answers first:
  // lidar_weather_test.cpp).
  const double sigma = fog_extinction(400.0);
  CHECK(sigma == Approx(3.912 / 400.0).epsilon(1e-3));
  double expected = 0.0, variance = 0.0;
  for (const auto& p : clear.points) {
    const double r = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    const double t = std::exp(-2.0 * sigma * r);
    expected += t;
    variance += t * (1.0 - t);
  }
  const PointCloud foggy = lidar.scan(scene, kMount, sigma, 7);
  const double kept = static_cast<double>(foggy.points.size());
  CHECK(std::fabs(kept - expected) < 4.0 * std::sqrt(variance));
  CHECK(kept < 0.9 * static_cast<double>(clear.points.size()));
  // Far returns suffer most: the mean range shrinks.
  auto mean_range = [](const PointCloud& c) {
    double s = 0.0;
    for (const auto& p : c.points) {
      s += std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    }
    return s / static_cast<double>(c.points.size());
  };
  CHECK(mean_range(foggy) < mean_range(clear));
}

TEST_CASE("a LiDAR scan is the same bytes for the same seed on 1 and 2 threads",
          "[sensors][lidar][determinism]") {
  Scene scene = plane_scene();
  scene.set_entities(std::vector{corsa::test::box_entity(1, "box", 8.0, 1.0, 4.0, 2.0, 1.5)});
  LidarOptions o = downward_lidar();
  o.noise_stddev_m = 0.03;
  o.dropoff_general_rate = 0.1;
  const LidarSimulator lidar(o);
  auto run = [&](int threads, uint64_t seed) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return lidar.scan(scene, kMount, fog_extinction(200.0), seed).points;
  };
  const auto one = run(1, 99);
  const auto two = run(2, 99);
  REQUIRE(one.size() == two.size());
  CHECK(std::memcmp(one.data(), two.data(), one.size() * sizeof(LidarPoint)) == 0);
  const auto other = run(2, 100);
  CHECK((other.size() != one.size() ||
         std::memcmp(one.data(), other.data(), one.size() * sizeof(LidarPoint)) != 0));
}

TEST_CASE("LiDAR points on an entity carry its class and instance id", "[sensors][lidar]") {
  Scene scene = plane_scene();
  scene.set_entities(std::vector{corsa::test::box_entity(5, "car", 10.0, 0.0, 4.0, 2.0, 1.5,
                                                         corsa::engine::EntityCategory::kCar)});
  LidarOptions o = downward_lidar();
  o.upper_fov_deg = 0.0;
  const LidarSimulator lidar(o);
  const PointCloud cloud = lidar.scan(scene, rigid_from_pose(0, 0, kHeight, 0, 0, 0), 0.0, 1);
  size_t on_car = 0;
  for (const auto& p : cloud.points) {
    if (p.instance_id == 5) {
      ++on_car;
      CHECK(p.semantic == SemanticClass::kCar);
      CHECK(p.x >= 7.99f);  // the rear face is at x = 10 - 2 = 8 m
      CHECK(p.x <= 12.01f);
    }
  }
  CHECK(on_car > 10);
}

TEST_CASE("LiDAR range noise is Gaussian: 68% of errors within one deviation, 95% within two",
          "[sensors][lidar]") {
  Scene scene = plane_scene();
  LidarOptions o = downward_lidar();
  o.noise_stddev_m = 0.05;
  const LidarSimulator lidar(o);
  const PointCloud cloud = lidar.scan(scene, kMount, 0.0, 5);
  REQUIRE(cloud.points.size() == cloud.rays);
  double within1 = 0.0, within2 = 0.0;
  for (const auto& p : cloud.points) {
    const double range = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    const double error = range - kHeight / std::sin(-lidar.elevation(p.ring));
    within1 += std::fabs(error) < 0.05 ? 1.0 : 0.0;
    within2 += std::fabs(error) < 0.10 ? 1.0 : 0.0;
  }
  const double n = static_cast<double>(cloud.points.size());
  auto sigma = [n](double p) { return std::sqrt(p * (1.0 - p) / n); };
  CHECK(std::fabs(within1 / n - 0.682689) < 5.0 * sigma(0.682689));
  CHECK(std::fabs(within2 / n - 0.954500) < 5.0 * sigma(0.954500));
}

TEST_CASE("general dropoff removes its share of the returns", "[sensors][lidar]") {
  Scene scene = plane_scene();
  LidarOptions o = downward_lidar();
  o.dropoff_general_rate = 0.25;
  const LidarSimulator lidar(o);
  const PointCloud cloud = lidar.scan(scene, kMount, 0.0, 11);
  const double rays = static_cast<double>(cloud.rays);  // every beam reaches the plane
  const double kept = static_cast<double>(cloud.points.size());
  CHECK(std::fabs(kept - 0.75 * rays) < 5.0 * std::sqrt(0.25 * 0.75 * rays));
  // Dropped beams leave gaps but the survivors stay in firing order.
  for (size_t i = 1; i < cloud.points.size(); ++i) {
    const auto& a = cloud.points[i - 1];
    const auto& b = cloud.points[i];
    REQUIRE((a.azimuth_index < b.azimuth_index ||
             (a.azimuth_index == b.azimuth_index && a.ring < b.ring)));
  }
}
