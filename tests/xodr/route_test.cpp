// Shortest routes over the lane graph.

#include "corsa/xodr/route.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "corsa/xodr/lane_graph.h"
#include "xodr_test_util.h"

using namespace corsa::xodr;

namespace {

Map straight_road() {
  MapData data;
  data.roads.push_back(test::make_road("r", LineGeometry{}, 500.0, 2, 3.5));
  corsa::Diagnostics diagnostics;
  return Map::build(std::move(data), diagnostics);
}

WorldPose lane_point(const Map& map, const LaneRef& lane, double s) {
  const auto span = map.lane_span_in_section(lane.road, lane.section, s, lane.lane);
  return map.world_pose(lane.road, s, span ? span->t_center() : 0.0);
}

/// Every step follows from the previous one: a lane change to an adjacent lane at the same s,
/// or a join of the lanes' ends in the lane graph (which, in a consistent file, is the same
/// place in the world). Returns the largest world gap between steps.
double check_continuous(const Map& map, const Route& route) {
  const LaneGraph& graph = map.lane_graph();
  double largest = 0.0;
  for (size_t i = 1; i < route.steps.size(); ++i) {
    const RouteStep& a = route.steps[i - 1];
    const RouteStep& b = route.steps[i];
    const LaneNode from = *graph.find(a.lane);
    const LaneNode to = *graph.find(b.lane);
    if (b.lane_change) {
      CHECK((graph.left(from) == to || graph.right(from) == to));
      CHECK(a.s_to == b.s_from);
    } else {
      const bool forward = a.s_to >= a.s_from && a.s_to == graph.info(from).s_end;
      const auto ends = graph.ends(from, !forward);
      const bool b_start = b.s_from == graph.info(to).s_start;
      CHECK(std::find(ends.begin(), ends.end(), LaneEnd{to, b_start}) != ends.end());
    }
    const WorldPose pa = lane_point(map, a.lane, a.s_to);
    const WorldPose pb = lane_point(map, b.lane, b.s_from);
    largest = std::max(largest, std::hypot(pa.x - pb.x, pa.y - pb.y));
  }
  return largest;
}

}  // namespace

TEST_CASE("a route along one lane is the distance driven", "[xodr][route]") {
  const Map map = straight_road();
  const auto route = find_route(map, LanePoint{0, -1, 10.0}, LanePoint{0, -1, 400.0});
  REQUIRE(route);
  CHECK(route->length == Approx(390.0).margin(1e-6));
  CHECK(route->lane_changes == 0);
  REQUIRE(route->steps.size() == 1);
  CHECK(route->steps[0].s_from == Approx(10.0));
  CHECK(route->steps[0].s_to == Approx(400.0));
}

TEST_CASE("left lanes are driven against s under right-hand traffic", "[xodr][route]") {
  const Map map = straight_road();
  const auto route = find_route(map, LanePoint{0, 1, 400.0}, LanePoint{0, 1, 10.0});
  REQUIRE(route);
  CHECK(route->length == Approx(390.0).margin(1e-6));
  CHECK(route->steps.front().s_from > route->steps.front().s_to);
  // Backwards along a one-way lane there is no way.
  CHECK_FALSE(find_route(map, LanePoint{0, -1, 400.0}, LanePoint{0, -1, 10.0}).has_value());
  CHECK_FALSE(find_route(map, LanePoint{0, 1, 10.0}, LanePoint{0, 1, 400.0}).has_value());
  // Unless driving against the direction of travel is allowed.
  RouteOptions wrong_way;
  wrong_way.against_traffic = true;
  const auto against = find_route(map, LanePoint{0, 1, 10.0}, LanePoint{0, 1, 400.0}, wrong_way);
  REQUIRE(against);
  CHECK(against->length == Approx(390.0).margin(1e-6));
  REQUIRE(against->steps.size() == 1);
  CHECK(against->steps[0].s_from == Approx(10.0));
  CHECK(against->steps[0].s_to == Approx(400.0));
}

TEST_CASE("routes change to adjacent lanes of the same direction", "[xodr][route]") {
  const Map map = straight_road();
  const auto route = find_route(map, LanePoint{0, -1, 10.0}, LanePoint{0, -2, 400.0});
  REQUIRE(route);
  CHECK(route->lane_changes == 1);
  CHECK(route->length == Approx(390.0).margin(1e-6));
  REQUIRE(route->steps.size() == 2);
  CHECK(route->steps[1].lane_change);
  CHECK(route->steps[1].lane.lane == -2);
  CHECK(check_continuous(map, *route) == Approx(3.5));  // the lane change itself
  RouteOptions no_changes;
  no_changes.allow_lane_changes = false;
  CHECK_FALSE(find_route(map, LanePoint{0, -1, 10.0}, LanePoint{0, -2, 400.0}, no_changes));
  // Never across the centre line into oncoming traffic.
  CHECK_FALSE(find_route(map, LanePoint{0, -1, 10.0}, LanePoint{0, 1, 5.0}).has_value());
}

TEST_CASE("a route crosses Town03", "[xodr][route][town03]") {
  const Map map = test::load_map(test::shared_map("Town03.xodr"));
  const LaneGraph& graph = map.lane_graph();
  // From the first driving lane outside junctions to the one farthest from it.
  LaneNode start = kNoLane;
  LaneNode target = kNoLane;
  double farthest = 0.0;
  for (LaneNode node = 0; node < graph.size(); ++node) {
    const auto& info = graph.info(node);
    if (info.type != LaneType::kDriving || map.road(info.lane.road).in_junction() ||
        info.length < 20.0) {
      continue;
    }
    if (start == kNoLane) {
      start = node;
      continue;
    }
    const WorldPose a = lane_point(map, graph.info(start).lane, graph.info(start).s_start + 5.0);
    const WorldPose b = lane_point(map, info.lane, info.s_start + 5.0);
    if (std::hypot(a.x - b.x, a.y - b.y) > farthest) {
      farthest = std::hypot(a.x - b.x, a.y - b.y);
      target = node;
    }
  }
  REQUIRE(target != kNoLane);
  CHECK(farthest > 200.0);
  const auto mid = [&](LaneNode n) {
    const auto& info = graph.info(n);
    return LanePoint{info.lane.road, info.lane.lane, 0.5 * (info.s_start + info.s_end)};
  };
  const auto route = find_route(map, mid(start), mid(target));
  REQUIRE(route);
  CHECK(route->length >= farthest - 1.0);
  CHECK(route->length < 5.0 * farthest);
  CHECK(route->steps.size() > 3);
  CHECK(route->steps.front().lane == graph.info(start).lane);
  CHECK(route->steps.back().lane == graph.info(target).lane);
  CHECK(route->steps.back().s_to == Approx(mid(target).s));
  size_t junction_steps = 0;
  for (const RouteStep& step : route->steps) {
    CHECK(is_drivable(map.lane(step.lane)->type));
    junction_steps += map.road(step.lane.road).in_junction() ? 1 : 0;
  }
  CHECK(junction_steps > 0);
  // Town03 shifts some lanes sideways at section boundaries (up to 4.5 m); nothing more.
  CHECK(check_continuous(map, *route) < 5.0);
}
