// Generated entity shapes, materials, procedural textures and lamps.

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <set>

#include "corsa/sensors/camera_render.h"
#include "corsa/sensors/labels.h"
#include "corsa/sensors/lidar.h"
#include "fixtures.h"
#include "noise_tile.h"
#include "scene_data.h"
#include "surface.h"
#include "vehicle_generators.h"

using namespace corsa::sensors;
using corsa::engine::EntityCategory;
using corsa::test::box_entity;

namespace {

corsa::engine::EntitySnapshot car_at(double x, double y, double heading) {
  auto e = box_entity(1, "car", x, y, 4.6, 1.9, 1.5, EntityCategory::kCar);
  e.box.center_x = 1.4;
  e.pose.h = heading;
  return e;
}

size_t count_material(const detail::ArticulatedMesh& m, auto pred) {
  size_t n = 0;
  for (const uint16_t i : m.material) {
    n += pred(m.materials[i]) ? 1 : 0;
  }
  return n;
}

/// The extent along x of the vertices of the triangles whose material `pred` accepts.
std::array<double, 2> x_extent(const detail::ArticulatedMesh& m, auto pred) {
  std::array<double, 2> out = {1e300, -1e300};
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    if (pred(m.materials[m.material[t]])) {
      for (const uint32_t v : m.triangles[t]) {
        out[0] = std::min(out[0], m.vertices[v].x);
        out[1] = std::max(out[1], m.vertices[v].x);
      }
    }
  }
  return out;
}

}  // namespace

TEST_CASE("a box filtered pulse train averages to its duty over whole periods",
          "[sensors][textures]") {
  using detail::filtered_pulse;
  CHECK(filtered_pulse(0.3, 1.0, 0.25, 0.0) == 0.0);  // point sample in the gap
  CHECK(filtered_pulse(0.1, 1.0, 0.25, 0.0) == 1.0);  // in the pulse
  CHECK(filtered_pulse(0.37, 1.0, 0.25, 3.0) == Approx(0.25));
  CHECK(filtered_pulse(123.4, 0.5, 0.1, 10.0) == Approx(0.1));
  // Half a pulse covered: [0.15, 0.35] overlaps [0, 0.25) by 0.1 of 0.2.
  CHECK(filtered_pulse(0.25, 1.0, 0.25, 0.2) == Approx(0.5));
}

TEST_CASE("procedural textures fade to their average where pixels are larger than their detail",
          "[sensors][textures]") {
  const detail::NoiseTile& tile = detail::NoiseTile::instance();
  // A footprint of the whole tile reads the mean.
  for (float v : tile.sample(17.3, -4.2, 1e6)) {
    CHECK(v == Approx(0.5).margin(0.02));
  }
  Material asphalt;
  asphalt.pattern = Pattern::kAsphalt;
  asphalt.base_color = {0.1, 0.1, 0.1};
  asphalt.params[0] = 0.6;
  auto spread = [&](double footprint) {
    double sum = 0.0, sum2 = 0.0;
    const int n = 400;
    for (int i = 0; i < n; ++i) {
      detail::TexturePoint p;
      p.position = {0.37 * i, 0.11 * i, 0.0};
      p.normal = {0.0, 0.0, 1.0};
      p.footprint = footprint;
      const double v = detail::sample_surface(asphalt, p).albedo.g;
      sum += v;
      sum2 += v * v;
    }
    return std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n)));
  };
  // Sharp up close, smooth far away: the variation between pixels falls by a factor of 3+.
  CHECK(spread(0.002) > 3.0 * spread(20.0));
}

