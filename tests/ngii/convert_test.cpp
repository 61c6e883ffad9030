#include "corsa/ngii/convert.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <set>
#include <unordered_map>

#include "corsa/xodr/map.h"
#include "corsa/xodr/parser.h"
#include "corsa/xodr/writer.h"
#include "ngii_areas.h"

using corsa::test::converted;
using corsa::test::ConvertedArea;

namespace {

const char* const kAreas[] = {"kcity", "seoul_sangam_testbed"};

/// Distance from (x, y) to a polyline, and whether the nearest point is inside it (not an end
/// reached from beyond it).
struct Nearest {
  double distance = 1e300;
  bool inside = false;
  double x = 0.0, y = 0.0;  ///< the nearest point
};

Nearest nearest_on(const std::vector<corsa::ngii::Point3>& line, double x, double y) {
  Nearest best;
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    const double ax = line[i].x, ay = line[i].y;
    const double dx = line[i + 1].x - ax, dy = line[i + 1].y - ay;
    const double len2 = dx * dx + dy * dy;
    const double f = len2 > 0.0 ? ((x - ax) * dx + (y - ay) * dy) / len2 : 0.0;
    const double c = std::clamp(f, 0.0, 1.0);
    const double d = std::hypot(x - ax - c * dx, y - ay - c * dy);
    if (d < best.distance) {
      best.distance = d;
      best.inside = !((i == 0 && f < 0.0) || (i + 2 == line.size() && f > 1.0));
      best.x = ax + c * dx;
      best.y = ay + c * dy;
    }
  }
  return best;
}

std::set<std::string> removed_links(const corsa::ngii::Conversion& conversion) {
  std::set<std::string> removed;
  for (const auto& c : conversion.corrections) {
    if (c.field == "geometry" && c.new_value == "removed") {
      removed.insert(c.link_id);
    }
  }
  return removed;
}

}  // namespace

TEST_CASE("both areas convert to maps that load without errors", "[ngii][convert]") {
  for (const char* name : kAreas) {
    INFO(name);
    const ConvertedArea& area = converted(name);
    CHECK_FALSE(area.diagnostics.has_errors());
    const auto& map = area.conversion.map;
    CHECK(area.map.road_count() == map.roads.size());
    CHECK(area.map.junction_count() == map.junctions.size());
    // Written and read back through the OpenDRIVE writer and parser, it still builds.
    corsa::Diagnostics diagnostics;
    const std::string text = corsa::xodr::write_xodr_text(map);
    const auto reparsed = corsa::xodr::parse_xodr_text(text, name, diagnostics);
    const auto reloaded = corsa::xodr::Map::build(reparsed, diagnostics);
    CHECK_FALSE(diagnostics.has_errors());
    CHECK(reloaded.road_count() == map.roads.size());
    // Not even a warning: reference lines are G1 (no heading jumps), lanes and links consistent.
    for (const auto& d : diagnostics.all()) {
      INFO(d.format());
      CHECK(d.severity == corsa::Severity::kNote);
    }
  }
}

TEST_CASE("the summary counts what the map holds", "[ngii][convert]") {
  for (const char* name : kAreas) {
    INFO(name);
    const auto& conversion = converted(name).conversion;
    const auto& s = conversion.summary;
    const auto& map = conversion.map;
    CHECK(s.links_read == converted(name).layers.links.size());
    CHECK(s.roads == map.roads.size());
    size_t lanes = 0, connecting = 0, geometries = 0, signals = 0;
    for (const auto& road : map.roads) {
      lanes += road.lane_sections.front().lanes.size() - 1;
      connecting += road.in_junction();
      geometries += road.plan_view.size();
      signals += road.signals.size();
    }
    // Lanes of the survey, the restricted strips between double centre lines and the
    // shoulders paving the ground beside joints of lanes of different widths.
    CHECK(s.lanes + s.centre_strips + s.mouth_fills == lanes);
    CHECK(s.centre_strips > 100);
    CHECK(s.connecting_roads == connecting);
    CHECK(s.geometries == geometries);
    CHECK(s.signals == signals);
    CHECK(s.junctions + s.direct_junctions == map.junctions.size());
    CHECK(s.corrections == conversion.corrections.size());
    // Fitting, not one record per vertex: far fewer planView records than A2 vertices.
    size_t vertices = 0;
    for (const auto& link : converted(name).layers.links) {
      vertices += link.points.size();
    }
    CHECK(geometries * 5 < vertices);
    CHECK(s.max_reference_error <= 0.05);
  }
}

