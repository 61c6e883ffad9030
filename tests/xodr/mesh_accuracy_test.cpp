// How closely the mesh follows the road: chord error on arcs and spirals, lane heights and curb
// faces, lateral shape, lanes that open or vanish, and the file's own discontinuities (kinks,
// sideways jumps, borders beyond the centre of curvature).

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "corsa/xodr/road_mesh.h"
#include "mesh_test_util.h"

using namespace corsa::xodr;
using namespace corsa::xodr::mesh_test;

namespace {

std::vector<LaneSpec> four_lanes() {
  return {{2, LaneType::kDriving, 3.5},
          {1, LaneType::kDriving, 3.5},
          {-1, LaneType::kDriving, 3.5},
          {-2, LaneType::kDriving, 3.5}};
}

/// Largest distance from the true borders of every lane (sampled every 5 cm along s) to that
/// lane's mesh outline, and the number of triangles per lane.
double worst_chord_error(const Map& map, const RoadMesh& mesh) {
  double worst = 0.0;
  std::vector<LaneSpan> spans;
  for (int lane : {2, 1, -1, -2}) {
    const auto outline = boundary_segments(mesh, [lane](const TriangleInfo& info) {
      return info.kind == SurfaceKind::kLane && info.lane_id == lane;
    });
    REQUIRE(!outline.empty());
    const double length = map.road(0).length;
    for (double s = 0.0; s <= length; s += 0.05) {
      const auto span = map.lane_span(0, s, lane);
      REQUIRE(span.has_value());
      for (double t : {span->t_inner, span->t_outer}) {
        const WorldPose p = map.world_pose(0, s, t);
        worst = std::max(worst, distance_to_segments(outline, Vec3{p.x, p.y, p.z}));
      }
    }
  }
  return worst;
}

size_t intervals(const RoadMesh& mesh) {
  size_t lane_triangles = 0;
  for (const TriangleInfo& info : mesh.info) {
    lane_triangles += info.kind == SurfaceKind::kLane ? 1 : 0;
  }
  return lane_triangles / 8;  // 4 lanes, 2 triangles per lane and interval
}

}  // namespace

TEST_CASE("the chord error stays under the tolerance on an arc", "[xodr][mesh][arc]") {
  const double radius = 50.0;
  const Map map = build(
      {make_road("arc", {geometry(0, 0, 0, 0, 100.0, ArcGeometry{1.0 / radius})}, four_lanes())});
  for (double tolerance : {0.1, 0.02}) {
    INFO("tolerance " << tolerance);
    MeshOptions options;
    options.tolerance = tolerance;
    options.road_marks = false;
    const RoadMesh mesh = build_road_mesh(map, options);
    CHECK(worst_chord_error(map, mesh) <= tolerance + 1e-9);
    // Not wastefully fine either: the outermost border (radius 57 m) needs pieces of
    // 2 * sqrt(2 r tol) along it; bisection at most halves that.
    const double piece =
        2.0 * std::sqrt(2.0 * (radius + 7.0) * tolerance) * radius / (radius + 7.0);
    const double ideal = 100.0 / piece;
    CHECK(static_cast<double>(intervals(mesh)) >= ideal);
    CHECK(static_cast<double>(intervals(mesh)) <= 2.0 * ideal + 1.0);
  }
}

TEST_CASE("the chord error stays under the tolerance on a spiral", "[xodr][mesh][spiral]") {
  const Map map = build({make_road(
      "spiral", {geometry(0, 10, -5, 0.3, 120.0, SpiralGeometry{-0.01, 0.04})}, four_lanes())});
  for (double tolerance : {0.1, 0.01}) {
    INFO("tolerance " << tolerance);
    MeshOptions options;
    options.tolerance = tolerance;
    options.road_marks = false;
    CHECK(worst_chord_error(map, build_road_mesh(map, options)) <= tolerance + 1e-9);
  }
}

TEST_CASE("the chord error stays under the tolerance on the ASAM line-spiral-arc road",
          "[xodr][mesh][spiral]") {
  const Map map = load(shared_map("Ex_Line-Spiral-Arc.xodr"));
  MeshOptions options;
  options.road_marks = false;
  const RoadMesh mesh = build_road_mesh(map, options);
  std::vector<LaneSpan> spans;
  map.lane_spans(0, 0.0, spans);
  double worst = 0.0;
  for (const LaneSpan& lane : spans) {
    const int id = lane.id;
    const auto outline = boundary_segments(mesh, [id](const TriangleInfo& info) {
      return info.kind == SurfaceKind::kLane && info.lane_id == id;
    });
    for (double s = 0.0; s <= map.road(0).length; s += 0.1) {
      const auto span = map.lane_span(0, s, id);
      REQUIRE(span.has_value());
      for (double t : {span->t_inner, span->t_outer}) {
        const WorldPose p = map.world_pose(0, s, t);
        worst = std::max(worst, distance_to_segments(outline, Vec3{p.x, p.y, p.z}));
      }
    }
  }
  CHECK(worst <= 0.1 + 1e-9);
}