TEST_CASE("grass and bare soil seen from above show no period of their noise tiles",
          "[sensors][textures]") {
  // A bird's-eye pixel: 80 m over 720 px. Each noise tile repeats; read at this footprint the
  // lawn's 0.7 m blade tile and the soil's 1.2 m tile made a lattice over every lawn. Points a
  // tile's period apart along its axes must differ about as much as points as far apart in
  // another direction (with main's patterns: 0.16 and 0.76 times as much).
  const double footprint = 80.0 / 720.0;
  auto mean_difference = [&](const Material& m, Vec3 offset) {
    double sum = 0.0;
    const int n = 2000;
    for (int i = 0; i < n; ++i) {
      detail::TexturePoint a;
      a.position = {0.731 * i, 0.293 * i - 0.017 * (i % 53) * i, 0.0};
      a.normal = {0.0, 0.0, 1.0};
      a.footprint = footprint;
      detail::TexturePoint b = a;
      b.position = a.position + offset;
      sum +=
          std::fabs(detail::sample_surface(m, a).albedo.g - detail::sample_surface(m, b).albedo.g);
    }
    return sum / n;
  };
  Material grass;
  grass.pattern = Pattern::kGrass;
  grass.base_color = {0.1, 0.16, 0.05};
  grass.secondary = {0.16, 0.14, 0.05};
  // The blade tile's axes are turned by 36.87 degrees (a 3-4-5 rotation) against the plane's.
  const double blade_period = mean_difference(grass, {0.56, -0.42, 0.0});
  // As far along the tile's diagonal: no period of it.
  const double diagonal = mean_difference(grass, {0.693, 0.099, 0.0});
  CHECK(blade_period > 0.9 * diagonal);
  Material dirt;
  dirt.pattern = Pattern::kDirt;
  dirt.base_color = {0.12, 0.08, 0.05};
  dirt.secondary = {0.08, 0.06, 0.04};
  CHECK(mean_difference(dirt, {1.2, 0.0, 0.0}) > 0.9 * mean_difference(dirt, {0.72, 0.96, 0.0}));
}

TEST_CASE("asphalt darkens the wheel paths of its lanes, filtered at a distance",
          "[sensors][textures]") {
  Material asphalt;
  asphalt.pattern = Pattern::kAsphalt;
  asphalt.base_color = {0.1, 0.1, 0.1};
  asphalt.params[0] = 0.0;  // no repairs: the bands alone
  const double width = 3.5;
  // Mean albedo along 2 km of a lane (the road mesh's lane coordinates: u metres along, v lanes
  // across, uv_per_m^2 = 1 / lane width) at `across` metres from the lane's centre.
  auto mean_at = [&](double across, double footprint) {
    double sum = 0.0;
    const int n = 2000;
    for (int i = 0; i < n; ++i) {
      detail::TexturePoint p;
      p.position = {1.0 * i, across, 0.0};
      p.normal = {0.0, 0.0, 1.0};
      p.footprint = footprint;
      p.u = 1.0 * i;
      p.v = 1.5 + across / width;  // lane -2: across 1 .. 2
      p.uv_per_m = 1.0 / std::sqrt(width);
      sum += detail::sample_surface(asphalt, p).albedo.g;
    }
    return sum / n;
  };
  const double wheel = mean_at(0.85, 0.002);
  const double between = mean_at(0.4, 0.002);
  const double verge = mean_at(1.6, 0.002);
  CHECK(wheel < 0.93 * between);
  CHECK(wheel < 0.93 * verge);
  // Seen from far (a 2 m footprint) the band blurs: less contrast, same darkening on average.
  const double far_wheel = mean_at(0.85, 2.0);
  const double far_between = mean_at(0.4, 2.0);
  CHECK(far_wheel / far_between > wheel / between);
  CHECK(far_wheel < far_between);
  // Without lane coordinates (uv 0) there are no bands.
  detail::TexturePoint a;
  a.position = {3.0, 0.85, 0.0};
  a.normal = {0.0, 0.0, 1.0};
  a.footprint = 0.002;
  detail::TexturePoint b = a;
  b.u = 3.0;
  b.v = 1.5 + 0.85 / width;
  b.uv_per_m = 1.0 / std::sqrt(width);
  CHECK(detail::sample_surface(asphalt, b).albedo.g < detail::sample_surface(asphalt, a).albedo.g);
}

