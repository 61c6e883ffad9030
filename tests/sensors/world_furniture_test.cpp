// Street furniture at the kerb and the verges of the ground: where things stand and what they
// are labelled.

#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "corsa/sensors/camera_render.h"
#include "corsa/sensors/labels.h"
#include "corsa/sensors/lidar.h"
#include "corsa/xodr/parser.h"
#include "scene_data.h"
#include "world_fixture.h"

using namespace corsa::sensors;

namespace {

/// A straight 300 m street along +x (t is y): a 4 m sidewalk and one lane on the left, two
/// lanes and a 4 m sidewalk on the right, 3.5 m lanes; a zebra crossing (StVO 293) at s = 150.
/// Kerbs at y = 3.5 and y = -7, sidewalks' outer edges at y = 7.5 and y = -11.
corsa::xodr::Map furnished_street() {
  const std::string text =
      R"(<?xml version="1.0"?><OpenDRIVE><header revMajor="1" revMinor="8"/>
<road id="1" length="300" junction="-1"><planView>
<geometry s="0" x="0" y="0" hdg="0" length="300"><line/></geometry></planView>
<lanes><laneSection s="0"><left>
<lane id="2" type="sidewalk"><width sOffset="0" a="4" b="0" c="0" d="0"/></lane>
<lane id="1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></left>
<center><lane id="0" type="none"/></center><right>
<lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
<lane id="-2" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
<lane id="-3" type="sidewalk"><width sOffset="0" a="4" b="0" c="0" d="0"/></lane>
</right></laneSection></lanes><signals>
<signal id="zebra" s="150" t="0" orientation="none" dynamic="no" country="DE" type="293"/>
</signals></road></OpenDRIVE>)";
  corsa::Diagnostics diagnostics;
  return corsa::xodr::Map::build(corsa::xodr::parse_xodr_text(text, "street.xodr", diagnostics),
                                 diagnostics);
}

const std::set<std::string> kFurnitureKinds = {"bus_shelter",  "bus_stop_sign", "street_name_sign",
                                               "fire_hydrant", "litter_bin",    "bench",
                                               "bollard"};

bool is_furniture(const Scene& scene, uint32_t instance) {
  const auto& objects = scene.data().objects;
  const auto it = objects.find(instance);
  return it != objects.end() && kFurnitureKinds.count(it->second.info.kind) > 0;
}

/// The furniture of a scene: kind and bounds, in instance order.
std::vector<std::pair<std::string, Bounds>> furniture_of(const Scene& scene) {
  std::vector<std::pair<std::string, Bounds>> out;
  for (const auto& [id, record] : scene.data().objects) {
    if (kFurnitureKinds.count(record.info.kind) > 0) {
      out.emplace_back(record.info.kind, record.bounds);
    }
  }
  return out;
}

/// Furniture hit by a ray straight down from head height (2.2 m) at (x, y), above the ground.
bool furniture_over(const Scene& scene, double x, double y) {
  const auto hit = scene.intersect({x, y, 2.2}, {0.0, 0.0, -1.0}, 2.5);
  return hit && hit->point.z > 0.02 && is_furniture(scene, hit->instance_id);
}

}  // namespace

TEST_CASE("street furniture stands in the kerb zone, never on the walking path or a crossing",
          "[sensors][world][furniture]") {
  const auto map = furnished_street();
  auto built = corsa::test::build_world_scene(map, 11);
  const auto items = furniture_of(built->scene);
  REQUIRE(built->report.street_furniture == items.size());
  REQUIRE(items.size() >= 8);
  std::map<std::string, int> kinds;
  for (const auto& [kind, b] : items) {
    ++kinds[kind];
    INFO(kind << " at x " << b.min.x << ".." << b.max.x << ", y " << b.min.y << ".." << b.max.y);
    // On a sidewalk, not over the road: left kerb y = 3.5, right kerb y = -7.
    CHECK((b.min.y >= 3.5 || b.max.y <= -7.0));
    // Not where the crossing lands: its paint spans x 148-152, kept clear by 2 m more.
    CHECK((b.max.x < 146.0 || b.min.x > 154.0));
  }
  CHECK(kinds["litter_bin"] >= 2);
  // The walking path (the outer 1.8 m of each sidewalk) is clear to head height.
  int blocked = 0;
  for (double x = 0.05; x < 300.0; x += 0.1) {
    for (double d = 0.05; d < 1.8; d += 0.15) {
      blocked += furniture_over(built->scene, x, 7.5 - d) ? 1 : 0;
      blocked += furniture_over(built->scene, x, -11.0 + d) ? 1 : 0;
    }
  }
  CHECK(blocked == 0);
  // ... and so is the sidewalk where the crossing lands, kerb to building line.
  for (double x = 147.5; x <= 152.5; x += 0.1) {
    for (double y = 3.55; y < 7.5; y += 0.1) {
      CHECK_FALSE(furniture_over(built->scene, x, y));
      CHECK_FALSE(furniture_over(built->scene, x, -y - 3.5));
    }
  }
}

