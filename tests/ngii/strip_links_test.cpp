// Lane links of the centre strips (strip_links.h) on small synthetic maps, and on both areas.

#include "strip_links.h"

#include <catch2/catch.hpp>
#include <string>

#include "corsa/xodr/map.h"

namespace {

using corsa::xodr::ContactPoint;
using corsa::xodr::LinkElement;

/// A straight road of one driving lane (-1) from (x0, y) heading east, `length` m long, with a
/// centre strip (+1, 0.3 m wide) when `strip`.
corsa::xodr::Road straight(const std::string& id, double x0, double y, double length, bool strip) {
  corsa::xodr::Road road;
  road.id = id;
  road.name = id;
  road.length = length;
  road.plan_view.push_back(corsa::xodr::Geometry{
      .s = 0.0, .x = x0, .y = y, .hdg = 0.0, .length = length, .shape = {}, .line = 0});
  corsa::xodr::LaneSection section;
  if (strip) {
    corsa::xodr::Lane lane;
    lane.id = 1;
    lane.type = corsa::xodr::LaneType::kRestricted;
    lane.type_name = "restricted";
    lane.widths.push_back({0.0, 0.3, 0.0, 0.0, 0.0});
    lane.user_data.push_back({"ngii:centre-strip", "half the gap to the opposing road"});
    section.lanes.push_back(lane);
  }
  corsa::xodr::Lane centre;
  centre.id = 0;
  section.lanes.push_back(centre);
  corsa::xodr::Lane driving;
  driving.id = -1;
  driving.type = corsa::xodr::LaneType::kDriving;
  driving.type_name = "driving";
  driving.widths.push_back({0.0, 3.25, 0.0, 0.0, 0.0});
  section.lanes.push_back(driving);
  road.lane_sections.push_back(section);
  return road;
}

corsa::xodr::RoadLink to_road(const std::string& id, ContactPoint contact) {
  return {LinkElement::kRoad, id, contact};
}

corsa::xodr::RoadLink to_junction(const std::string& id) {
  return {LinkElement::kJunction, id, ContactPoint::kNone};
}

const corsa::xodr::Lane& lane_of(const corsa::xodr::MapData& map, const std::string& road, int id) {
  for (const auto& r : map.roads) {
    for (const auto& lane : r.lane_sections.front().lanes) {
      if (r.id == road && lane.id == id) {
        return lane;
      }
    }
  }
  FAIL("no lane " << id << " on road " << road);
  throw;
}

}  // namespace

TEST_CASE("centre strips continue into each other from road to road and through junctions",
          "[ngii][centre][strips]") {
  // a -> b road to road; b -> junction 9 (connecting road c) -> d. Road e follows d without a
  // strip, and road f lies 2 m aside of where d ends, so neither joins.
  corsa::xodr::MapData map;
  map.roads.push_back(straight("a", 0.0, 0.0, 10.0, true));
  map.roads.push_back(straight("b", 10.0, 0.0, 10.0, true));
  map.roads.push_back(straight("c", 20.0, 0.0, 10.0, true));
  map.roads.push_back(straight("d", 30.0, 0.0, 10.0, true));
  map.roads.push_back(straight("e", 40.0, 0.0, 10.0, false));
  map.roads[0].successor = to_road("b", ContactPoint::kStart);
  map.roads[1].predecessor = to_road("a", ContactPoint::kEnd);
  map.roads[1].successor = to_junction("9");
  map.roads[2].junction = "9";
  map.roads[2].predecessor = to_road("b", ContactPoint::kEnd);
  map.roads[2].successor = to_road("d", ContactPoint::kStart);
  map.roads[3].predecessor = to_junction("9");
  map.roads[3].successor = to_road("e", ContactPoint::kStart);
  map.roads[4].predecessor = to_road("d", ContactPoint::kEnd);
  corsa::xodr::Junction junction;
  junction.id = "9";
  junction.connections.push_back(corsa::xodr::Connection{.id = "0",
                                                         .incoming_road = "b",
                                                         .connecting_road = "c",
                                                         .linked_road = "",
                                                         .contact_point = ContactPoint::kStart,
                                                         .lane_links = {{-1, -1}},
                                                         .line = 0});
  map.junctions.push_back(junction);

  SECTION("linked where they touch") {
    CHECK(corsa::ngii::detail::link_centre_strips(map) == 3);
    CHECK(lane_of(map, "a", 1).successors == std::vector<int>{1});
    CHECK(lane_of(map, "b", 1).predecessors == std::vector<int>{1});
    CHECK(lane_of(map, "c", 1).predecessors == std::vector<int>{1});
    CHECK(lane_of(map, "c", 1).successors == std::vector<int>{1});
    CHECK(lane_of(map, "d", 1).successors.empty());  // e has no strip
    // b's connection carries the strip; d, leaving the junction, gets one of its own.
    const auto& connections = map.junctions.front().connections;
    REQUIRE(connections.size() == 2);
    CHECK(connections[0].lane_links.size() == 2);
    CHECK(connections[0].lane_links[1].from == 1);
    CHECK(connections[0].lane_links[1].to == 1);
    CHECK(connections[1].incoming_road == "d");
    CHECK(connections[1].connecting_road == "c");
    CHECK(connections[1].contact_point == ContactPoint::kEnd);
    REQUIRE(connections[1].lane_links.size() == 1);
    CHECK(connections[1].lane_links[0].from == 1);
    // The lane graph joins the strips at every joint: a -> b -> c -> d.
    corsa::Diagnostics diagnostics;
    const auto built = corsa::xodr::Map::build(map, diagnostics);
    CHECK(diagnostics.count(corsa::Severity::kWarning) == 0);
    const auto& graph = built.lane_graph();
    for (const char* id : {"a", "b", "c"}) {
      INFO(id);
      const auto node = graph.find({static_cast<uint32_t>(*built.find_road(id)), 0, 1});
      REQUIRE(node);
      CHECK(graph.successors(*node).size() == 1);
    }
  }
  SECTION("not where the strips do not meet") {
    map.roads[3].plan_view.front().y = 2.0;  // d's start lies 2 m aside of c's end
    CHECK(corsa::ngii::detail::link_centre_strips(map) == 2);
    CHECK(lane_of(map, "c", 1).successors.empty());
    CHECK(map.junctions.front().connections.size() == 1);
  }
}