// Distances are to the link's polyline joined with the links before and after it (by node), so
// that a lane rounding the corner where two links meet is measured against both. A point counts
// when its nearest source point lies inside a link (not past an end).
TEST_CASE("every A2 link is a lane whose centre stays within 10 cm of the link",
          "[ngii][convert][accuracy]") {
  for (const char* name : kAreas) {
    INFO(name);
    const ConvertedArea& area = converted(name);
    std::unordered_map<std::string, const corsa::ngii::Link*> links;
    std::unordered_map<std::string, std::vector<const corsa::ngii::Link*>> starting, ending;
    for (const auto& link : area.layers.links) {
      links[link.id] = &link;
      starting[link.from_node].push_back(&link);
      ending[link.to_node].push_back(&link);
    }
    std::set<std::string> placed;
    double worst = 0.0;
    std::string worst_link;
    size_t samples = 0;
    for (const auto& p : area.conversion.placements) {
      placed.insert(p.link_id);
      const auto road = area.map.find_road(p.road_id);
      REQUIRE(road);
      const corsa::ngii::Link& link = *links.at(p.link_id);
      std::vector<const corsa::ngii::Link*> chain = {&link};
      for (const auto* before : ending[link.from_node]) {
        chain.push_back(before);
      }
      for (const auto* after : starting[link.to_node]) {
        chain.push_back(after);
      }
      // Ordinary links starting or ending at the same node as this one (a lane split or merge).
      std::vector<const corsa::ngii::Link*> siblings;
      for (const auto* other : starting[link.from_node]) {
        if (other != &link && other->link_type != "1" && link.link_type != "1") {
          siblings.push_back(other);
        }
      }
      for (const auto* other : ending[link.to_node]) {
        if (other != &link && other->link_type != "1" && link.link_type != "1") {
          siblings.push_back(other);
        }
      }
      for (double s = p.s_start; s <= p.s_end; s += 1.0) {
        const auto span = area.map.lane_span(*road, s, p.lane_id);
        REQUIRE(span);
        const auto pose = area.map.world_pose(*road, s, span->t_center());
        const double x = pose.x + area.conversion.map.header.offset_x;
        const double y = pose.y + area.conversion.map.header.offset_y;
        Nearest n;
        for (const auto* source : chain) {
          const Nearest candidate = nearest_on(source->points, x, y);
          if (candidate.distance < n.distance) {
            n = candidate;
          }
        }
        // Where a lane splits off (merges into) a neighbour, its link runs inside that
        // neighbour until the two are a lane apart (up to 4.5 m in K-City): the lane lies beside
        // it, not on it.
        const Nearest own = nearest_on(link.points, x, y);
        const bool beside_sibling =
            std::any_of(siblings.begin(), siblings.end(), [&](const corsa::ngii::Link* other) {
              return nearest_on(other->points, own.x, own.y).distance < 4.5;
            });
        if (n.inside && !beside_sibling) {
          ++samples;
          if (n.distance > worst) {
            worst = n.distance;
            worst_link = p.link_id + " road " + p.road_id + " s " + std::to_string(s) + " at " +
                         std::to_string(x) + "," + std::to_string(y);
          }
        }
      }
    }
    INFO("worst link " << worst_link);
    CHECK(worst <= 0.10);
    CHECK(samples > 10000);
    const auto removed = removed_links(area.conversion);
    for (const auto& link : area.layers.links) {
      if (!removed.contains(link.id)) {
        INFO(link.id);
        CHECK(placed.contains(link.id));
      }
    }
  }
}
