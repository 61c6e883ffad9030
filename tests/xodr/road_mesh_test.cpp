// The road mesh of the real maps: it builds, its size is sane, it faces up, its vertices lie on
// the road surface, it has no cracks inside a road, and it is deterministic.

#include "corsa/xodr/road_mesh.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <set>
#include <string>

#include "mesh_test_util.h"

using namespace corsa::xodr;
using namespace corsa::xodr::mesh_test;

namespace {

/// Lane length (m) of a map: section length times lanes with a width somewhere in the section.
double lane_length(const Map& map) {
  double total = 0.0;
  for (size_t r = 0; r < map.road_count(); ++r) {
    const Road& road = map.road(r);
    for (size_t k = 0; k < road.lane_sections.size(); ++k) {
      const double length = std::max(0.0, map.section_end(r, k) - road.lane_sections[k].s);
      total += length * static_cast<double>(road.lane_sections[k].lanes.size() - 1);
    }
  }
  return total;
}

bool is_lane(const TriangleInfo& info) { return info.kind == SurfaceKind::kLane; }

/// Maps of one road without lane heights or kinks, where locate() finds the road of any point.
const char* const kSingleRoadMaps[] = {
    "Ex_Line-Spiral-Arc.xodr", "Ex_Line-Spiral-Arc_elevation_and_superelevation.xodr",
    "Ex_Lane-Width.xodr",      "two_plus_one.xodr",
    "velodrome.xodr",          "e6mini.xodr",
    "straight_500m.xodr",      "road_geometry_param_poly3_length_match_valid.xodr",
};

}  // namespace

TEST_CASE("every shared map gives a sane upward-facing mesh", "[xodr][mesh]") {
  const auto maps = all_shared_maps();
  REQUIRE(maps.size() >= 19);
  for (const auto& path : maps) {
    INFO(path.filename().string());
    const Map map = load(path);
    corsa::Diagnostics diagnostics;
    const RoadMesh mesh = build_road_mesh(map, MeshOptions{}, diagnostics);
    REQUIRE(mesh.info.size() == mesh.triangles.size());
    size_t lane_triangles = 0;
    size_t marks = 0;
    size_t bad = 0;
    std::vector<bool> used(mesh.vertices.size(), false);
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
      const auto& t = mesh.triangles[i];
      for (uint32_t v : t) {
        REQUIRE(v < mesh.vertices.size());
        used[v] = true;
      }
      const Vec3 n = normal(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
      const double length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
      // Up (counter-clockwise from above), or vertical (a curb face), never down or degenerate.
      bad += (length > 0.0 && n.z >= -1e-9 * length) ? 0 : 1;
      lane_triangles += mesh.info[i].kind == SurfaceKind::kLane ? 1 : 0;
      marks += mesh.info[i].kind == SurfaceKind::kRoadMark ? 1 : 0;
      REQUIRE(mesh.info[i].road_index < map.road_count());
    }
    CHECK(bad == 0);
    CHECK(std::count(used.begin(), used.end(), false) == 0);
    for (const Vec3& v : mesh.vertices) {
      REQUIRE((std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)));
    }
    // At least a quad per road; at most one row every 5 cm of lane on average.
    CHECK(lane_triangles >= 2 * map.road_count());
    CHECK(static_cast<double>(lane_triangles) <= 2.0 * lane_length(map) / 0.05);
    const bool has_marks =
        std::any_of(map.data().roads.begin(), map.data().roads.end(), [](const Road& road) {
          for (const auto& section : road.lane_sections) {
            for (const auto& lane : section.lanes) {
              for (const auto& m : lane.road_marks) {
                if (m.type == "solid" || m.type == "broken") {
                  return true;
                }
              }
            }
          }
          return false;
        });
    CHECK((marks > 0) == has_marks);
  }
}

