// The repairs on the lane groups that ../shared/data/ngii/README.md flags: lane numbers that do
// not start at 1, repeated numbers, LaneNo 10, L/R pointers that name a successor, and the report
// naming each repaired link with its A2 record.

#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <string>
#include <utility>

#include "corsa/ngii/convert.h"
#include "ngii_areas.h"

using corsa::test::converted;

namespace {

/// (link, field) -> the correction, for one area; a field repaired twice (a pointer cleared,
/// then set to the right neighbour) reads as one change from the first old to the last new value.
std::map<std::pair<std::string, std::string>, corsa::ngii::Correction> by_link(
    const std::string& area) {
  std::map<std::pair<std::string, std::string>, corsa::ngii::Correction> out;
  for (const auto& c : converted(area).conversion.corrections) {
    const auto [it, added] = out.emplace(std::make_pair(c.link_id, c.field), c);
    if (!added) {
      it->second.new_value = c.new_value;
      it->second.reason += "; " + c.reason;
    }
  }
  return out;
}

std::string lane_no_after(
    const std::map<std::pair<std::string, std::string>, corsa::ngii::Correction>& fixes,
    const std::string& link) {
  const auto it = fixes.find({link, "LaneNo"});
  return it == fixes.end() ? std::string("unchanged") : it->second.new_value;
}

}  // namespace

TEST_CASE("K-City groups numbered 2 3 4 5 6 7 and 2 3 are renumbered from 1",
          "[ngii][corrections]") {
  const auto fixes = by_link("kcity");
  // Left to right: A219BS010207, 205, 206, 204, 203 read 2..6 (README: group A219BS010207).
  const char* const group[] = {"A219BS010207", "A219BS010205", "A219BS010206", "A219BS010204",
                               "A219BS010203"};
  for (int k = 0; k < 5; ++k) {
    INFO(group[k]);
    REQUIRE(fixes.contains({group[k], "LaneNo"}));
    const auto& c = fixes.at({group[k], "LaneNo"});
    CHECK(c.old_value == std::to_string(k + 2));
    CHECK(c.new_value == std::to_string(k + 1));
    CHECK_THAT(c.reason, Catch::Contains("read 2 3 4 5 6 7"));
    CHECK_THAT(c.reason, Catch::Contains("start at 1"));
  }
  CHECK(lane_no_after(fixes, "A219BS010408") == "1");
  CHECK(lane_no_after(fixes, "A219BS010409") == "2");
}

TEST_CASE(
    "repeated lane numbers are a source defect; numbers continuing across a road split "
    "are a relabelling, listed without a note",
    "[ngii][corrections]") {
  const auto fixes = by_link("kcity");
  REQUIRE(fixes.contains({"A219BS010108", "LaneNo"}));
  const auto& repeated = fixes.at({"A219BS010108", "LaneNo"});
  CHECK(repeated.old_value == "1");
  CHECK(repeated.new_value == "2");
  CHECK_THAT(repeated.reason, Catch::Contains("read 1 1"));
  CHECK(repeated.kind == corsa::ngii::CorrectionKind::kDefect);
  // A219BS010103 reads 3 beside A219BS010104 (2); the two are different roads here, so the
  // road of 103 numbers it 1: the source is not wrong.
  REQUIRE(fixes.contains({"A219BS010103", "LaneNo"}));
  const auto& relabel = fixes.at({"A219BS010103", "LaneNo"});
  CHECK(relabel.old_value == "3");
  CHECK(relabel.new_value == "1");
  CHECK(relabel.kind == corsa::ngii::CorrectionKind::kRelabel);
  CHECK_THAT(relabel.reason, Catch::Contains("continuing the numbers of link A219BS010104"));
  // Located notes name every defect and no relabelling.
  const auto& area = converted("kcity");
  size_t defects = 0, relabels = 0;
  for (const auto& c : area.conversion.corrections) {
    (c.kind == corsa::ngii::CorrectionKind::kDefect ? defects : relabels) += 1;
  }
  CHECK(relabels > 0);
  CHECK(area.conversion.summary.defects == defects);
  size_t repair_notes = 0;
  for (const auto& d : area.diagnostics.all()) {
    if (d.message.find("-> '") != std::string::npos) {
      ++repair_notes;
      CHECK(d.severity == corsa::Severity::kNote);
      CHECK(d.record >= 0);
    }
    CHECK(d.message.find("A219BS010103: LaneNo") == std::string::npos);
  }
  CHECK(repair_notes == defects);
}

TEST_CASE("Sangam's LaneNo 10 and L/R pointers to successors are repaired", "[ngii][corrections]") {
  const auto fixes = by_link("seoul_sangam_testbed");
  REQUIRE(fixes.contains({"A219AS319251", "LaneNo"}));
  CHECK(fixes.at({"A219AS319251", "LaneNo"}).old_value == "10");
  CHECK(fixes.at({"A219AS319251", "LaneNo"}).new_value == "1");
  // README group A219AS318033 (`3 3 4`): its R_LinkID names the link that continues it.
  REQUIRE(fixes.contains({"A219AS318033", "R_LinkID"}));
  const auto& pointer = fixes.at({"A219AS318033", "R_LinkID"});
  CHECK(pointer.old_value == "A219AS318034");
  CHECK(pointer.new_value == "A219AS318035");
  CHECK_THAT(pointer.reason, Catch::Contains("parallel same-direction link"));
}