TEST_CASE("sign faces are drawn from their shape, border and symbol", "[sensors][textures]") {
  SignFace stop;
  stop.shape = SignShape::kOctagon;
  stop.fill = {0.6, 0.0, 0.0};
  stop.border = {0.9, 0.9, 0.9};
  stop.border_width = 0.1;
  stop.symbol = SignSymbol::kBar;
  stop.symbol_color = {0.9, 0.9, 0.9};
  const Color centre = detail::sign_face_color(stop, 0.5, 0.5, 1e-3);  // on the bar
  const Color fill = detail::sign_face_color(stop, 0.5, 0.75, 1e-3);   // red field
  const Color edge = detail::sign_face_color(stop, 0.5, 0.985, 1e-3);  // border band
  CHECK(centre.r == Approx(0.9));
  CHECK(fill.r == Approx(0.6));
  CHECK(fill.g == Approx(0.0));
  CHECK(edge.g == Approx(0.9));
}

TEST_CASE("car paints follow the real-world colour shares", "[sensors][assets]") {
  corsa::RandomStream rng(11);
  std::map<std::string, int> counts;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const std::string name = detail::draw_car_paint(rng).name;
    counts[name.find("white") != std::string::npos   ? "white"
           : name.find("black") != std::string::npos ? "black"
           : name.find("grey") != std::string::npos  ? "grey"
                                                     : "other"]++;
  }
  CHECK(counts["white"] / static_cast<double>(n) == Approx(0.34).margin(0.015));
  CHECK(counts["black"] / static_cast<double>(n) == Approx(0.21).margin(0.015));
  CHECK(counts["grey"] / static_cast<double>(n) == Approx(0.19).margin(0.015));
}

TEST_CASE("a generated car has a body, glazing, lamps for every role, plates and turning wheels",
          "[sensors][assets]") {
  detail::EntityShape shape;
  const auto car = car_at(0.0, 0.0, 0.0);
  detail::build_entity_shape(car, 1, shape);
  const auto& m = shape.mesh;
  CHECK(m.triangles.size() > 2000);
  CHECK(count_material(m, [](const Material& x) { return x.transmission > 0.5; }) > 50);
  for (LightRole role : {LightRole::kHeadlight, LightRole::kTail, LightRole::kBrake,
                         LightRole::kIndicatorLeft, LightRole::kIndicatorRight}) {
    CHECK(count_material(m, [role](const Material& x) { return x.light == role; }) > 0);
  }
  CHECK(count_material(m, [](const Material& x) { return x.pattern == Pattern::kPlate; }) >= 4);
  // Everything within the box (x from -0.9 to 3.7 m, |y| <= 0.95, z from 0 to 1.5).
  for (const Vec3& v : m.vertices) {
    REQUIRE(v.x >= -0.9 - 1e-6);
    REQUIRE(v.x <= 3.7 + 1e-6);
    REQUIRE(std::fabs(v.y) <= 0.95 + 1e-6);
    REQUIRE(v.z >= -1e-6);
    REQUIRE(v.z <= 1.5 + 1e-6);
  }
  // Wheels: four bones; rolling turns them about their axles, steering only the front ones.
  REQUIRE(shape.pose);
  auto moving = car;
  moving.speed = 10.0;
  moving.odometer = 0.5;
  moving.yaw_rate = 0.2;
  std::vector<Rigid> bones;
  shape.pose(moving, bones);
  REQUIRE(bones.size() == 5);
  int steered = 0;
  for (size_t b = 1; b < 5; ++b) {
    const Mat3& r = bones[b].rotation;
    CHECK(std::fabs(r.m[2][0]) > 1e-3);              // forward axis tilted: turned about the axle
    steered += std::fabs(r.m[0][1]) > 1e-3 ? 1 : 0;  // axle turned about the vertical
  }
  CHECK(steered == 2);
}

TEST_CASE("a generated car's plates and tail lamps are not flush with its end faces, in its box",
          "[sensors][assets]") {
  // Flush with the body's end faces they z-fought with the paint (a speckled stripe across the
  // tail) or hid inside the body (no plate seen from behind).
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    CAPTURE(seed);
    detail::EntityShape shape;
    detail::build_entity_shape(car_at(0.0, 0.0, 0.0), seed, shape);
    const auto& m = shape.mesh;
    const auto paint = x_extent(m, [](const Material& x) { return x.clearcoat > 0.5; });
    const auto plates = x_extent(m, [](const Material& x) { return x.pattern == Pattern::kPlate; });
    const auto tail = x_extent(m, [](const Material& x) { return x.light == LightRole::kTail; });
    CHECK(plates[0] < paint[0] - 0.005);  // the rear plate behind the rear face
    CHECK(plates[1] > paint[1] + 0.005);  // the front plate ahead of the front face
    // Tail lamps 4 mm proud of the surface under them: behind the rear face, or on a tail
    // that slopes in above it, but never flush with the face.
    CHECK(std::fabs(tail[0] - paint[0]) > 0.003);
    CHECK(plates[0] >= -0.9 - 1e-9);  // the box: x from -0.9 to 3.7 m
    CHECK(plates[1] <= 3.7 + 1e-9);
  }
}

