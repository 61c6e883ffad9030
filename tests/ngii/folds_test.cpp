// Roads whose lane borders fold over themselves (mesh_folds.h), on small synthetic layers: each
// case is one cause that folded roads of the sample areas.

#include <catch2/catch.hpp>
#include <cmath>
#include <variant>

#include "corsa/ngii/convert.h"
#include "corsa/xodr/map.h"
#include "mesh_folds.h"

namespace {

using corsa::ngii::Layers;
using corsa::ngii::Link;
using corsa::ngii::Node;
using corsa::ngii::Point3;

/// One ordinary lane along `points` (UTM-like coordinates), its two end nodes.
Layers one_lane(std::vector<Point3> points) {
  Layers layers;
  layers.node_file = "A1_NODE.dbf";
  layers.link_file = "A2_LINK.dbf";
  layers.nodes.push_back(
      Node{.id = "N1", .node_type = "99", .position = points.front(), .record = 0});
  layers.nodes.push_back(
      Node{.id = "N2", .node_type = "99", .position = points.back(), .record = 1});
  Link link{.id = "A2TEST000001",
            .link_type = "6",
            .road_rank = "",
            .road_type = "1",
            .road_no = "",
            .lane_no = 1,
            .max_speed = 0,
            .right_id = "",
            .left_id = "",
            .from_node = "N1",
            .to_node = "N2",
            .length_attr = 0.0,
            .points = std::move(points),
            .record = 0};
  for (size_t i = 1; i < link.points.size(); ++i) {
    link.length_attr += std::hypot(link.points[i].x - link.points[i - 1].x,
                                   link.points[i].y - link.points[i - 1].y);
  }
  layers.links.push_back(std::move(link));
  return layers;
}

/// Smallest curvature (1/m, most negative: the tightest right turn) of the road's records.
double tightest_right_turn(const corsa::xodr::Road& road) {
  double k = 0.0;
  for (const auto& g : road.plan_view) {
    if (const auto* arc = std::get_if<corsa::xodr::ArcGeometry>(&g.shape)) {
      k = std::min(k, arc->curvature);
    } else if (const auto* spiral = std::get_if<corsa::xodr::SpiralGeometry>(&g.shape)) {
      k = std::min({k, spiral->curv_start, spiral->curv_end});
    }
  }
  return k;
}

}  // namespace

TEST_CASE("a lane over a survey jog of a few centimetres does not fold its right edge",
          "[ngii][folds]") {
  // A straight lane surveyed every 0.4 m whose vertices step 20 cm to the left between two
  // of them (a digitising jog as in K-City's A219BS010004). The plan-view records that meet
  // the data heading right after the step swing the curvature to -0.5 1/m and back: the
  // right edge of the 3.25 m lane lay beyond the centre of curvature there.
  std::vector<Point3> points;
  const double x0 = 300000.0, y0 = 4100000.0;
  for (int i = 0; i <= 112; ++i) {
    const double u = 0.4 * i;
    points.push_back({x0 + u, y0 + (u > 15.0 ? 0.2 : 0.0), 50.0});
  }
  corsa::Diagnostics diagnostics;
  const auto conversion = corsa::ngii::convert(one_lane(points), {}, diagnostics);
  const auto map = corsa::xodr::Map::build(conversion.map, diagnostics);
  REQUIRE(conversion.map.roads.size() == 1);
  const auto& road = conversion.map.roads.front();
  INFO("tightest right turn " << tightest_right_turn(road));
  CHECK(tightest_right_turn(road) > -1.0 / 3.25);
  CHECK(corsa::test::folded_roads(map) == 0);
  // The lane still follows the survey (the laneOffset takes up the eased reference line).
  CHECK(conversion.summary.max_lane_error <= 0.05);
}
