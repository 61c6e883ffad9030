// Parked vehicles: where they stand (parking lanes, parking spaces, kerb strips; never a driving
// lane, never in a prop), how they are labelled, and that the seed alone decides them.

#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "corsa/sensors/camera_render.h"
#include "corsa/sensors/kitti.h"
#include "corsa/sensors/labels.h"
#include "corsa/sensors/lidar.h"
#include "corsa/xodr/parser.h"
#include "scene_data.h"
#include "world_fixture.h"

using namespace corsa::sensors;

namespace {

const std::filesystem::path kParkingStreet =
    std::filesystem::path(CORSA_SOURCE_DIR) / "scenarios" / "look" / "parking_street.xodr";

/// A straight 200 m street along +x without parking markup: on the right one driving lane, a
/// 2.5 m shoulder and a 4 m sidewalk (kerb at y = -6); on the left one driving lane, a 0.5 m
/// border and a 4 m sidewalk.
corsa::xodr::Map kerb_street() {
  const std::string text =
      R"(<?xml version="1.0"?><OpenDRIVE><header revMajor="1" revMinor="8"/>
<road id="1" length="200" junction="-1"><type s="0" type="town"/><planView>
<geometry s="0" x="0" y="0" hdg="0" length="200"><line/></geometry></planView>
<lanes><laneSection s="0"><left>
<lane id="3" type="sidewalk"><width sOffset="0" a="4" b="0" c="0" d="0"/></lane>
<lane id="2" type="border"><width sOffset="0" a="0.5" b="0" c="0" d="0"/></lane>
<lane id="1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></left>
<center><lane id="0" type="none"/></center><right>
<lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
<lane id="-2" type="shoulder"><width sOffset="0" a="2.5" b="0" c="0" d="0"/></lane>
<lane id="-3" type="sidewalk"><width sOffset="0" a="4" b="0" c="0" d="0"/></lane>
</right></laneSection></lanes></road></OpenDRIVE>)";
  corsa::Diagnostics diagnostics;
  return corsa::xodr::Map::build(corsa::xodr::parse_xodr_text(text, "kerb.xodr", diagnostics),
                                 diagnostics);
}

struct ParkedCar {
  uint32_t id = 0;
  ObjectInfo info;
  Box3 box;
};

std::vector<ParkedCar> parked_cars(const Scene& scene) {
  std::vector<ParkedCar> out;
  for (const auto& [id, record] : scene.data().objects) {
    if (record.info.kind == "parked_vehicle") {
      REQUIRE(record.info.box.has_value());
      out.push_back({id, record.info, *record.info.box});
    }
  }
  return out;
}

/// Points over a car's footprint (its box's ground rectangle, `inset` metres inside its
/// edges), every 0.3 m.
std::vector<Vec3> car_footprint(const Box3& b, double inset) {
  std::vector<Vec3> out;
  const double hl = 0.5 * b.length - inset, hw = 0.5 * b.width - inset;
  for (double u = -hl; u <= hl + 1e-9; u += 2.0 * hl / std::ceil(2.0 * hl / 0.3)) {
    for (double v = -hw; v <= hw + 1e-9; v += 2.0 * hw / std::ceil(2.0 * hw / 0.3)) {
      out.push_back(b.center + b.rotation * Vec3{u, v, 0.0});
    }
  }
  return out;
}

/// The type of the lane under (x, y), or none off the road.
std::optional<corsa::xodr::LaneType> lane_type_at(const corsa::xodr::Map& map, double x, double y) {
  corsa::xodr::LocateOptions o;
  o.max_distance = 0.0;
  const auto at = map.locate(x, y, o);
  if (!at || at->distance > 0.0) {
    return std::nullopt;
  }
  for (const auto& lane : map.road(at->road).lane_sections[at->section].lanes) {
    if (lane.id == at->lane) {
      return lane.type;
    }
  }
  return std::nullopt;
}

}  // namespace

