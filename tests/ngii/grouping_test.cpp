// Side-by-side lanes inside a junction on small synthetic layers: an ordinary run of lanes that a
// junction takes in whole stays one connecting road of several lanes where its lanes lead into
// one road (network_plan.h). A lane of the run fed by another road joins it through a second
// <connection> (OpenDRIVE 1.8, the default); for output that keeps one <connection> per
// connecting road (OpenDRIVE 1.7, `--compat 1.4`) it stays a connecting road of its own.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "corsa/ngii/convert.h"
#include "corsa/xodr/lane_graph.h"
#include "corsa/xodr/map.h"
#include "synthetic_layers.h"

namespace {

constexpr double kGroupingX0 = 310000.0, kGroupingY0 = 4110000.0;

struct GroupingLayers : corsa::ngii::testing::SyntheticLayers {
  GroupingLayers() : SyntheticLayers(kGroupingX0, kGroupingY0, 40.0) {}
};

/// Eastbound: a three-lane approach (lanes 3.5 m apart, y = 0, -3.5, -7) ending at x = 30, a
/// one-lane road coming in from the south-west beside its end (y = -10.5), a 7 m four-lane run (x
/// = 30..37, LaneNo 1-4) continuing them, and a four-lane exit road from x = 37. A junction path
/// also turns left off the approach's first lane, so the approach's end leads into a junction and
/// straight on: the short run joins that junction whole.
GroupingLayers run_in_junction() {
  GroupingLayers g;
  const std::vector<double> ys = {0.0, -3.5, -7.0, -10.5};
  for (size_t k = 0; k < ys.size(); ++k) {
    const std::string n = std::to_string(k + 1);
    // The road beside the approach comes in at an angle from the south-west (another road).
    g.node("S" + n, k < 3 ? 0.0 : 6.0, k < 3 ? ys[k] : -25.0);
    g.node("M" + n, 30.0, ys[k]);
    g.node("R" + n, 37.0, ys[k]);
    g.node("E" + n, 80.0, ys[k]);
  }
  g.node("N0", 45.0, 15.0);
  g.node("N1", 45.0, 60.0);
  const auto id = [](const std::string& road, size_t k) {
    return "A2TEST" + road + "0000" + std::to_string(k + 1);
  };
  for (size_t k = 0; k < ys.size(); ++k) {
    const std::string n = std::to_string(k + 1);
    const int lane_no = static_cast<int>(k) + 1;
    const std::string right_run = k + 1 < ys.size() ? id("RN", k + 1) : "";
    const std::string left_run = k > 0 ? id("RN", k - 1) : "";
    const std::string right_exit = k + 1 < ys.size() ? id("EX", k + 1) : "";
    const std::string left_exit = k > 0 ? id("EX", k - 1) : "";
    if (k < 3) {  // the three-lane approach
      const std::string right = k + 1 < 3 ? id("AP", k + 1) : "";
      const std::string left = k > 0 ? id("AP", k - 1) : "";
      g.link(id("AP", k), "6", lane_no, "S" + n, "M" + n, right, left);
    } else {  // the one-lane road beside it
      g.link(id("SD", 0), "6", 1, "S" + n, "M" + n);
    }
    g.link(id("RN", k), "6", lane_no, "M" + n, "R" + n, right_run, left_run);
    g.link(id("EX", k), "6", lane_no, "R" + n, "E" + n, right_exit, left_exit);
  }
  g.link("A2TESTTURN001", "1", 1, "M1", "N0");
  g.link("A2TESTNRTH001", "6", 1, "N0", "N1");
  return g;
}

const corsa::ngii::LinkPlacement& placement_of(const corsa::ngii::Conversion& conversion,
                                               const std::string& link) {
  const auto it =
      std::find_if(conversion.placements.begin(), conversion.placements.end(),
                   [&](const corsa::ngii::LinkPlacement& p) { return p.link_id == link; });
  REQUIRE(it != conversion.placements.end());
  return *it;
}

const corsa::xodr::Road& road_of(const corsa::ngii::Conversion& conversion, const std::string& id) {
  const auto& roads = conversion.map.roads;
  const auto it =
      std::find_if(roads.begin(), roads.end(), [&](const auto& r) { return r.id == id; });
  REQUIRE(it != roads.end());
  return *it;
}

}  // namespace