TEST_CASE("lane heights raise the lane and a curb face joins it to the road",
          "[xodr][mesh][height]") {
  const LaneHeight raised{0.0, 0.15, 0.15};
  const Map map = build({make_road("1", {geometry(0, 0, 0, 0, 40.0)},
                                   {{1, LaneType::kDriving, 3.5},
                                    {-1, LaneType::kDriving, 3.5},
                                    {-2, LaneType::kSidewalk, 2.0, {}, {raised}, {}},
                                    {-3, LaneType::kBorder, 0.5, {}, {raised}, {}}})});
  const RoadMesh mesh = build_road_mesh(map);
  size_t curb = 0;
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    const TriangleInfo& info = mesh.info[i];
    const Vec3 n = normal(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
    if (std::abs(n.z) < 1e-9) {
      // The curb: vertical, at t = -3.5, labelled as the sidewalk, facing the road (+y here).
      ++curb;
      CHECK(info.lane_id == -2);
      CHECK(info.lane_type == LaneType::kSidewalk);
      CHECK(n.y > 0.0);
      for (uint32_t v : t) {
        CHECK(mesh.vertices[v].y == Approx(-3.5).margin(1e-9));
      }
      continue;
    }
    for (uint32_t v : t) {
      const double expected = info.lane_id <= -2 ? 0.15 : 0.0;
      CHECK(mesh.vertices[v].z == Approx(expected).margin(1e-12));
    }
  }
  CHECK(curb == 2);
  // The sidewalk and the border at the same height share their vertices (no second curb): the
  // shared edges are the two lanes' diagonals, their common border, the curb's diagonal and the
  // curb's top, which is the sidewalk's inner edge.
  const auto shared = edge_counts(mesh, [](const TriangleInfo& info) {
    return info.lane_id <= -2 && info.kind == SurfaceKind::kLane;
  });
  size_t inner_edges = 0;
  for (const auto& [edge, count] : shared) {
    inner_edges += count == 2 ? 1 : 0;
  }
  CHECK(inner_edges == 5);
}

TEST_CASE("a lane height that changes along s ramps linearly", "[xodr][mesh][height]") {
  const Map map = build(
      {make_road("1", {geometry(0, 0, 0, 0, 40.0)},
                 {{-1, LaneType::kDriving, 3.5},
                  {-2, LaneType::kSidewalk, 2.0, {}, {{0.0, 0.0, 0.0}, {10.0, 0.2, 0.2}}, {}}})});
  MeshOptions options;
  options.max_segment = 2.5;
  const RoadMesh mesh = build_road_mesh(map, options);
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    if (mesh.info[i].lane_id != -2 || mesh.info[i].kind != SurfaceKind::kLane) {
      continue;
    }
    for (uint32_t v : mesh.triangles[i]) {
      const Vec3& p = mesh.vertices[v];
      if (std::abs(p.y + 3.5) < 1e-9 && p.z < 1e-12) {
        continue;  // the road-level foot of the curb face
      }
      CHECK(p.z == Approx(std::min(p.x, 10.0) / 10.0 * 0.2).margin(1e-9));
    }
  }
}

TEST_CASE("a lateral shape is followed across the lanes", "[xodr][mesh][shape]") {
  Road road = make_road("1", {geometry(0, 0, 0, 0, 30.0)},
                        {{1, LaneType::kDriving, 4.0}, {-1, LaneType::kDriving, 4.0}});
  // A crown: 0 at the road edges (t = -4 and 4), 0.6 m at the middle (§8.4.3).
  road.shapes.push_back(ShapeRecord{0.0, -4.0, 0.0, 0.3, -0.0375, 0.0});
  const Map map = build({road});
  for (double tolerance : {0.1, 0.02}) {
    INFO("tolerance " << tolerance);
    MeshOptions options;
    options.tolerance = tolerance;
    const RoadMesh mesh = build_road_mesh(map, options);
    double worst = 0.0;
    for (double s = 0.5; s < 30.0; s += 1.7) {
      for (double t = -3.95; t < 3.95; t += 0.13) {
        const WorldPose p = map.world_pose(0, s, t);
        bool covered = false;
        for (size_t i = 0; i < mesh.triangles.size() && !covered; ++i) {
          const auto& tri = mesh.triangles[i];
          double z = 0.0;
          if (mesh.info[i].kind == SurfaceKind::kLane &&
              z_at(mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]], p.x, p.y,
                   z)) {
            covered = true;
            worst = std::max(worst, std::abs(z - p.z));
          }
        }
        REQUIRE(covered);
      }
    }
    CHECK(worst <= tolerance + 1e-9);
  }
}

