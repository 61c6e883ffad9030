// Lane links across sections, road links and junctions; neighbours; travel directions.

#include "corsa/xodr/lane_graph.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "corsa/xodr/map.h"
#include "xodr_test_util.h"

using namespace corsa::xodr;

namespace {

/// World position of a lane end (its centre at the section start or end).
WorldPose end_point(const Map& map, const LaneEnd& end) {
  const auto& info = map.lane_graph().info(end.node);
  const double s = end.at_start ? info.s_start : info.s_end;
  const auto span = map.lane_span_in_section(info.lane.road, info.lane.section, s, info.lane.lane);
  return map.world_pose(info.lane.road, s, span ? span->t_center() : 0.0);
}

}  // namespace

TEST_CASE("lanes continue across lane sections", "[xodr][graph]") {
  const Map map = test::load_map(test::shared_map("two_plus_one.xodr"));
  const LaneGraph& graph = map.lane_graph();
  const auto first = graph.find(LaneRef{0, 0, -1});
  REQUIRE(first);
  const auto next = graph.successors(*first);
  REQUIRE_FALSE(next.empty());
  CHECK(graph.info(next[0].node).lane.section == 1);
  CHECK(next[0].at_start);
  // Joins are symmetric: the successor's predecessors include us.
  bool back = false;
  for (const LaneEnd& end : graph.predecessors(next[0].node)) {
    back = back || (end.node == *first && !end.at_start);
  }
  CHECK(back);
  CHECK(graph.info(*first).direction == TravelDirection::kForward);
  CHECK(graph.info(*graph.find(LaneRef{0, 0, 1})).direction == TravelDirection::kBackward);
}

TEST_CASE("neighbours skip the centre lane", "[xodr][graph]") {
  const Map map = test::load_map(test::shared_map("straight_500m.xodr"));
  const LaneGraph& graph = map.lane_graph();
  const LaneNode right1 = *graph.find(LaneRef{0, 0, -1});
  const LaneNode left1 = *graph.find(LaneRef{0, 0, 1});
  CHECK(graph.left(right1) == left1);
  CHECK(graph.right(left1) == right1);
  const LaneNode right2 = graph.right(right1);
  REQUIRE(right2 != kNoLane);
  CHECK(graph.info(right2).lane.lane == -2);
  CHECK_FALSE(graph.find(LaneRef{0, 0, 0}).has_value());
  CHECK_FALSE(graph.find(LaneRef{0, 5, -1}).has_value());
}

TEST_CASE("junction connections join incoming lanes to connecting roads",
          "[xodr][graph][junction]") {
  // Joined lane ends meet in the world wherever the file is consistent. Where it is not, the
  // graph still follows the file's links: CARLA's Town03 shifts lanes sideways at some section
  // boundaries (lane -1 continues as lane -4 when 4.5 m of "none" lanes appear); the ASAM
  // slip-lane example's direct junction 6 links road 95 to the far side of road 86; in the LHT
  // example road 3's geometry runs against its links (it starts at the far end, so its lane -1
  // lies where the connecting roads' lane 1 mirror would be): 3 lane links, 6 lane ends.
  struct Case {
    const char* name;
    size_t max_apart;
  };
  for (const Case c : {Case{"fabriksgatan.xodr", 0}, Case{"Ex_Slip_Lane.xodr", 4},
                       Case{"Ex_LHT-Complex-X-Junction.xodr", 6}, Case{"Town03.xodr", 160}}) {
    INFO(c.name);
    const Map map = test::load_map(test::shared_map(c.name));
    const LaneGraph& graph = map.lane_graph();
    size_t into_junction = 0;
    size_t joins = 0;
    size_t apart = 0;
    for (LaneNode node = 0; node < graph.size(); ++node) {
      for (const bool at_start : {true, false}) {
        for (const LaneEnd& end : graph.ends(node, at_start)) {
          ++joins;
          const bool here = map.road(graph.info(node).lane.road).in_junction();
          const bool there = map.road(graph.info(end.node).lane.road).in_junction();
          into_junction += !here && there ? 1 : 0;
          const WorldPose a = end_point(map, LaneEnd{node, at_start});
          const WorldPose b = end_point(map, end);
          apart += std::hypot(a.x - b.x, a.y - b.y) > 0.5 ? 1 : 0;
          // Every join is recorded at both ends.
          const auto back = graph.ends(end.node, end.at_start);
          CHECK(std::find(back.begin(), back.end(), LaneEnd{node, at_start}) != back.end());
        }
      }
    }
    CHECK(joins == 2 * graph.join_count());
    CHECK(apart <= c.max_apart);
    CHECK(into_junction + (std::string(c.name) == "Ex_Slip_Lane.xodr" ? 1 : 0) > 0);
  }
}

TEST_CASE("lane lengths follow the lane centre", "[xodr][graph]") {
  const Map map = test::load_map(test::shared_map("straight_500m.xodr"));
  const LaneGraph& graph = map.lane_graph();
  const auto node = graph.find(LaneRef{0, 0, -1});
  REQUIRE(node);
  CHECK(graph.info(*node).length == Approx(map.road(0).length).margin(1e-6));
  // On an arc of curvature k a lane at constant t has length L (1 - k t).
  MapData data;
  data.roads.push_back(test::make_road("arc", ArcGeometry{0.01}, 100.0, 1, 3.0));
  corsa::Diagnostics diagnostics;
  const Map arc = Map::build(std::move(data), diagnostics);
  const LaneGraph& arc_graph = arc.lane_graph();
  CHECK(arc_graph.info(*arc_graph.find(LaneRef{0, 0, 1})).length ==
        Approx(100.0 * (1.0 - 0.01 * 1.5)).epsilon(1e-5));
  CHECK(arc_graph.info(*arc_graph.find(LaneRef{0, 0, -1})).length ==
        Approx(100.0 * (1.0 + 0.01 * 1.5)).epsilon(1e-5));
}