TEST_CASE("parked cars fill the map's parking lane and parking spaces, never a driving lane",
          "[sensors][world][parked]") {
  const auto map = corsa::test::load_map(kParkingStreet);
  auto built = corsa::test::build_world_scene(map, 5);
  const auto cars = parked_cars(built->scene);
  REQUIRE(built->report.parked_vehicles == cars.size());
  int in_lane = 0, in_spaces = 0;
  for (const ParkedCar& car : cars) {
    INFO(car.info.type << " at " << car.box.center.x << ", " << car.box.center.y);
    for (const Vec3& p : car_footprint(car.box, 0.05)) {
      const auto type = lane_type_at(map, p.x, p.y);
      CHECK((!type || !corsa::xodr::is_drivable(*type)));
      if (type) {
        CHECK(*type == corsa::xodr::LaneType::kParking);
      }
    }
    // The parking lane is y -7 .. -9.5 (cars along it, with the right side's traffic); the
    // stalls and the lot lie behind the left sidewalk (y > 10), cars across the road.
    if (car.box.center.y < 0.0) {
      ++in_lane;
      CHECK(std::fabs(car.box.yaw()) < 0.03);
      CHECK(car.box.center.y - 0.5 * car.box.width > -9.5 + 0.14);
      CHECK(car.box.center.y + 0.5 * car.box.width < -7.0);
    } else {
      ++in_spaces;
      CHECK(car.box.center.y > 10.0);
      CHECK(std::fabs(std::fabs(car.box.yaw()) - 0.5 * 3.14159265358979) < 0.05);
    }
    // On the ground: the street is flat at z = 0, the box's bottom on it.
    CHECK(std::fabs(car.box.center.z - 0.5 * car.box.height) < 0.01);
  }
  // 200 m of parking lane less the bus stop, the crosswalk and the ego's spot; ten stalls and a
  // 30 x 20 m lot (two rows of twelve stalls).
  CHECK(in_lane >= 6);
  CHECK(in_spaces >= 10);
}

TEST_CASE("parked cars stand clear of trees, poles, furniture and each other",
          "[sensors][world][parked]") {
  const auto map = corsa::test::load_map(kParkingStreet);
  WorldOptions options;
  options.seed = 8;
  options.parked_density = 1.0;
  auto built = corsa::test::build_world_scene(map, options);
  const auto cars = parked_cars(built->scene);
  REQUIRE(cars.size() >= 20);
  for (const ParkedCar& car : cars) {
    INFO(car.info.type << " at " << car.box.center.x << ", " << car.box.center.y);
    // Straight down through the car's volume, from above its roof: the first thing hit is the
    // car itself or paving; never another object inside the car's box.
    for (const Vec3& p : car_footprint(car.box, 0.02)) {
      const double top = car.box.center.z + 0.5 * car.box.height + 0.05;
      auto hit = built->scene.intersect({p.x, p.y, top}, {0.0, 0.0, -1.0}, top + 1.0);
      REQUIRE(hit);
      const bool paving =
          hit->semantic == SemanticClass::kParking || hit->semantic == SemanticClass::kRoad ||
          hit->semantic == SemanticClass::kLaneMarking ||
          hit->semantic == SemanticClass::kTerrain || hit->semantic == SemanticClass::kSidewalk;
      CHECK((hit->instance_id == car.id || paving));
    }
  }
  // No fire hydrant within 5 m of a car's end, no car beside a bus stop or on a crosswalk.
  for (const auto& [id, record] : built->scene.data().objects) {
    const std::string& kind = record.info.kind;
    if (kind != "fire_hydrant" && kind != "bus_shelter" && kind != "crosswalk") {
      continue;
    }
    const double margin = kind == "bus_shelter" ? 12.0 : 5.0;
    for (const ParkedCar& car : cars) {
      const double dx = std::max(
          {record.bounds.min.x - car.box.center.x, 0.0, car.box.center.x - record.bounds.max.x});
      const double dy = std::max(
          {record.bounds.min.y - car.box.center.y, 0.0, car.box.center.y - record.bounds.max.y});
      INFO(kind << " and a car at " << car.box.center.x << ", " << car.box.center.y);
      CHECK(std::hypot(dx, dy) >= margin + 0.5 * car.box.length - 1e-6);
    }
  }
}

TEST_CASE("kerb parking takes a shoulder wide enough for a car, never a border or a lane",
          "[sensors][world][parked]") {
  const auto map = kerb_street();
  WorldOptions options;
  options.seed = 3;
  auto by_map = corsa::test::build_world_scene(map, options);
  CHECK(by_map->report.parked_vehicles == 0);  // no parking markup: the default parks nothing
  options.parked = ParkedVehicles::kKerb;
  auto built = corsa::test::build_world_scene(map, options);
  const auto cars = parked_cars(built->scene);
  // 200 m less 8 m at each end, in slots of 5-8 m, 60% taken.
  CHECK(cars.size() >= 10);
  for (const ParkedCar& car : cars) {
    INFO(car.info.type << " at " << car.box.center.x << ", " << car.box.center.y);
    CHECK(car.info.subtype == "kerb");
    // On the right shoulder (y -3.5 .. -6), with the right side's traffic, by the kerb.
    CHECK(car.box.center.y - 0.5 * car.box.width > -6.0 + 0.14);
    CHECK(car.box.center.y - 0.5 * car.box.width < -6.0 + 0.36);
    CHECK(car.box.center.y + 0.5 * car.box.width < -3.5);
    CHECK(std::fabs(car.box.yaw()) < 0.03);
    CHECK(car.box.center.x - 0.5 * car.box.length > 0.0);
    CHECK(car.box.center.x + 0.5 * car.box.length < 200.0);
  }
  // The demo street's 0.5 m border holds no car: its kerb-side lanes are driving lanes.
  const auto demo = corsa::test::load_map(std::filesystem::path(CORSA_SOURCE_DIR) / "scenarios" /
                                          "demo" / "city_street.xodr");
  auto demo_built = corsa::test::build_world_scene(demo, options);
  CHECK(demo_built->report.parked_vehicles == 0);
}