TEST_CASE("vertices where a link turns back on itself are removed as a located defect",
          "[ngii][corrections]") {
  // A digitising error runs a link back over its own path and forward again; the plan-view
  // fit cannot follow it (Sangam's fit missed a lane by 1.6 m).
  const auto kcity = by_link("kcity");
  REQUIRE(kcity.contains({"A219BS010048", "geometry"}));
  const auto& spike = kcity.at({"A219BS010048", "geometry"});
  CHECK(spike.old_value == "32 vertices");
  CHECK(spike.new_value == "31 vertices");
  CHECK_THAT(spike.reason, Catch::Contains("turns back on itself"));
  CHECK(spike.kind == corsa::ngii::CorrectionKind::kDefect);
  const auto sangam = by_link("seoul_sangam_testbed");
  REQUIRE(sangam.contains({"A219AS318684", "geometry"}));
  CHECK(sangam.at({"A219AS318684", "geometry"}).new_value == "18 vertices");
  CHECK(converted("seoul_sangam_testbed").conversion.summary.max_lane_error < 0.2);
}

TEST_CASE("every correction names its link, its A2 record and a reason", "[ngii][corrections]") {
  for (const char* name : {"kcity", "seoul_sangam_testbed"}) {
    INFO(name);
    const auto& area = converted(name);
    REQUIRE(area.conversion.corrections.size() > 100);
    for (const auto& c : area.conversion.corrections) {
      REQUIRE(c.record >= 0);
      REQUIRE(static_cast<size_t>(c.record) < area.layers.links.size());
      CHECK(area.layers.links[static_cast<size_t>(c.record)].id == c.link_id);
      CHECK_FALSE(c.field.empty());
      CHECK_FALSE(c.reason.empty());
      CHECK(c.old_value != c.new_value);
    }
    // The notes name the same records.
    size_t located = 0;
    for (const auto& d : area.diagnostics.all()) {
      located += d.severity == corsa::Severity::kNote && d.record >= 0;
    }
    CHECK(located >= area.conversion.corrections.size() / 2);
  }
}

// RoadNo is empty, so roads come from L/R adjacency: two ordinary links that name each other
// as neighbours and run side by side from end to end (lengths within 10 %, no shared end node)
// are lanes of one road, next to each other.
TEST_CASE("reciprocal side-by-side neighbours are adjacent lanes of one road",
          "[ngii][corrections][grouping]") {
  for (const char* name : {"kcity", "seoul_sangam_testbed"}) {
    INFO(name);
    const auto& area = converted(name);
    std::map<std::string, const corsa::ngii::Link*> links;
    for (const auto& link : area.layers.links) {
      links[link.id] = &link;
    }
    std::map<std::string, const corsa::ngii::LinkPlacement*> placed;  // ordinary: one placement
    for (const auto& p : area.conversion.placements) {
      placed.emplace(p.link_id, &p);
    }
    const auto length = [](const corsa::ngii::Link& link) {
      double total = 0.0;
      for (size_t i = 1; i < link.points.size(); ++i) {
        total += std::hypot(link.points[i].x - link.points[i - 1].x,
                            link.points[i].y - link.points[i - 1].y);
      }
      return total;
    };
    size_t pairs = 0;
    for (const auto& left : area.layers.links) {
      const auto it = links.find(left.right_id);
      if (left.link_type != "6" || it == links.end()) {
        continue;
      }
      const auto& right = *it->second;
      if (right.link_type != "6" || right.left_id != left.id || !placed.contains(left.id) ||
          !placed.contains(right.id)) {
        continue;
      }
      const double a = length(left);
      const double b = length(right);
      // Side by side from end to end: starts and ends a lane width apart. Links that meet or
      // part at one end are a split or merge (one lane tapering out of the other): separate
      // roads joined by a direct junction, not lanes of one road.
      const auto apart = [](const corsa::ngii::Point3& p, const corsa::ngii::Point3& q) {
        const double d = std::hypot(p.x - q.x, p.y - q.y);
        return d > 2.0 && d < 6.0;
      };
      if (std::abs(a - b) > 0.1 * std::max(a, b) || std::max(a, b) < 10.0 ||
          !apart(left.points.front(), right.points.front()) ||
          !apart(left.points.back(), right.points.back())) {
        continue;
      }
      INFO(left.id << " | " << right.id);
      const auto& pl = *placed.at(left.id);
      const auto& pr = *placed.at(right.id);
      // Short roads inside an intersection are cut into single-lane connecting roads (one per
      // path, OpenDRIVE 1.8 §10.4).
      const auto in_junction = [&](const corsa::ngii::LinkPlacement& p) {
        return area.map.road(*area.map.find_road(p.road_id)).in_junction();
      };
      if (in_junction(pl) || in_junction(pr)) {
        continue;
      }
      CHECK(pl.road_id == pr.road_id);
      CHECK(pr.lane_id == pl.lane_id - 1);  // right-hand lanes: -1, -2, ... left to right
      ++pairs;
    }
    CHECK(pairs > 50);
  }
}
