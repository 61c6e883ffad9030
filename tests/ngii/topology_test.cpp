// Lane connectivity of the converted maps against the A1/A2 topology: every pair of links that
// meet at a node (A.ToNodeID == B.FromNodeID) is joined in the map's lane graph, and every join
// between two roads' lanes is such a pair.

#include <catch2/catch.hpp>
#include <map>
#include <set>
#include <unordered_map>

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