TEST_CASE("parked cars keep clear of the scenario's entities and their kerb lanes",
          "[sensors][world][parked]") {
  const auto map = kerb_street();
  WorldOptions options;
  options.seed = 3;
  options.parked = ParkedVehicles::kKerb;
  options.parked_density = 1.0;
  options.keep_clear.push_back({100.0, -4.75, 6.0, "", 0});
  auto built = corsa::test::build_world_scene(map, options);
  const auto cars = parked_cars(built->scene);
  REQUIRE(!cars.empty());
  for (const ParkedCar& car : cars) {
    CHECK(std::fabs(car.box.center.x - 100.0) >= 6.0 + 0.5 * car.box.length - 1e-6);
  }
  // An entity that starts on the shoulder keeps the whole shoulder free.
  options.keep_clear.push_back({30.0, -4.75, 3.0, "1", -2});
  auto kept = corsa::test::build_world_scene(map, options);
  CHECK(kept->report.parked_vehicles == 0);
}

TEST_CASE("the seed alone decides the parked cars", "[sensors][world][parked]") {
  const auto map = corsa::test::load_map(kParkingStreet);
  auto summary = [&](uint64_t seed) {
    auto built = corsa::test::build_world_scene(map, seed);
    std::vector<std::string> out;
    for (const ParkedCar& car : parked_cars(built->scene)) {
      out.push_back(car.info.type + " " + std::to_string(car.box.center.x) + " " +
                    std::to_string(car.box.center.y) + " " + std::to_string(car.box.yaw()));
    }
    out.push_back(std::to_string(built->scene.static_triangle_count()));
    return out;
  };
  CHECK(summary(21) == summary(21));
  CHECK(summary(21) != summary(22));
}

TEST_CASE("parked cars are labelled cars, with their own instance, box and parked mark",
          "[sensors][world][parked][labels]") {
  const auto map = corsa::test::load_map(kParkingStreet);
  auto built = corsa::test::build_world_scene(map, 5);
  built->scene.set_entities({});
  const auto cars = parked_cars(built->scene);
  REQUIRE(!cars.empty());
  // A camera in the right-hand driving lane looking along the parking lane.
  const CameraRenderer camera(corsa::test::wide_camera());
  RenderSettings settings;
  settings.outputs.semantic = true;
  CameraMotion motion;
  motion.world_from_body = rigid_from_pose(60.0, -5.25, 1.5, -0.15, 0.0, 0.0);
  const CameraImages img = camera.render(built->scene, motion, settings);
  const auto labels = static_object_labels(built->scene, img.instance, img.width, img.semantic);
  int seen = 0;
  for (const auto& l : labels) {
    if (l.info.kind != "parked_vehicle") {
      continue;
    }
    ++seen;
    CHECK(l.semantic == SemanticClass::kCar);
    CHECK(l.instance_id >= kStaticInstanceBase);
    CHECK_FALSE(l.info.type.empty());
    // The label's box is the car's own, turned with it (not its axis-aligned bounds).
    const auto& record = built->scene.data().objects.at(l.instance_id);
    CHECK(l.box_world.length == Approx(record.info.box->length));
    CHECK(l.box_world.yaw() == Approx(record.info.box->yaw()));
  }
  CHECK(seen >= 2);
  // Depth and the LiDAR: a ray at a car's door, 3 m from its box, returns the car, its
  // instance and its body a few centimetres inside the box (the mirrors stand out further).
  const ParkedCar& car = cars.front();
  const Vec3 door = car.box.center + car.box.rotation * Vec3{0.3, 0.0, 0.0};
  const Vec3 side = door + car.box.rotation * Vec3{0.0, 0.5 * car.box.width + 3.0, 0.0};
  const Vec3 towards = door - side;
  const auto hit = built->scene.intersect(side, towards, 10.0);
  REQUIRE(hit);
  CHECK(hit->semantic == SemanticClass::kCar);
  CHECK(hit->instance_id == car.id);
  CHECK(hit->distance > 3.0);
  CHECK(hit->distance < 3.0 + 0.2);
  LidarOptions o;
  o.channels = 32;
  o.lower_fov_deg = -25.0;
  o.upper_fov_deg = 5.0;
  o.range_m = 60.0;
  const LidarSimulator lidar(o);
  const PointCloud cloud =
      lidar.scan(built->scene, rigid_from_pose(60.0, -5.25, 1.8, 0, 0, 0), 0.0, 3);
  int points = 0;
  for (const auto& p : cloud.points) {
    const auto it = built->scene.data().objects.find(p.instance_id);
    if (it != built->scene.data().objects.end() && it->second.info.kind == "parked_vehicle") {
      ++points;
      CHECK(p.semantic == SemanticClass::kCar);
    }
  }
  CHECK(points > 50);
}