TEST_CASE("street furniture keeps clear of trees, street lights and each other",
          "[sensors][world][furniture]") {
  const auto map = furnished_street();
  auto built = corsa::test::build_world_scene(map, 4);
  const auto items = furniture_of(built->scene);
  REQUIRE(!items.empty());
  // Trunks and lamp posts: the labelled trees and street lights' bounds at their foot.
  for (const auto& [id, record] : built->scene.data().objects) {
    if (record.info.kind != "tree" && record.info.kind != "street_light") {
      continue;
    }
    const double fx = 0.5 * (record.bounds.min.x + record.bounds.max.x);
    const double fy = 0.5 * (record.bounds.min.y + record.bounds.max.y);
    for (const auto& [kind, b] : items) {
      const double dx = std::max({b.min.x - fx, 0.0, fx - b.max.x});
      const double dy = std::max({b.min.y - fy, 0.0, fy - b.max.y});
      INFO(kind << " near " << record.info.kind << " at " << fx << ", " << fy);
      CHECK(std::hypot(dx, dy) > 0.5);
    }
  }
  for (size_t i = 0; i < items.size(); ++i) {
    for (size_t j = i + 1; j < items.size(); ++j) {
      const Bounds& a = items[i].second;
      const Bounds& b = items[j].second;
      const bool overlap = a.min.x < b.max.x && b.min.x < a.max.x && a.min.y < b.max.y &&
                           b.min.y < a.max.y && a.min.z < 2.2 && b.min.z < 2.2;
      CHECK_FALSE(overlap);
    }
  }
}

TEST_CASE("street furniture is the same for a seed and moves with another",
          "[sensors][world][furniture][determinism]") {
  const auto map = furnished_street();
  auto a = corsa::test::build_world_scene(map, 7);
  auto b = corsa::test::build_world_scene(map, 7);
  auto c = corsa::test::build_world_scene(map, 8);
  const auto fa = furniture_of(a->scene);
  const auto fb = furniture_of(b->scene);
  const auto fc = furniture_of(c->scene);
  REQUIRE(fa.size() == fb.size());
  for (size_t i = 0; i < fa.size(); ++i) {
    CHECK(fa[i].first == fb[i].first);
    CHECK(fa[i].second.min.x == fb[i].second.min.x);
    CHECK(fa[i].second.max.y == fb[i].second.max.y);
  }
  bool moved = fa.size() != fc.size();
  for (size_t i = 0; !moved && i < fa.size(); ++i) {
    moved = fa[i].first != fc[i].first || fa[i].second.min.x != fc[i].second.min.x;
  }
  CHECK(moved);
  CHECK(a->scene.static_triangle_count() == b->scene.static_triangle_count());
}