TEST_CASE("zero-width lanes make no triangles and their neighbours share an edge", "[xodr][mesh]") {
  const Map map = build({make_road("1", {geometry(0, 0, 0, 0, 50.0)},
                                   {{-1, LaneType::kDriving, 3.5},
                                    {-2, LaneType::kShoulder, 0.0},
                                    {-3, LaneType::kDriving, 3.0}})});
  const RoadMesh mesh = build_road_mesh(map);
  for (const TriangleInfo& info : mesh.info) {
    CHECK(info.lane_id != -2);
  }
  size_t shared = 0;
  for (const auto& [edge, count] : edge_counts(mesh, [](const TriangleInfo&) { return true; })) {
    shared += count == 2 ? 1 : 0;
  }
  CHECK(shared == 3);  // two diagonals and the border between lanes -1 and -3
}

TEST_CASE("a lane that opens from zero width starts with a single triangle", "[xodr][mesh]") {
  const Map map =
      build({make_road("1", {geometry(0, 0, 0, 0, 50.0)},
                       {{-1, LaneType::kDriving, 3.5},
                        {-2, LaneType::kDriving, 0.0, {Poly3{0.0, 0.0, 0.1, 0.0, 0.0}}, {}, {}}})});
  const RoadMesh mesh = build_road_mesh(map);
  size_t opening = 0;
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    if (mesh.info[i].lane_id != -2) {
      continue;
    }
    const auto& t = mesh.triangles[i];
    const Vec3& a = mesh.vertices[t[0]];
    const Vec3& b = mesh.vertices[t[1]];
    const Vec3& c = mesh.vertices[t[2]];
    CHECK(area2_xy(a, b, c) > 0.0);
    opening += (a.x == 0.0 || b.x == 0.0 || c.x == 0.0) ? 1 : 0;
  }
  CHECK(opening == 1);
}

TEST_CASE("a kink between planView records gets a wedge, not a fold", "[xodr][mesh][kink]") {
  const double turn = 0.3;
  corsa::Diagnostics diagnostics;
  const Map map =
      build({make_road("1", {geometry(0, 0, 0, 0, 50.0), geometry(50.0, 50.0, 0.0, turn, 50.0)},
                       four_lanes())},
            diagnostics);
  corsa::Diagnostics mesh_warnings;
  const RoadMesh mesh = build_road_mesh(map, MeshOptions{}, mesh_warnings);
  CHECK(mesh_warnings.size() == 0);
  // A straight road on either side: few triangles, not a pile of slivers at the joint.
  CHECK(mesh.info.size() <= 4 * 2 * 4);
  // The outer side of the turn (right, -t) is covered between the two straight parts.
  for (double r : {2.0, 5.0, 6.8}) {
    const double angle = -std::numbers::pi / 2.0 + turn / 2.0;
    const double x = 50.0 + r * std::cos(angle);
    const double y = r * std::sin(angle);
    bool covered = false;
    for (const auto& t : mesh.triangles) {
      double z = 0.0;
      covered =
          covered || z_at(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], x, y, z);
    }
    INFO("r " << r);
    CHECK(covered);
  }
}

TEST_CASE("a sideways jump of the lanes leaves a gap, not slivers", "[xodr][mesh][jump]") {
  Road road = make_road("1", {geometry(0, 0, 0, 0, 100.0)}, four_lanes());
  road.lane_offsets = {Poly3{0.0, 0.0, 0, 0, 0}, Poly3{50.0, 2.0, 0, 0, 0}};
  const Map map = build({road});
  corsa::Diagnostics warnings;
  const RoadMesh mesh = build_road_mesh(map, MeshOptions{}, warnings);
  CHECK(warnings.size() == 0);
  for (const auto& t : mesh.triangles) {
    const Vec3& a = mesh.vertices[t[0]];
    const Vec3& b = mesh.vertices[t[1]];
    const Vec3& c = mesh.vertices[t[2]];
    const double longest = std::max({distance(a, b), distance(b, c), distance(c, a)});
    CHECK(area2_xy(a, b, c) / longest > 1e-3);  // no triangle thinner than a millimetre
  }
  CHECK(mesh.info.size() == 2 * 8);  // 4 lanes x 2 triangles on each side of the jump
}

TEST_CASE("a border beyond the centre of curvature is left out with a warning",
          "[xodr][mesh][fold]") {
  const Map map = build({make_road("tight", {geometry(0, 0, 0, 0, 20.0, ArcGeometry{0.2})},
                                   {{2, LaneType::kSidewalk, 3.0},
                                    {1, LaneType::kDriving, 3.5},
                                    {-1, LaneType::kDriving, 3.5}})});
  corsa::Diagnostics warnings;
  const RoadMesh mesh = build_road_mesh(map, MeshOptions{}, warnings);
  REQUIRE(warnings.size() == 1);
  CHECK_THAT(warnings.all()[0].message, Catch::Contains("folds over itself"));
  CHECK(warnings.all()[0].file == "memory.xodr");
  for (const auto& t : mesh.triangles) {
    CHECK(area2_xy(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]) > 0.0);
  }
}