TEST_CASE(
    "parked cars are objects of the camera, KITTI and LiDAR labels, class car without a "
    "semantic camera",
    "[sensors][world][parked][labels][kitti]") {
  const auto map = corsa::test::load_map(kParkingStreet);
  auto built = corsa::test::build_world_scene(map, 5);
  built->scene.set_entities({});
  const auto cars = parked_cars(built->scene);
  REQUIRE(!cars.empty());
  const CameraRenderer camera(corsa::test::wide_camera());
  RenderSettings settings;  // no semantic image
  CameraMotion motion;
  motion.world_from_body = rigid_from_pose(60.0, -5.25, 1.5, -0.15, 0.0, 0.0);
  const CameraImages img = camera.render(built->scene, motion, settings);
  REQUIRE(img.semantic.empty());
  const auto statics = static_object_labels(built->scene, img.instance, img.width);
  const auto labels = camera_labels(built->scene, camera, motion.world_from_body, img.instance);
  int static_parked = 0;
  for (const auto& l : statics) {
    if (l.info.kind == "parked_vehicle") {
      ++static_parked;
      CHECK(l.semantic == SemanticClass::kCar);  // known, not read from pixels
    } else {
      CHECK(l.semantic == SemanticClass::kStatic);  // other objects: as before
    }
  }
  REQUIRE(static_parked >= 2);
  int parked = 0, occluded = 0;
  for (const auto& l : labels) {
    REQUIRE(l.parked);  // the scene has no entity
    ++parked;
    const auto& box = *built->scene.data().objects.at(l.instance_id).info.box;
    CHECK(l.semantic == SemanticClass::kCar);
    CHECK(l.track_id == l.instance_id);
    CHECK(l.box_world.length == Approx(box.length));
    CHECK(l.box_world.yaw() == Approx(box.yaw()));
    CHECK(l.box_sensor.center.z > 0.0);  // in front of the camera (optical frame: z ahead)
    CHECK(l.visible_pixels > 0);
    CHECK(l.box_2d_visible.x_min >= l.box_2d.x_min - 1.0);
    CHECK(l.box_2d_visible.x_max <= l.box_2d.x_max + 1.0);
    CHECK(l.occlusion >= 0.0);
    CHECK(l.occlusion <= 1.0);
    occluded += l.occlusion > 0.3;
  }
  // Every car a static label lists is an object too (none is behind the camera here).
  CHECK(parked == static_parked);
  // Cars in a row along the kerb hide each other: the ones further on are occluded.
  CHECK(occluded >= 1);
  // KITTI: one line per car, Car for the near ones, DontCare for the far or small ones.
  KittiOptions options;
  options.max_distance_m = 80.0;
  const std::string kitti = kitti_label_lines(labels, camera.model(), img.instance, options);
  int cars_lines = 0, dont_care = 0, lines = 0;
  for (size_t at = 0; at < kitti.size();) {
    const size_t end = kitti.find('\n', at);
    const std::string line = kitti.substr(at, end - at);
    cars_lines += line.rfind("Car ", 0) == 0;
    dont_care += line.rfind("DontCare ", 0) == 0;
    ++lines;
    at = end + 1;
  }
  CHECK(lines == parked);
  CHECK(cars_lines + dont_care == parked);
  CHECK(cars_lines >= 1);
  // LiDAR: every parked car within range is an object, with its points.
  LidarOptions o;
  o.channels = 32;
  o.lower_fov_deg = -25.0;
  o.upper_fov_deg = 5.0;
  o.range_m = 60.0;
  const LidarSimulator lidar(o);
  const Rigid at = rigid_from_pose(60.0, -5.25, 1.8, 0, 0, 0);
  const PointCloud cloud = lidar.scan(built->scene, at, 0.0, 3);
  const auto sweep = lidar_labels(built->scene, at, cloud, o.range_m);
  int in_range = 0;
  for (const ParkedCar& car : cars) {
    in_range += norm(car.box.center - at.translation) <= o.range_m;
  }
  CHECK(static_cast<int>(sweep.size()) == in_range);
  uint64_t points = 0;
  for (const auto& l : sweep) {
    CHECK(l.parked);
    CHECK(l.semantic == SemanticClass::kCar);
    CHECK(l.distance <= o.range_m);
    points += l.lidar_points;
  }
  CHECK(points > 50);
}