TEST_CASE("street furniture carries its class and instance id in the labels and the LiDAR",
          "[sensors][world][furniture][labels]") {
  const auto map = furnished_street();
  auto built = corsa::test::build_world_scene(map, 11);
  built->scene.set_entities({});
  // A camera on the right sidewalk's walking path, looking along it.
  const CameraRenderer camera(corsa::test::wide_camera());
  RenderSettings settings;
  settings.outputs.semantic = true;
  CameraMotion motion;
  motion.world_from_body = rigid_from_pose(20.0, -10.0, 1.6, 0.0, 0.0, 0.0);
  const CameraImages img = camera.render(built->scene, motion, settings);
  const auto labels = static_object_labels(built->scene, img.instance, img.width, img.semantic);
  int furniture = 0;
  for (const auto& l : labels) {
    if (kFurnitureKinds.count(l.info.kind) == 0) {
      continue;
    }
    ++furniture;
    INFO(l.info.kind);
    CHECK(l.instance_id >= kStaticInstanceBase);
    if (l.info.kind == "litter_bin" || l.info.kind == "bench" || l.info.kind == "fire_hydrant" ||
        l.info.kind == "bollard" || l.info.kind == "bus_shelter") {
      CHECK(l.semantic == SemanticClass::kStatic);
    } else {
      CHECK((l.semantic == SemanticClass::kPole || l.semantic == SemanticClass::kTrafficSign));
    }
  }
  CHECK(furniture >= 3);
  // A LiDAR on the sidewalk sees the furniture with its class and instance.
  LidarOptions o;
  o.channels = 32;
  o.lower_fov_deg = -25.0;
  o.upper_fov_deg = 5.0;
  o.range_m = 60.0;
  const LidarSimulator lidar(o);
  const PointCloud cloud =
      lidar.scan(built->scene, rigid_from_pose(20.0, -10.0, 1.8, 0, 0, 0), 0.0, 3);
  int points = 0;
  for (const auto& p : cloud.points) {
    if (is_furniture(built->scene, p.instance_id)) {
      ++points;
    }
  }
  CHECK(points > 20);
}

TEST_CASE("the ground meets road and sidewalk edges in a verge that reaches under the edge",
          "[sensors][world][verge]") {
  const auto map = furnished_street();
  auto built = corsa::test::build_world_scene(map, 11);
  CHECK(built->report.verge_triangles > 300);  // both outer edges, 300 m in 1.5 m steps
  // Just beyond the right sidewalk's edge the first thing down is terrain lying above the
  // ground mesh, a little under the sidewalk, and inside the edge it is still the sidewalk.
  for (double x = 30.0; x < 270.0; x += 7.3) {
    const auto verge = built->scene.intersect({x, -11.2, 2.0}, {0.0, 0.0, -1.0}, 5.0);
    REQUIRE(verge);
    CHECK(verge->semantic == SemanticClass::kTerrain);
    CHECK(verge->point.z < 0.0);
    CHECK(verge->point.z > -0.08);
    const auto walk = built->scene.intersect({x, -10.9, 2.0}, {0.0, 0.0, -1.0}, 5.0);
    REQUIRE(walk);
    CHECK((walk->semantic == SemanticClass::kSidewalk ||
           is_furniture(built->scene, walk->instance_id) ||
           walk->semantic == SemanticClass::kVegetation || walk->semantic == SemanticClass::kPole));
  }
}

TEST_CASE("on the 2 m sidewalks of a CARLA town only slim furniture stands, at the kerb",
          "[sensors][world][furniture]") {
  // Town04's sidewalks are 2 m wide: a 1.5 m walking path leaves room for posts alone.
  const auto map = corsa::test::load_map(corsa::test::kXodrData / "Town04.xodr");
  auto built = corsa::test::build_world_scene(map, 3);
  const auto items = furniture_of(built->scene);
  CHECK(items.size() >= 10);
  for (const auto& [kind, b] : items) {
    INFO(kind << " at " << b.min.x << ", " << b.min.y);
    CHECK((kind == "bollard" || kind == "street_name_sign" || kind == "bus_stop_sign"));
    // It stands on a sidewalk, by the kerb (its box's middle within 1 m of the kerb: a bollard's
    // 0.35 m, a street-name sign's blade over the path shifts it to about 0.7 m).
    const double x = 0.5 * (b.min.x + b.max.x);
    const double y = 0.5 * (b.min.y + b.max.y);
    const auto at = map.locate(x, y);
    REQUIRE(at);
    CHECK(at->distance == 0.0);
    const auto& lanes = map.road(at->road).lane_sections[at->section].lanes;
    for (const auto& lane : lanes) {
      if (lane.id == at->lane) {
        CHECK(lane.type == corsa::xodr::LaneType::kSidewalk);
      }
    }
    std::vector<corsa::xodr::LaneSpan> spans;
    map.lane_spans(at->road, at->s, spans);
    for (const auto& span : spans) {
      if (span.id == at->lane) {
        CHECK(std::fabs(at->t - span.t_inner) < 1.0);
      }
    }
  }
}