TEST_CASE("with one connection per connecting road a run's lane fed by another road stays apart",
          "[ngii][grouping][junction]") {
  const GroupingLayers g = run_in_junction();
  corsa::Diagnostics diagnostics;
  corsa::ngii::ConvertOptions options;
  options.several_incoming_roads = false;
  const corsa::ngii::Conversion conversion = corsa::ngii::convert(g.layers, options, diagnostics);
  const auto& first = placement_of(conversion, "A2TESTRN00001");
  const corsa::xodr::Road& run = road_of(conversion, first.road_id);
  CHECK(run.junction != "-1");
  const auto& approach = placement_of(conversion, "A2TESTAP00001");
  const auto& exit = placement_of(conversion, "A2TESTEX00001");
  CHECK(run.predecessor.element_id == approach.road_id);
  CHECK(run.successor.element_id == exit.road_id);
  // The three lanes fed by the approach: one road, lanes -1..-3 left to right, each linked to
  // the approach's lane beside it before and to the exit's after it.
  const auto& lanes = run.lane_sections.front().lanes;
  for (int k = 0; k < 3; ++k) {
    const auto& p = placement_of(conversion, "A2TESTRN0000" + std::to_string(k + 1));
    CHECK(p.road_id == run.id);
    CHECK(p.lane_id == -k - 1);
    const auto lane =
        std::find_if(lanes.begin(), lanes.end(), [&](const auto& l) { return l.id == -k - 1; });
    REQUIRE(lane != lanes.end());
    CHECK(lane->predecessors == std::vector<int>{-k - 1});
    CHECK(lane->successors == std::vector<int>{-k - 1});
    CHECK(std::count_if(lane->user_data.begin(), lane->user_data.end(), [&](const auto& d) {
            return d.code == "ngii:link" && d.value == p.link_id;
          }) == 1);
  }
  // One connection from the approach, a laneLink per lane.
  std::vector<const corsa::xodr::Connection*> connections;
  for (const auto& junction : conversion.map.junctions) {
    for (const auto& c : junction.connections) {
      if (c.connecting_road == run.id) {
        connections.push_back(&c);
        CHECK(junction.id == run.junction);
      }
    }
  }
  REQUIRE(connections.size() == 1);
  CHECK(connections.front()->incoming_road == approach.road_id);
  CHECK(connections.front()->lane_links.size() == 3);
  // The fourth lane comes from the road beside the approach: a connecting road of its own in
  // the same junction, into the same exit road.
  const auto& fourth = placement_of(conversion, "A2TESTRN00004");
  CHECK(fourth.road_id != run.id);
  const corsa::xodr::Road& alone = road_of(conversion, fourth.road_id);
  CHECK(alone.junction == run.junction);
  CHECK(alone.predecessor.element_id == placement_of(conversion, "A2TESTSD00001").road_id);
  CHECK(alone.successor.element_id == exit.road_id);
  // In the lane graph a vehicle can change between the run's lanes, and drives on from each.
  const corsa::xodr::Map map = corsa::xodr::Map::build(conversion.map, diagnostics);
  const auto road = map.find_road(run.id);
  REQUIRE(road);
  const auto node = [&](int lane) {
    const auto n =
        map.lane_graph().find(corsa::xodr::LaneRef{static_cast<uint32_t>(*road), 0, lane});
    REQUIRE(n);
    return *n;
  };
  CHECK(map.lane_graph().left(node(-2)) == node(-1));
  CHECK(map.lane_graph().right(node(-2)) == node(-3));
  for (const int lane : {-1, -2, -3}) {
    CHECK(map.lane_graph().predecessors(node(lane)).size() == 1);
    CHECK(map.lane_graph().successors(node(lane)).size() == 1);
  }
  CHECK(diagnostics.count(corsa::Severity::kWarning) == 0);
}

