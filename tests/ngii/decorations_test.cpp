// What the converter adds around the lanes: traffic lights with catalogue types and their
// controllers, tunnels and bridges from A2 RoadType, and optional sidewalks.

#include <catch2/catch.hpp>
#include <map>
#include <set>

#include "corsa/xodr/writer.h"
#include "ngii_areas.h"

using corsa::test::converted;

TEST_CASE("traffic lights carry OpenDRIVE catalogue types and keep the NGII code",
          "[ngii][signals]") {
  const auto& area = converted("kcity");
  std::map<std::string, std::string> ngii_type;  // C1 ID -> Type
  for (const auto& light : area.layers.lights) {
    ngii_type[light.id] = light.type;
  }
  size_t signals = 0;
  for (const auto& road : area.conversion.map.roads) {
    for (const auto& signal : road.signals) {
      ++signals;
      INFO(signal.id);
      CHECK(signal.country == "OpenDRIVE");
      CHECK(signal.dynamic);
      const std::string code = ngii_type.at(signal.id);
      const std::string expected = code == "11"                   ? "1000002"
                                   : code == "4" || code == "6"   ? "1000011"
                                   : code == "12" || code == "13" ? "1000013"
                                                                  : "1000001";
      CHECK(signal.type == expected);
      CHECK(signal.unit.empty());  // no empty unit attribute (the 1.7 XSD refuses one)
      REQUIRE_FALSE(signal.user_data.empty());
      CHECK(signal.user_data[0].code == "ngii:C1_TRAFFICLIGHT.Type");
      CHECK(signal.user_data[0].value == code);
    }
  }
  CHECK(signals == area.layers.lights.size());
}

TEST_CASE("the lights of each intersection are grouped per approach into controllers",
          "[ngii][signals][controllers]") {
  for (const char* name : {"kcity", "seoul_sangam_testbed"}) {
    INFO(name);
    const auto& map = converted(name).conversion.map;
    std::set<std::string> signal_ids;
    for (const auto& road : map.roads) {
      for (const auto& signal : road.signals) {
        signal_ids.insert(signal.id);
      }
    }
    std::set<std::string> controller_ids;
    std::set<std::string> controlled;
    for (const auto& controller : map.controllers) {
      CHECK(controller_ids.insert(controller.id).second);
      CHECK_FALSE(controller.controls.empty());
      for (const auto& control : controller.controls) {
        CHECK(signal_ids.contains(control.signal_id));
        CHECK(controlled.insert(control.signal_id).second);  // one controller per signal
      }
    }
    CHECK(map.controllers.size() > 20);
    // Every junction lists its controllers once, numbered 0, 1, 2, ... in its own order.
    size_t listed = 0;
    for (const auto& junction : map.junctions) {
      for (size_t i = 0; i < junction.controllers.size(); ++i) {
        CHECK(controller_ids.contains(junction.controllers[i].id));
        CHECK(junction.controllers[i].sequence == static_cast<uint32_t>(i));
        ++listed;
      }
    }
    CHECK(listed == map.controllers.size());
    CHECK(converted(name).conversion.summary.controllers == map.controllers.size());
  }
}

TEST_CASE("Sangam's tunnels and underground road become tunnel records on their roads",
          "[ngii][structures]") {
  const auto& area = converted("seoul_sangam_testbed");
  std::set<std::string> tunnel_links;  // A2 RoadType 2 (tunnel) or 4 (underground road)
  for (const auto& link : area.layers.links) {
    if (link.road_type == "2" || link.road_type == "4") {
      tunnel_links.insert(link.id);
    }
  }
  REQUIRE_FALSE(tunnel_links.empty());
  size_t tunnels = 0;
  for (const auto& road : area.conversion.map.roads) {
    for (const auto& tunnel : road.tunnels) {
      ++tunnels;
      CHECK(tunnel.length > 1.0);
      CHECK(tunnel.s + tunnel.length <= road.length + 1e-6);
    }
  }
  CHECK(tunnels > 0);
  // Every placement of a tunnel link lies inside a tunnel record of its road.
  std::map<std::string, const corsa::xodr::Road*> roads;
  for (const auto& road : area.conversion.map.roads) {
    roads[road.id] = &road;
  }
  for (const auto& p : area.conversion.placements) {
    if (!tunnel_links.contains(p.link_id)) {
      continue;
    }
    INFO(p.link_id);
    bool inside = false;
    for (const auto& tunnel : roads.at(p.road_id)->tunnels) {
      inside =
          inside || (tunnel.s <= p.s_start + 1e-6 && tunnel.s + tunnel.length >= p.s_end - 1e-6);
    }
    CHECK(inside);
  }
}

TEST_CASE("sidewalks are added on free road edges only when asked for", "[ngii][sidewalks]") {
  const auto& plain = converted("kcity");
  size_t sidewalks = 0;
  for (const auto& road : plain.conversion.map.roads) {
    for (const auto& lane : road.lane_sections.front().lanes) {
      sidewalks += lane.type == corsa::xodr::LaneType::kSidewalk;
    }
  }
  CHECK(sidewalks == 0);

  corsa::ngii::ConvertOptions options;
  options.sidewalk_width = 2.0;
  corsa::Diagnostics diagnostics;
  const auto conversion = corsa::ngii::convert(plain.layers, options, diagnostics);
  const auto map = corsa::xodr::Map::build(conversion.map, diagnostics);
  CHECK_FALSE(diagnostics.has_errors());
  size_t added = 0;
  size_t linked = 0;
  for (const auto& road : conversion.map.roads) {
    const auto& lanes = road.lane_sections.front().lanes;
    for (size_t k = 0; k < lanes.size(); ++k) {
      if (lanes[k].type != corsa::xodr::LaneType::kSidewalk) {
        continue;
      }
      ++added;
      CHECK(k + 1 == lanes.size());  // the outermost lane
      CHECK_FALSE(road.in_junction());
      REQUIRE(lanes[k].widths.size() == 1);
      CHECK(lanes[k].widths[0].a == 2.0);
      REQUIRE(lanes[k].heights.size() == 1);
      CHECK(lanes[k].heights[0].inner > 0.1);  // a kerb
      linked += !lanes[k].successors.empty();
    }
  }
  CHECK(added == conversion.summary.sidewalks);
  CHECK(added > 100);
  CHECK(linked > 10);  // continuous along roads joined end to end
  // A sidewalk lies where no other road's lane is: the map locates the lane centres of the
  // driving lanes on driving lanes still.
  for (const auto& p : conversion.placements) {
    const auto road = map.find_road(p.road_id);
    const auto span = map.lane_span(*road, 0.5 * (p.s_start + p.s_end), p.lane_id);
    REQUIRE(span);
    const auto pose = map.world_pose(*road, 0.5 * (p.s_start + p.s_end), span->t_center());
    corsa::xodr::LocateOptions drivable;
    drivable.drivable_only = true;
    const auto found = map.locate(pose.x, pose.y, drivable);
    REQUIRE(found);
    CHECK(found->distance == 0.0);
  }
}