TEST_CASE("lane vertices lie on the road surface at their s and t", "[xodr][mesh]") {
  for (const char* name : kSingleRoadMaps) {
    INFO(name);
    const Map map = load(shared_map(name));
    REQUIRE(map.road_count() == 1);
    const RoadMesh mesh = build_road_mesh(map);
    std::set<uint32_t> lane_vertices;
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
      if (is_lane(mesh.info[i])) {
        lane_vertices.insert(mesh.triangles[i].begin(), mesh.triangles[i].end());
      }
    }
    REQUIRE(!lane_vertices.empty());
    double worst = 0.0;
    LocateOptions options;
    options.max_distance = 0.01;
    for (uint32_t v : lane_vertices) {
      const Vec3& p = mesh.vertices[v];
      const auto position = map.locate(p.x, p.y, options);
      REQUIRE(position.has_value());
      const WorldPose pose = map.world_pose(position->road, position->s, position->t);
      worst = std::max(worst, distance(p, Vec3{pose.x, pose.y, pose.z}));
    }
    CHECK(worst < 1e-6);
  }
}

TEST_CASE("lanes and lane sections of a road share their border vertices", "[xodr][mesh]") {
  // Every edge used by a single lane triangle lies on the road's outer edge or at its ends:
  // inside the road each edge is shared by two triangles (no crack, no T-junction).
  for (const char* name : kSingleRoadMaps) {
    INFO(name);
    const Map map = load(shared_map(name));
    const RoadMesh mesh = build_road_mesh(map);
    const Road& road = map.road(0);
    size_t inner_boundary = 0;
    size_t boundary = 0;
    std::vector<LaneSpan> spans;
    LocateOptions options;
    options.max_distance = 0.2;  // chords of a concave outer border lie outside by the tolerance
    for (const auto& [edge, count] : edge_counts(mesh, is_lane)) {
      if (count != 1) {
        continue;
      }
      ++boundary;
      const Vec3& a = mesh.vertices[edge.first];
      const Vec3& b = mesh.vertices[edge.second];
      const auto position = map.locate(0.5 * (a.x + b.x), 0.5 * (a.y + b.y), options);
      REQUIRE(position.has_value());
      if (position->s < 1e-3 || position->s > road.length - 1e-3) {
        continue;  // an end of the road
      }
      map.lane_spans(0, position->s, spans);
      double t_min = 1e300;
      double t_max = -1e300;
      for (const LaneSpan& span : spans) {
        t_min = std::min(t_min, span.t_min());
        t_max = std::max(t_max, span.t_max());
      }
      // Chords cut inside curved outer borders by up to the tolerance, in 3D; on a banked road
      // t (measured across the slope) stretches that by 1 / cos(roll).
      const double slack = 0.11 / std::cos(map.superelevation(0, position->s));
      const bool outer =
          std::abs(position->t - t_min) < slack || std::abs(position->t - t_max) < slack;
      inner_boundary += outer ? 0 : 1;
    }
    CHECK(boundary > 0);
    CHECK(inner_boundary == 0);
  }
}

TEST_CASE("the mesh of a map is the same every time", "[xodr][mesh]") {
  const Map map = load(shared_map("Ex_Entry_Exit.xodr"));
  const RoadMesh a = build_road_mesh(map);
  const RoadMesh b = build_road_mesh(map);
  REQUIRE(a.vertices.size() == b.vertices.size());
  REQUIRE(a.triangles == b.triangles);
  for (size_t i = 0; i < a.vertices.size(); ++i) {
    REQUIRE(a.vertices[i].x == b.vertices[i].x);
    REQUIRE(a.vertices[i].y == b.vertices[i].y);
    REQUIRE(a.vertices[i].z == b.vertices[i].z);
  }
  for (size_t i = 0; i < a.info.size(); ++i) {
    REQUIRE(a.info[i].lane_id == b.info[i].lane_id);
    REQUIRE(a.info[i].road_index == b.info[i].road_index);
  }
}

