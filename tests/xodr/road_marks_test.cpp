// Road marks: where the lines go, how they are cut into dashes, their colours, and the strips
// they become in the mesh.

#include "corsa/xodr/road_marks.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "corsa/xodr/road_mesh.h"
#include "mesh_test_util.h"

using namespace corsa::xodr;
using namespace corsa::xodr::mesh_test;

namespace {

std::vector<MarkLine> marks_of(const Map& map, int lane) {
  corsa::Diagnostics diagnostics;
  std::vector<MarkLine> out;
  for (MarkLine& line : build_road_marks(map, MeshOptions{}, diagnostics)) {
    if (line.lane_id == lane) {
      out.push_back(std::move(line));
    }
  }
  return out;
}

/// A straight 100 m road along +x (so t is y) with the given marks on the centre and lane -1.
Map straight(std::vector<RoadMark> center, std::vector<RoadMark> right = {}) {
  return build({make_road("1", {geometry(0, 0, 0, 0, 100.0)},
                          {{0, LaneType::kNone, 0.0, {}, {}, center},
                           {1, LaneType::kDriving, 3.5},
                           {-1, LaneType::kDriving, 3.5, {}, {}, right}})});
}

}  // namespace

TEST_CASE("road marks float just above the road surface", "[xodr][marks]") {
  for (const char* name :
       {"Ex_Line-Spiral-Arc_elevation_and_superelevation.xodr", "straight_500m.xodr"}) {
    INFO(name);
    const Map map = load(shared_map(name));
    const RoadMesh mesh = build_road_mesh(map);
    size_t checked = 0;
    LocateOptions options;
    options.max_distance = 1.0;  // half of an edge line lies past the road's edge
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
      if (mesh.info[i].kind != SurfaceKind::kRoadMark) {
        continue;
      }
      for (uint32_t v : mesh.triangles[i]) {
        const Vec3& p = mesh.vertices[v];
        const auto position = map.locate(p.x, p.y, options);
        REQUIRE(position.has_value());
        const double surface = map.world_pose(0, position->s, position->t).z;
        // These files give their marks a height (thickness) of 0.02 m.
        CHECK(p.z - surface == Approx(0.02).margin(1e-6));
        ++checked;
      }
    }
    CHECK(checked > 100);
  }
}

TEST_CASE("marks without a height are lifted by the mesh option", "[xodr][marks]") {
  const Map map = straight({mark("solid")});
  MeshOptions options;
  options.mark_lift = 0.005;
  const RoadMesh mesh = build_road_mesh(map, options);
  size_t marks = 0;
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    for (uint32_t v : mesh.triangles[i]) {
      const double expected = mesh.info[i].kind == SurfaceKind::kRoadMark ? 0.005 : 0.0;
      CHECK(mesh.vertices[v].z == Approx(expected).margin(1e-12));
    }
    marks += mesh.info[i].kind == SurfaceKind::kRoadMark ? 1 : 0;
  }
  CHECK(marks == 2);
  options.road_marks = false;
  for (const TriangleInfo& info : build_road_mesh(map, options).info) {
    CHECK(info.kind == SurfaceKind::kLane);
  }
}

TEST_CASE("a broken line is 3 m of paint and 9 m of gap from the record's start", "[xodr][marks]") {
  const auto lines = marks_of(straight({mark("broken")}), 0);
  REQUIRE(lines.size() == 9);  // dashes at 0, 12, ..., 96
  for (size_t k = 0; k < lines.size(); ++k) {
    INFO("dash " << k);
    CHECK(lines[k].s.front() == Approx(12.0 * static_cast<double>(k)));
    CHECK(lines[k].s.back() == Approx(12.0 * static_cast<double>(k) + 3.0));
    CHECK(lines[k].center.front().y == Approx(0.0).margin(1e-12));
    CHECK(lines[k].color == MarkColor::kWhite);
  }
}

TEST_CASE("double lines lie a line width apart, the first one inside", "[xodr][marks]") {
  const Map map =
      straight({mark("solid broken", "yellow", 0.15)}, {mark("broken solid", "standard", 0.15)});
  // Centre lane: first named (solid) on the left, +t.
  const auto center = marks_of(map, 0);
  size_t solid = 0;
  size_t dashes = 0;
  for (const MarkLine& line : center) {
    CHECK(line.color == MarkColor::kYellow);
    const double y = line.center.front().y;
    if (y > 0.0) {
      ++solid;
      CHECK(y == Approx(0.15));
      CHECK(line.s.back() - line.s.front() == Approx(100.0));
    } else {
      ++dashes;
      CHECK(y == Approx(-0.15));
    }
    // The strip is the line's width wide.
    CHECK(distance(line.left.front(), line.right.front()) == Approx(0.15));
  }
  CHECK(solid == 1);
  CHECK(dashes == 9);
  // Lane -1: first named (broken) inside, towards the centre (+t), at its outer border -3.5.
  for (const MarkLine& line : marks_of(map, -1)) {
    const bool is_dash = line.s.back() - line.s.front() < 50.0;
    CHECK(line.center.front().y == Approx(is_dash ? -3.35 : -3.65));
    CHECK(line.color == MarkColor::kWhite);
  }
}

