// Lane connectivity of the converted maps against the A1/A2 topology: every pair of links that
// meet at a node (A.ToNodeID == B.FromNodeID) is joined in the map's lane graph, and every join
// between two roads' lanes is such a pair.

#include <algorithm>
#include <catch2/catch.hpp>
#include <map>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "corsa/xodr/lane_graph.h"
#include "ngii_areas.h"

using corsa::test::converted;
using corsa::test::ConvertedArea;

namespace {

using Placement = corsa::ngii::LinkPlacement;

struct Topology {
  const ConvertedArea& area;
  std::unordered_map<std::string, std::vector<const Placement*>> placements;
  std::unordered_map<std::string, const corsa::ngii::Link*> links;
  std::map<std::string, std::string> node_alias;  // merged node -> kept node (zero-length links)

  explicit Topology(const ConvertedArea& a) : area(a) {
    for (const auto& p : a.conversion.placements) {
      placements[p.link_id].push_back(&p);
    }
    for (const auto& link : a.layers.links) {
      links[link.id] = &link;
    }
    for (const auto& c : a.conversion.corrections) {
      if (c.field == "geometry" && c.new_value == "removed") {
        const auto* link = links.at(c.link_id);
        if (link->to_node != link->from_node) {
          node_alias[link->to_node] = link->from_node;
        }
      }
    }
  }

  std::string node(std::string id) const {
    for (auto it = node_alias.find(id); it != node_alias.end(); it = node_alias.find(id)) {
      id = it->second;
    }
    return id;
  }
  /// Links folded into a node (zero length) have no lane.
  bool removed(const std::string& id) const { return !placements.contains(id); }

  corsa::xodr::LaneNode lane_node(const Placement& p) const {
    const auto road = area.map.find_road(p.road_id);
    const auto node = area.map.lane_graph().find(
        corsa::xodr::LaneRef{static_cast<uint32_t>(*road), 0, p.lane_id});
    return node ? *node : corsa::xodr::kNoLane;
  }
  double road_length(const Placement& p) const {
    return area.map.road(*area.map.find_road(p.road_id)).length;
  }

  /// Whether some placement of `a` continues into some placement of `b`: inside one lane, or
  /// from the end of a lane to the start of the lane that succeeds it in the lane graph.
  bool joined(const std::string& a, const std::string& b) const {
    for (const Placement* pa : placements.at(a)) {
      for (const Placement* pb : placements.at(b)) {
        if (pa->road_id == pb->road_id && pa->lane_id == pb->lane_id &&
            std::abs(pa->s_end - pb->s_start) < 0.5) {
          return true;
        }
        if (std::abs(pa->s_end - road_length(*pa)) > 0.5 || pb->s_start > 0.5) {
          continue;
        }
        for (const auto& end : area.map.lane_graph().successors(lane_node(*pa))) {
          if (end.node == lane_node(*pb) && end.at_start) {
            return true;
          }
        }
      }
    }
    return false;
  }
};

}  // namespace

TEST_CASE("every pair of links meeting at a node is joined in the lane graph",
          "[ngii][convert][topology]") {
  for (const char* name : {"kcity", "seoul_sangam_testbed"}) {
    INFO(name);
    const Topology topology(converted(name));
    std::unordered_map<std::string, std::vector<const corsa::ngii::Link*>> starting;
    for (const auto& link : topology.area.layers.links) {
      if (!topology.removed(link.id)) {
        starting[topology.node(link.from_node)].push_back(&link);
      }
    }
    size_t pairs = 0;
    std::vector<std::string> missing;
    for (const auto& link : topology.area.layers.links) {
      if (topology.removed(link.id)) {
        continue;
      }
      for (const auto* next : starting[topology.node(link.to_node)]) {
        ++pairs;
        if (!topology.joined(link.id, next->id)) {
          missing.push_back(link.id + " -> " + next->id);
        }
      }
    }
    INFO(missing.size() << " missing; first: "
                        << (missing.empty() ? std::string("none") : missing.front()));
    CHECK(pairs > 500);
    CHECK(missing.empty());
    for (const auto& m : missing) {
      WARN(m);
    }
  }
}