TEST_CASE("lane vertices carry their s and their place across the lanes", "[xodr][mesh]") {
  for (const char* name : kSingleRoadMaps) {
    if (std::string(name) == "two_plus_one.xodr") {
      // Its lanes open from zero width: there the lanes either side of the closed one share a
      // vertex, which carries the first one's value (a known limit of per-vertex coordinates).
      continue;
    }
    INFO(name);
    const Map map = load(shared_map(name));
    const double length = map.road(0).length;
    const RoadMesh mesh = build_road_mesh(map);
    REQUIRE(mesh.lane_coords.size() == mesh.vertices.size());
    LocateOptions options;
    options.max_distance = 0.01;
    size_t lanes = 0;
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
      if (!is_lane(mesh.info[i])) {
        continue;
      }
      // A lane |id| k spans k - 1 (its inner border) to k (its outer border) across.
      const double outer = std::abs(mesh.info[i].lane_id);
      double across_sum = 0.0;
      for (uint32_t v : mesh.triangles[i]) {
        const auto& coords = mesh.lane_coords[v];
        CHECK(coords[1] >= outer - 1.0 - 1e-6);
        CHECK(coords[1] <= outer + 1e-6);
        across_sum += coords[1];
        const Vec3& p = mesh.vertices[v];
        const auto position = map.locate(p.x, p.y, options);
        REQUIRE(position.has_value());
        // s of a closed loop's first and last rows are the same place.
        CHECK(std::remainder(coords[0] - position->s, length) == Approx(0.0).margin(1e-3));
      }
      // Corners on both borders: the triangle spans the lane.
      CHECK(across_sum / 3.0 > outer - 1.0 + 0.2);
      CHECK(across_sum / 3.0 < outer - 0.2);
      ++lanes;
    }
    CHECK(lanes > 0);
  }
}

TEST_CASE("triangles carry their road, lane, type and junction flag", "[xodr][mesh]") {
  const Map map = load(shared_map("fabriksgatan.xodr"));
  const RoadMesh mesh = build_road_mesh(map);
  size_t junction = 0;
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    const TriangleInfo& info = mesh.info[i];
    const Road& road = map.road(info.road_index);
    CHECK(info.in_junction == road.in_junction());
    junction += info.in_junction ? 1 : 0;
    if (info.kind != SurfaceKind::kLane) {
      continue;
    }
    // The lane exists in the road with that type, and the triangle lies inside it.
    const auto& t = mesh.triangles[i];
    const Vec3& a = mesh.vertices[t[0]];
    const Vec3& b = mesh.vertices[t[1]];
    const Vec3& c = mesh.vertices[t[2]];
    if (std::abs(area2_xy(a, b, c)) < 1e-6) {
      continue;  // vertical curb faces
    }
    const double cx = (a.x + b.x + c.x) / 3.0;
    const double cy = (a.y + b.y + c.y) / 3.0;
    bool found = false;
    for (const LaneSection& section : road.lane_sections) {
      for (const Lane& lane : section.lanes) {
        found = found || (lane.id == info.lane_id && lane.type == info.lane_type);
      }
    }
    CHECK(found);
    const auto position = map.locate(cx, cy);
    REQUIRE(position.has_value());
    CHECK(position->distance < 0.1);
  }
  CHECK(junction > 0);
}

TEST_CASE("a straight road of constant width needs only its two ends", "[xodr][mesh]") {
  const Map map = build({make_road("1", {geometry(0, 0, 0, 0.4, 200.0)},
                                   {{2, LaneType::kSidewalk, 2.0},
                                    {1, LaneType::kDriving, 3.5},
                                    {-1, LaneType::kDriving, 3.5},
                                    {-2, LaneType::kShoulder, 1.0}})});
  const RoadMesh mesh = build_road_mesh(map);
  CHECK(mesh.triangles.size() == 8);  // 4 lanes x 2
  CHECK(mesh.vertices.size() == 10);  // 5 borders x 2 rows
  MeshOptions capped;
  capped.max_segment = 30.0;
  const RoadMesh fine = build_road_mesh(map, capped);
  CHECK(fine.triangles.size() == 8 * 8);  // 200 m halved three times: 8 pieces of 25 m
}

TEST_CASE("bad mesh options are refused", "[xodr][mesh]") {
  const Map map = build({make_road("1", {geometry(0, 0, 0, 0, 10.0)}, {{-1}})});
  MeshOptions options;
  options.tolerance = 0.0;
  CHECK_THROWS_AS(build_road_mesh(map, options), std::invalid_argument);
  options.tolerance = std::nan("");
  CHECK_THROWS_AS(build_road_mesh(map, options), std::invalid_argument);
  options.tolerance = 0.1;
  options.max_segment = -1.0;
  CHECK_THROWS_AS(build_road_mesh(map, options), std::invalid_argument);
}