TEST_CASE("botts dots are short dots along the border", "[xodr][marks]") {
  const auto dots = marks_of(straight({mark("botts dots")}), 0);
  CHECK(dots.size() == 84);  // every 1.2 m over 100 m
  for (const MarkLine& dot : dots) {
    CHECK(dot.s.back() - dot.s.front() == Approx(0.15));
  }
}

TEST_CASE("marks follow their record's range and skip what is not paint", "[xodr][marks]") {
  RoadMark later = mark("none");
  later.s_offset = 40.0;
  const Map map = straight({mark("solid"), later}, {mark("curb")});
  const auto center = marks_of(map, 0);
  REQUIRE(center.size() == 1);
  CHECK(center[0].s.front() == Approx(0.0));
  CHECK(center[0].s.back() == Approx(40.0));
  CHECK(marks_of(map, -1).empty());
  for (const char* type : {"grass", "edge", "none"}) {
    CHECK(marks_of(straight({mark(type)}), 0).empty());
  }
}

TEST_CASE("a zero-width lane carries no mark", "[xodr][marks]") {
  const Map map = build({make_road("1", {geometry(0, 0, 0, 0, 30.0)},
                                   {{-1, LaneType::kDriving, 3.5, {}, {}, {mark("solid")}},
                                    {-2, LaneType::kShoulder, 0.0, {}, {}, {mark("solid")}}})});
  CHECK(marks_of(map, -1).size() == 1);
  CHECK(marks_of(map, -2).empty());
}

TEST_CASE("unknown mark types and colours are warned about once", "[xodr][marks]") {
  const Map map =
      build({make_road("1", {geometry(0, 0, 0, 0, 30.0)},
                       {{1, LaneType::kDriving, 3.5, {}, {}, {mark("zigzag")}},
                        {-1, LaneType::kDriving, 3.5, {}, {}, {mark("zigzag")}},
                        {-2, LaneType::kDriving, 3.5, {}, {}, {mark("custom")}},
                        {-3, LaneType::kDriving, 3.5, {}, {}, {mark("solid", "purple")}}})});
  corsa::Diagnostics warnings;
  const RoadMesh mesh = build_road_mesh(map, MeshOptions{}, warnings);
  const auto all = warnings.all();
  REQUIRE(all.size() == 3);
  CHECK_THAT(all[0].message, Catch::Contains("'zigzag'"));
  CHECK_THAT(all[1].message, Catch::Contains("'custom'"));
  CHECK_THAT(all[2].message, Catch::Contains("'purple'"));
  CHECK(all[0].severity == corsa::Severity::kWarning);
  size_t marks = 0;
  for (const TriangleInfo& info : mesh.info) {
    if (info.kind == SurfaceKind::kRoadMark) {
      ++marks;
      CHECK(info.lane_id == -3);
      CHECK(info.color == MarkColor::kWhite);
    }
  }
  CHECK(marks == 2);
}

TEST_CASE("mark triangles face up and carry their lane and colour", "[xodr][marks]") {
  const Map map = load(shared_map("Town03.xodr"));
  const RoadMesh mesh = build_road_mesh(map);
  size_t yellow = 0;
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    const TriangleInfo& info = mesh.info[i];
    if (info.kind != SurfaceKind::kRoadMark) {
      continue;
    }
    const auto& t = mesh.triangles[i];
    CHECK(area2_xy(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]) > 0.0);
    CHECK(info.color != MarkColor::kNone);
    yellow += info.color == MarkColor::kYellow ? 1 : 0;
  }
  CHECK(yellow > 0);
}

TEST_CASE("mark colour names map to colours", "[xodr][marks]") {
  CHECK(mark_color_from_name("standard") == MarkColor::kWhite);
  CHECK(mark_color_from_name("White") == MarkColor::kWhite);
  CHECK(mark_color_from_name("yellow") == MarkColor::kYellow);
  CHECK(mark_color_from_name("violet") == MarkColor::kViolet);
  CHECK(mark_color_from_name("mauve") == MarkColor::kNone);
  CHECK(std::string(mark_color_name(MarkColor::kOrange)) == "orange");
}