TEST_CASE("looks come from the seed and the name: same seed same look, names differ",
          "[sensors][assets]") {
  auto paint_of = [](uint64_t seed, const std::string& name) {
    detail::EntityShape shape;
    auto e = car_at(0.0, 0.0, 0.0);
    e.name = name;
    detail::build_entity_shape(e, seed, shape);
    for (const Material& m : shape.mesh.materials) {
      if (m.clearcoat > 0.5) {
        return m.name;
      }
    }
    return std::string();
  };
  CHECK(paint_of(5, "a") == paint_of(5, "a"));
  std::set<std::string> paints;
  for (int i = 0; i < 12; ++i) {
    paints.insert(paint_of(5, "car" + std::to_string(i)));
  }
  CHECK(paints.size() >= 3);
}

TEST_CASE("a walking person swings its legs with the distance walked and stands still at rest",
          "[sensors][assets]") {
  auto walker = box_entity(1, "walker", 0.0, 0.0, 0.6, 0.6, 1.75, EntityCategory::kPedestrian);
  detail::EntityShape shape;
  detail::build_entity_shape(walker, 3, shape);
  REQUIRE(shape.pose);
  std::vector<Rigid> a, b, still;
  walker.speed = 1.4;
  walker.odometer = 0.0;
  shape.pose(walker, a);
  walker.odometer = 0.36;  // about a quarter of a gait cycle
  shape.pose(walker, b);
  walker.speed = 0.0;
  shape.pose(walker, still);
  const auto thigh = static_cast<size_t>(detail::kBoneThighL);
  CHECK(std::fabs(a[thigh].rotation.m[0][2] - b[thigh].rotation.m[0][2]) > 0.1);
  // Standing: both thighs nearly vertical.
  CHECK(std::fabs(still[detail::kBoneThighL].rotation.m[0][2]) < 0.05);
  CHECK(std::fabs(still[detail::kBoneThighR].rotation.m[0][2]) < 0.05);
}

TEST_CASE("a walking person's label box holds the whole stride", "[sensors][assets][labels]") {
  Scene scene;
  scene.add_road_mesh(corsa::test::flat_road());
  scene.commit();
  // The demo's generated walkers have a 0.5 m long box, shorter than a brisk stride. This one
  // walks across the LiDAR's view, its stride seen side-on.
  auto walker = box_entity(7, "walker", 10.0, 0.0, 0.5, 0.6, 1.8, EntityCategory::kPedestrian);
  walker.pose.h = 0.5 * M_PI;
  walker.speed = 1.7;
  LidarOptions o;
  o.channels = 64;
  o.lower_fov_deg = -20.0;
  o.upper_fov_deg = 10.0;
  o.points_per_second = 64.0 * 3600.0 * 10.0;  // 0.1 degree steps
  o.range_m = 50.0;
  const Rigid sensor = rigid_from_pose(0.0, 0.0, 1.0, 0.0, 0.0, 0.0);
  double longest = 0.0;
  size_t points = 0, outside = 0;
  for (int k = 0; k < 8; ++k) {
    walker.odometer = 0.19 * k;  // through a gait cycle (0.83 statures)
    scene.set_entities(std::vector{walker});
    LidarScanInput input;
    input.world_from_sensor = sensor;
    const PointCloud cloud = LidarSimulator(o).scan(scene, input);
    const auto labels = lidar_labels(scene, sensor, cloud, 50.0);
    REQUIRE(labels.size() == 1);
    const Box3& b = labels[0].box_sensor;
    longest = std::max(longest, b.length);
    for (const LidarPoint& p : cloud.points) {
      if (p.instance_id != 7) {
        continue;
      }
      ++points;
      const Vec3 q = b.rotation.transposed() * (Vec3{p.x, p.y, p.z} - b.center);
      const bool in = std::fabs(q.x) <= 0.5 * b.length + 0.01 &&
                      std::fabs(q.y) <= 0.5 * b.width + 0.01 &&
                      std::fabs(q.z) <= 0.5 * b.height + 0.01;
      outside += in ? 0 : 1;
    }
  }
  CHECK(points > 200);
  CHECK(outside == 0);
  CHECK(longest > 0.6);  // the entity's own 0.5 m would not hold the stride
}