TEST_CASE("every join between two roads' lanes is a pair of links meeting at a node",
          "[ngii][convert][topology]") {
  for (const char* name : {"kcity", "seoul_sangam_testbed"}) {
    INFO(name);
    const Topology topology(converted(name));
    const auto& graph = topology.area.map.lane_graph();
    // The link at each end of every lane (first and last placement along it).
    std::map<corsa::xodr::LaneNode, std::pair<const Placement*, const Placement*>> ends;
    for (const auto& p : topology.area.conversion.placements) {
      auto& slot = ends[topology.lane_node(p)];
      if (slot.first == nullptr || p.s_start < slot.first->s_start) {
        slot.first = &p;
      }
      if (slot.second == nullptr || p.s_end > slot.second->s_end) {
        slot.second = &p;
      }
    }
    size_t joins = 0;
    std::vector<std::string> unexplained;
    for (const auto& [node, lane_ends] : ends) {
      for (const auto& end : graph.successors(node)) {
        if (!end.at_start || !ends.contains(end.node)) {
          continue;
        }
        ++joins;
        const auto& from = *topology.links.at(lane_ends.second->link_id);
        const auto& to = *topology.links.at(ends.at(end.node).first->link_id);
        const bool meet = topology.node(from.to_node) == topology.node(to.from_node);
        // A link cut in two (its start joined to a junction) continues into itself.
        if (!meet && from.id != to.id) {
          unexplained.push_back(from.id + " -> " + to.id);
        }
      }
    }
    INFO(
        "first unexplained: " << (unexplained.empty() ? std::string("none") : unexplained.front()));
    CHECK(joins > 500);
    CHECK(unexplained.empty());
  }
}

TEST_CASE("side-by-side links taken into a junction whole stay one connecting road of lanes",
          "[ngii][topology][grouping]") {
  // K-City: four ordinary 7 m links (LaneNo 1-4, a complete L/R chain) between two
  // intersections, taken into the junction whole. A219BS010309/322/321 continue one road's
  // three lanes, A219BS010320 continues another road (A219BS010440's): one four-lane
  // connecting road, fed by each road through a <connection> of its own (OpenDRIVE 1.8 §12.4).
  const ConvertedArea& area = converted("kcity");
  const Topology topology(area);
  const auto placed = [&](const std::string& link) -> const Placement& {
    REQUIRE(topology.placements.contains(link));
    REQUIRE(topology.placements.at(link).size() == 1);
    return *topology.placements.at(link).front();
  };
  const std::vector<std::string> run = {"A219BS010309", "A219BS010322", "A219BS010321",
                                        "A219BS010320"};
  const Placement& first = placed(run.front());
  const auto& roads = area.conversion.map.roads;
  const auto road = std::find_if(roads.begin(), roads.end(),
                                 [&](const auto& r) { return r.id == first.road_id; });
  REQUIRE(road != roads.end());
  CHECK(road->junction != "-1");
  CHECK(road->predecessor.element_type == corsa::xodr::LinkElement::kRoad);
  CHECK(road->successor.element_type == corsa::xodr::LinkElement::kRoad);
  const auto& lanes = road->lane_sections.front().lanes;
  for (size_t k = 0; k < run.size(); ++k) {
    INFO(run[k]);
    const Placement& p = placed(run[k]);
    CHECK(p.road_id == road->id);
    CHECK(p.lane_id == -static_cast<int>(k) - 1);
    // Each lane has its own lane links: the approach's lane before it, the exit's after it.
    const auto lane =
        std::find_if(lanes.begin(), lanes.end(), [&](const auto& l) { return l.id == p.lane_id; });
    REQUIRE(lane != lanes.end());
    // The fourth lane's road before it is not the road's predecessor: only its connection
    // names it.
    CHECK(lane->predecessors.size() == (k < 3 ? 1 : 0));
    CHECK(lane->successors.size() == 1);
    // In the lane graph: joined to the links before and after it, and a lane change away
    // from its neighbour in the run.
    const auto node = topology.lane_node(p);
    REQUIRE(node != corsa::xodr::kNoLane);
    CHECK(area.map.lane_graph().predecessors(node).size() == 1);
    CHECK(area.map.lane_graph().successors(node).size() == 1);
    if (k > 0) {
      CHECK(area.map.lane_graph().left(node) == topology.lane_node(placed(run[k - 1])));
    }
  }
  // Two connections: from the approach road a laneLink per lane of its three, and from
  // A219BS010440's road into lane -4.
  std::vector<const corsa::xodr::Connection*> connections;
  for (const auto& junction : area.conversion.map.junctions) {
    for (const auto& c : junction.connections) {
      if (c.connecting_road == road->id) {
        connections.push_back(&c);
        CHECK(junction.id == road->junction);
      }
    }
  }
  REQUIRE(connections.size() == 2);
  CHECK(connections[0]->incoming_road == road->predecessor.element_id);
  CHECK(connections[0]->lane_links.size() == 3);
  const Placement& feeder = placed("A219BS010440");
  CHECK(feeder.road_id != road->predecessor.element_id);
  CHECK(connections[1]->incoming_road == feeder.road_id);
  REQUIRE(connections[1]->lane_links.size() == 1);
  CHECK(connections[1]->lane_links.front().from == feeder.lane_id);
  CHECK(connections[1]->lane_links.front().to == -4);
  const auto before_fourth = area.map.lane_graph().predecessors(topology.lane_node(placed(run[3])));
  REQUIRE(before_fourth.size() == 1);
  CHECK(before_fourth.front().node == topology.lane_node(feeder));
}