TEST_CASE("a run of lanes a junction takes in whole is one connecting road fed by each road",
          "[ngii][grouping][junction]") {
  const GroupingLayers g = run_in_junction();
  corsa::Diagnostics diagnostics;
  const corsa::ngii::Conversion conversion = corsa::ngii::convert(g.layers, {}, diagnostics);
  const auto& first = placement_of(conversion, "A2TESTRN00001");
  const corsa::xodr::Road& run = road_of(conversion, first.road_id);
  CHECK(run.junction != "-1");
  const auto& approach = placement_of(conversion, "A2TESTAP00001");
  const auto& beside = placement_of(conversion, "A2TESTSD00001");
  const auto& exit = placement_of(conversion, "A2TESTEX00001");
  CHECK(beside.road_id != approach.road_id);
  // The road has one road before it (the approach) and one after it (the exit).
  CHECK(run.predecessor.element_id == approach.road_id);
  CHECK(run.successor.element_id == exit.road_id);
  // All four lanes in it, left to right; the fourth, fed by the road beside the approach, has
  // no lane predecessor (its road's predecessor is the approach) but leads into the exit's.
  const auto& lanes = run.lane_sections.front().lanes;
  for (int k = 0; k < 4; ++k) {
    const auto& p = placement_of(conversion, "A2TESTRN0000" + std::to_string(k + 1));
    CHECK(p.road_id == run.id);
    CHECK(p.lane_id == -k - 1);
    const auto lane =
        std::find_if(lanes.begin(), lanes.end(), [&](const auto& l) { return l.id == -k - 1; });
    REQUIRE(lane != lanes.end());
    CHECK(lane->predecessors == (k < 3 ? std::vector<int>{-k - 1} : std::vector<int>{}));
    CHECK(lane->successors == std::vector<int>{-k - 1});
  }
  // Two connections into it, one per incoming road (OpenDRIVE 1.8 §12.4): the approach's three
  // lanes, and the road beside it into lane -4.
  std::vector<const corsa::xodr::Connection*> connections;
  for (const auto& junction : conversion.map.junctions) {
    for (const auto& c : junction.connections) {
      if (c.connecting_road == run.id) {
        connections.push_back(&c);
        CHECK(junction.id == run.junction);
      }
    }
  }
  REQUIRE(connections.size() == 2);
  CHECK(connections[0]->incoming_road == approach.road_id);
  CHECK(connections[0]->lane_links.size() == 3);
  CHECK(connections[1]->incoming_road == beside.road_id);
  REQUIRE(connections[1]->lane_links.size() == 1);
  CHECK(connections[1]->lane_links.front().from == beside.lane_id);
  CHECK(connections[1]->lane_links.front().to == -4);
  // In the lane graph the road beside leads into lane -4, a vehicle may change between all four
  // lanes, and each drives on into the exit.
  const corsa::xodr::Map map = corsa::xodr::Map::build(conversion.map, diagnostics);
  const auto node = [&](const std::string& road_id, int lane) {
    const auto road = map.find_road(road_id);
    REQUIRE(road);
    const auto n =
        map.lane_graph().find(corsa::xodr::LaneRef{static_cast<uint32_t>(*road), 0, lane});
    REQUIRE(n);
    return *n;
  };
  const auto fourth = node(run.id, -4);
  const auto before_fourth = map.lane_graph().predecessors(fourth);
  REQUIRE(before_fourth.size() == 1);
  CHECK(before_fourth.front().node == node(beside.road_id, beside.lane_id));
  CHECK(map.lane_graph().left(fourth) == node(run.id, -3));
  CHECK(map.lane_graph().right(node(run.id, -3)) == fourth);
  for (const int lane : {-1, -2, -3, -4}) {
    CHECK(map.lane_graph().predecessors(node(run.id, lane)).size() == 1);
    CHECK(map.lane_graph().successors(node(run.id, lane)).size() == 1);
  }
  CHECK(diagnostics.count(corsa::Severity::kWarning) == 0);
}
