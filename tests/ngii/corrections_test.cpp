// The repairs on the lane groups that ../shared/data/ngii/README.md flags: lane numbers that do
// not start at 1, repeated numbers, LaneNo 10, L/R pointers that name a successor, and the report
// naming each repaired link with its A2 record.

#include <catch2/catch.hpp>
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

TEST_CASE("repeated lane numbers and two roads sharing one sequence are repaired",
          "[ngii][corrections]") {
  const auto fixes = by_link("kcity");
  REQUIRE(fixes.contains({"A219BS010108", "LaneNo"}));
  const auto& repeated = fixes.at({"A219BS010108", "LaneNo"});
  CHECK(repeated.old_value == "1");
  CHECK(repeated.new_value == "2");
  CHECK_THAT(repeated.reason, Catch::Contains("read 1 1"));
  REQUIRE(fixes.contains({"A219BS010074", "LaneNo"}));
  const auto& shared = fixes.at({"A219BS010074", "LaneNo"});
  CHECK(shared.new_value == "1");
  CHECK_THAT(shared.reason, Catch::Contains("two roads sharing one sequence"));
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
    // The warnings name the same records.
    size_t located = 0;
    for (const auto& d : area.diagnostics.all()) {
      located += d.severity == corsa::Severity::kWarning && d.record >= 0;
    }
    CHECK(located >= area.conversion.corrections.size() / 2);
  }
}