TEST_CASE("riders are labelled rider on their bicycle, people person, every pixel an instance",
          "[sensors][assets][labels]") {
  Scene scene;
  scene.add_road_mesh(corsa::test::flat_road());
  scene.commit();
  auto bike = box_entity(1, "bike", 8.0, 1.0, 1.8, 0.6, 1.8, EntityCategory::kBicycle);
  auto walker = box_entity(2, "walker", 8.0, -1.0, 0.6, 0.6, 1.75, EntityCategory::kPedestrian);
  bike.pose.h = 1.57;
  scene.set_entities(std::vector<corsa::engine::EntitySnapshot>{bike, walker});
  CameraIntrinsics k;
  k.width = 320;
  k.height = 240;
  k.fov_deg = 60.0;
  const CameraRenderer camera(k);
  RenderSettings settings;
  settings.outputs.semantic = true;
  CameraMotion motion;
  motion.world_from_body = rigid_from_pose(0.0, 0.0, 1.2, 0.0, 0.0, 0.0);
  const CameraImages img = camera.render(scene, motion, settings);
  std::map<std::pair<uint32_t, int>, int> seen;
  for (size_t i = 0; i < img.semantic.size(); ++i) {
    if (img.instance[i] != 0) {
      seen[{img.instance[i], img.semantic[i]}]++;
    }
  }
  CHECK(seen[{1, static_cast<int>(SemanticClass::kRider)}] > 100);
  CHECK(seen[{1, static_cast<int>(SemanticClass::kBicycle)}] > 20);
  CHECK(seen[{2, static_cast<int>(SemanticClass::kPerson)}] > 100);
  CHECK(seen.count({2, static_cast<int>(SemanticClass::kRider)}) == 0);
  // Nothing hit: sky.
  CHECK(img.semantic[0] == static_cast<uint8_t>(SemanticClass::kSky));
}

TEST_CASE("brake lamps light up when the snapshot says the vehicle brakes", "[sensors][assets]") {
  auto render_rear = [](bool braking) {
    Scene scene;
    scene.add_road_mesh(corsa::test::flat_road());
    scene.commit();
    auto car = car_at(10.0, 0.0, 0.0);  // seen from behind by a camera at the origin
    car.lights_on = braking ? corsa::engine::light_bit(corsa::engine::VehicleLight::kBrake) : 0u;
    scene.set_entities(std::vector<corsa::engine::EntitySnapshot>{car});
    CameraIntrinsics k;
    k.width = 320;
    k.height = 240;
    k.fov_deg = 40.0;
    const CameraRenderer camera(k);
    corsa::engine::EnvironmentState env;
    env.sun_azimuth = 2.0;
    env.sun_elevation = 0.8;
    const Lighting day = compute_lighting(env, {});
    RenderSettings settings;
    settings.outputs.rgb = true;
    settings.lighting = &day;
    settings.rgb.noise = false;
    CameraMotion motion;
    motion.world_from_body = rigid_from_pose(0.0, 0.0, 1.0, 0.0, 0.0, 0.0);
    const CameraImages img = camera.render(scene, motion, settings);
    size_t bright_red = 0;
    for (size_t i = 0; i < img.rgb.size(); i += 3) {
      bright_red += img.rgb[i] > 240 && img.rgb[i + 1] < 120 ? 1 : 0;
    }
    return bright_red;
  };
  const size_t off = render_rear(false);
  const size_t on = render_rear(true);
  CHECK(on > off + 20);
}
