// Lane borders, widths, laneOffset, elevation and superelevation (OpenDRIVE 1.8 §8, §9).

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>

#include "corsa/xodr/map.h"
#include "span_table.h"
#include "xodr_test_util.h"

using namespace corsa::xodr;

TEST_CASE("lane widths follow their cubic polynomials", "[xodr][lanes]") {
  const Map map = test::load_map(test::shared_map("Ex_Lane-Width.xodr"));
  // Second section (s = 50): one lane opens with w(ds) = 0.026775 ds² - 0.0008925 ds³ until
  // ds = 20, then keeps 3.57 m.
  const LaneSection& section = map.road(0).lane_sections.at(1);
  REQUIRE(section.s == 50.0);
  const Lane* opening = nullptr;
  for (const Lane& lane : section.lanes) {
    opening = lane.widths.size() == 2 ? &lane : opening;
  }
  REQUIRE(opening != nullptr);
  for (const double ds : {0.0, 5.0, 10.0, 19.0, 20.0, 35.0}) {
    const double expected =
        ds < 20.0 ? 2.6774999999999993e-02 * ds * ds - 8.9249999999999985e-04 * ds * ds * ds : 3.57;
    const auto span = map.lane_span(0, 50.0 + ds, opening->id);
    REQUIRE(span);
    CHECK(span->width() == Approx(expected).margin(1e-12));
  }
  // The lanes tile the road: each inner border is the outer border of the next lane inward.
  std::vector<LaneSpan> spans;
  map.lane_spans(0, 62.0, spans);
  REQUIRE(spans.size() == section.lanes.size() - 1);
  for (size_t i = 0; i + 1 < spans.size(); ++i) {
    if (spans[i].id > 0 && spans[i + 1].id > 0) {
      CHECK(spans[i].t_inner == spans[i + 1].t_outer);
    }
    if (spans[i].id < 0 && spans[i + 1].id < 0) {
      CHECK(spans[i + 1].t_inner == spans[i].t_outer);
    }
  }
}

TEST_CASE("laneOffset shifts every lane and applies only from its first record",
          "[xodr][lanes][laneOffset]") {
  const Map map = test::load_map(test::shared_map("Ex_Simple-LaneOffset.xodr"));
  CHECK(map.lane_offset(0, 10.0) == 0.0);  // before the first record at s = 25
  const double ds = 30.0;
  const double expected = 3.8999999999999998e-03 * ds * ds - 5.1999999999999997e-05 * ds * ds * ds;
  CHECK(map.lane_offset(0, 25.0 + ds) == Approx(expected).margin(1e-12));
  CHECK(map.lane_offset(0, 90.0) == Approx(3.25));
  const auto lane1 = map.lane_span(0, 90.0, 1);
  const auto right1 = map.lane_span(0, 90.0, -1);
  REQUIRE(lane1);
  REQUIRE(right1);
  CHECK(lane1->t_inner == Approx(3.25));
  CHECK(right1->t_inner == Approx(3.25));
}

TEST_CASE("lane_at finds the lane whose span holds t", "[xodr][lanes]") {
  const Map map = test::load_map(test::shared_map("straight_500m.xodr"));
  std::vector<LaneSpan> spans;
  map.lane_spans(0, 100.0, spans);
  REQUIRE_FALSE(spans.empty());
  for (const LaneSpan& span : spans) {
    if (span.width() > 0.0) {
      CHECK(map.lane_at(0, 100.0, span.t_center()) == span.id);
    }
  }
  const double outside = spans.front().t_max() + 1.0;
  CHECK_FALSE(map.lane_at(0, 100.0, outside).has_value());
}

TEST_CASE("world poses include elevation, pitch and superelevation roll",
          "[xodr][lanes][elevation]") {
  const Map map =
      test::load_map(test::shared_map("Ex_Line-Spiral-Arc_elevation_and_superelevation.xodr"));
  const Road& road = map.road(0);
  REQUIRE_FALSE(road.elevation.empty());
  REQUIRE_FALSE(road.superelevation.empty());
  const double s = 40.0;
  const double z = road.elevation.front().value(s);  // one record (b = 1: a 45° grade)
  const double roll = map.superelevation(0, s);
  CHECK(roll != 0.0);
  const WorldPose centre = map.world_pose(0, s, 0.0);
  CHECK(centre.z == Approx(z).margin(1e-12));
  CHECK(centre.p == Approx(-std::atan(map.elevation_slope(0, s))).margin(1e-12));
  CHECK(centre.r == roll);
  const WorldPose left = map.world_pose(0, s, 2.0);
  // t runs along the rolled normal: 2 cos(roll) sideways, 2 sin(roll) up.
  CHECK(left.z - centre.z == Approx(2.0 * std::sin(roll)).margin(1e-12));
  CHECK(std::hypot(left.x - centre.x, left.y - centre.y) ==
        Approx(2.0 * std::cos(roll)).margin(1e-12));
  const RefPoint ref = map.reference(0, s);
  CHECK(centre.x == ref.x);
  CHECK(centre.h == ref.hdg);
}

TEST_CASE("reference positions are clamped to the road", "[xodr][lanes]") {
  const Map map = test::load_map(test::shared_map("straight_500m.xodr"));
  const RefPoint start = map.reference(0, -5.0);
  const RefPoint zero = map.reference(0, 0.0);
  CHECK(start.x == zero.x);
  CHECK(map.section_index(0, 1e9) == map.road(0).lane_sections.size() - 1);
  CHECK(map.section_end(0, map.road(0).lane_sections.size() - 1) == map.road(0).length);
}

namespace {

bool same_span_bits(const LaneSpan& a, const LaneSpan& b) {
  return a.id == b.id && std::memcmp(&a.t_inner, &b.t_inner, sizeof(double)) == 0 &&
         std::memcmp(&a.t_outer, &b.t_outer, sizeof(double)) == 0;
}

// The distinct starts (sOffset) of the section's width records.
std::vector<double> width_starts(const LaneSection& section) {
  std::vector<double> starts;
  for (const Lane& lane : section.lanes) {
    for (const Poly3& width : lane.widths) {
      starts.push_back(width.s);
    }
  }
  std::sort(starts.begin(), starts.end());
  starts.erase(std::unique(starts.begin(), starts.end()), starts.end());
  return starts;
}

// Every lane's span alone (Map::lane_span_in_section, from the packed sections) against the
// section's spans together (Map::lane_spans_in_section, from the Lane records), at the section's
// start, inside it and at its end; returns the spans compared.
size_t check_lane_spans_alone(const Map& map) {
  size_t compared = 0;
  std::vector<LaneSpan> spans;
  for (size_t road = 0; road < map.road_count(); ++road) {
    const auto& sections = map.road(road).lane_sections;
    for (size_t section = 0; section < sections.size(); ++section) {
      // The section's flag kept at build: no lane whose border comes from borders alone.
      const auto& lanes = sections[section].lanes;
      CHECK(map.section_widths_only(road, section) ==
            std::none_of(lanes.begin(), lanes.end(), [](const Lane& lane) {
              return lane.widths.empty() && !lane.borders.empty();
            }));
      const double start = sections[section].s, end = map.section_end(road, section);
      // The section's start, inside it and its end; and every width record's start (where a
      // packed row of constant widths may begin) and the point just before it.
      std::vector<double> at = {start, start + 0.37 * (end - start), start + 0.5 * (end - start),
                                end};
      for (const double offset : width_starts(sections[section])) {
        at.push_back(start + offset);
        at.push_back(std::nextafter(start + offset, -1e300));
      }
      for (const double s : at) {
        map.lane_spans_in_section(road, section, s, spans);
        for (const LaneSpan& span : spans) {
          const auto alone = map.lane_span_in_section(road, section, s, span.id);
          REQUIRE(alone);
          REQUIRE(same_span_bits(*alone, span));
          ++compared;
        }
        // Ids the section lacks: far out, the centre, one beyond each side.
        const int left = static_cast<int>(std::count_if(
            lanes.begin(), lanes.end(), [](const Lane& lane) { return lane.id > 0; }));
        const int right = static_cast<int>(std::count_if(
            lanes.begin(), lanes.end(), [](const Lane& lane) { return lane.id < 0; }));
        for (const int id : {1000, -1000, 0, left + 1, -right - 1}) {
          if (std::none_of(lanes.begin(), lanes.end(),
                           [id](const Lane& lane) { return lane.id == id; })) {
            CHECK_FALSE(map.lane_span_in_section(road, section, s, id));
          }
        }
      }
    }
  }
  return compared;
}

}  // namespace

TEST_CASE("a lane's span alone is its span among the section's, to the bit", "[xodr][lanes]") {
  SECTION("every outer border rule: one width, widths, one border, borders, neither") {
    Road road = test::make_road("rules", LineGeometry{}, 100.0, 3, 3.0);
    road.lane_offsets.push_back(Poly3{0.0, 0.25, 0.01, 0.0, 0.0});
    road.lane_offsets.push_back(Poly3{40.0, 0.65, 0.0, -0.0002, 0.0});
    for (Lane& lane : road.lane_sections[0].lanes) {
      if (lane.id == 3) {  // one border record, no widths
        lane.widths.clear();
        lane.borders.push_back(Poly3{0.0, 9.4, 0.002, 0.0, 0.0});
      } else if (lane.id == 2) {  // widths of two records
        lane.widths = {Poly3{0.0, 3.0, 0.0, 0.0, 0.0}, Poly3{30.0, 3.0, 0.01, 0.0, -1e-6}};
      } else if (lane.id == -2) {  // borders of two records
        lane.widths.clear();
        lane.borders = {Poly3{0.0, -5.9, 0.0, 0.0, 0.0}, Poly3{50.0, -5.9, -0.02, 0.0, 0.0}};
      } else if (lane.id == -3) {  // neither
        lane.widths.clear();
      } else if (lane.id == -1) {  // a negative width (counted as 0) over its first metres
        lane.widths = {Poly3{0.0, -0.5, 0.2, 0.0, 0.0}};
      }
    }
    MapData data;
    data.roads.push_back(road);
    corsa::Diagnostics diagnostics;
    const Map map = Map::build(std::move(data), diagnostics);
    CHECK(check_lane_spans_alone(map) == (4 + 2 * 2) * 6);  // width starts 0 and 30
    // Lane 3's border is a border record: the lanes may overlap.
    CHECK_FALSE(map.section_widths_only(0, 0));
    // The rules themselves: one border record gives the border, neither the inner border.
    const auto border = map.lane_span_in_section(0, 0, 10.0, 3);
    REQUIRE(border);
    CHECK(border->t_outer == Approx(9.42));
    const auto neither = map.lane_span_in_section(0, 0, 10.0, -3);
    REQUIRE(neither);
    CHECK(neither->t_outer == neither->t_inner);
  }
  SECTION("constant widths, read from the packed widths, and the sections that cannot be") {
    // Section 0: constant widths of every kind (a negative one, counted as 0; -0; 0; a record
    // starting past the section's start; b, c and d of -0), ids 1..3 and -1..-3. Section 1: the
    // same but for a lane of varying width. Section 2: ids skipping 2 on the left. Section 3: no
    // centre lane. Section 4: lanes of several constant records (two starting at the same s, one
    // narrowing to 0 and widening again). Section 5: the same with one lane's records out of s
    // order.
    Road road = test::make_road("constant", LineGeometry{}, 120.0, 3, 3.5);
    road.lane_offsets.push_back(Poly3{0.0, -0.75, 0.002, 0.0, 0.0});
    for (Lane& lane : road.lane_sections[0].lanes) {
      if (lane.id == 3) {
        lane.widths = {Poly3{4.0, 0.5, -0.0, -0.0, -0.0}};
      } else if (lane.id == 2) {
        lane.widths = {Poly3{0.0, -0.0, 0.0, 0.0, 0.0}};
      } else if (lane.id == -2) {
        lane.widths = {Poly3{0.0, -1.25, 0.0, 0.0, 0.0}};
      } else if (lane.id == -3) {
        lane.widths = {Poly3{0.0, 0.0, 0.0, 0.0, 0.0}};
      }
    }
    LaneSection varying = road.lane_sections[0];
    varying.s = 30.0;
    varying.lanes[1].widths = {Poly3{0.0, 3.0, 0.01, 0.0, 0.0}};  // lane 2
    LaneSection skipping = road.lane_sections[0];
    skipping.s = 60.0;
    skipping.lanes[1].id = 4;  // ids 4, 3, 1 on the left
    std::swap(skipping.lanes[0], skipping.lanes[1]);
    LaneSection no_center = road.lane_sections[0];
    no_center.s = 90.0;
    no_center.lanes.erase(no_center.lanes.begin() + 3);
    LaneSection several = road.lane_sections[0];
    several.s = 100.0;
    several.lanes[2].widths = {Poly3{0.0, 3.0, 0.0, 0.0, 0.0}, Poly3{5.0, 3.25, 0.0, 0.0, 0.0},
                               Poly3{5.0, 3.5, 0.0, 0.0, 0.0}};  // lane 1
    several.lanes[4].widths = {Poly3{2.0, 2.75, 0.0, 0.0, 0.0}, Poly3{9.0, 0.0, 0.0, 0.0, 0.0},
                               Poly3{14.0, 3.0, 0.0, 0.0, 0.0}};  // lane -1
    LaneSection unordered = several;
    unordered.s = 110.0;
    std::swap(unordered.lanes[4].widths[0], unordered.lanes[4].widths[2]);
    road.length = 130.0;
    road.plan_view.front().length = 130.0;
    road.lane_sections.push_back(varying);
    road.lane_sections.push_back(skipping);
    road.lane_sections.push_back(no_center);
    road.lane_sections.push_back(several);
    road.lane_sections.push_back(unordered);
    MapData data;
    data.roads.push_back(road);
    detail::SpanTable table;
    table.build(data.roads);
    CHECK(table.section(0, 0).constant_widths);
    CHECK_FALSE(table.section(0, 1).constant_widths);
    CHECK_FALSE(table.section(0, 2).constant_widths);
    CHECK(table.section(0, 3).constant_widths);
    CHECK(table.section(0, 4).constant_widths);
    // Rows from 5 (lane 1's 3.5 m), 9 and 14 (lane -1's 0 m, then 3 m); before 5 lane -1 has
    // its first record's 2.75 m, also where ds precedes its start at 2.
    CHECK(table.section(0, 4).break_count == 3);
    CHECK_FALSE(table.section(0, 5).constant_widths);
    // The width starts: 0 and 4 in sections 0 to 3, 0, 2, 4, 5, 9 and 14 in 4 and 5.
    corsa::Diagnostics diagnostics;
    const Map map = Map::build(std::move(data), diagnostics);
    CHECK(check_lane_spans_alone(map) == 6 * (4 * (4 + 2 * 2) + 2 * (4 + 2 * 6)));
    // Lane 1 of section 4 is 3.5 m from ds = 5 (the second of two records at 5), lane -1 0 m
    // from ds = 9 to 14.
    const auto one = map.lane_span_in_section(0, 4, 106.0, 1);
    const auto minus_one = map.lane_span_in_section(0, 4, 110.0 - 0.5, -1);
    REQUIRE(one);
    REQUIRE(minus_one);
    CHECK(one->width() == 3.5);
    CHECK(minus_one->width() == 0.0);
    // Lane -2's negative width counts as 0: lane -3 starts where lane -1 ends.
    const auto minus1 = map.lane_span_in_section(0, 0, 10.0, -1);
    const auto minus3 = map.lane_span_in_section(0, 0, 10.0, -3);
    REQUIRE(minus1);
    REQUIRE(minus3);
    CHECK(minus3->t_inner == minus1->t_outer);
    CHECK(minus3->width() == 0.0);
  }
  SECTION("the shared maps") {
    size_t sections = 0, widths_only = 0;
    for (const auto& path : test::all_shared_maps()) {
      INFO(path.string());
      const Map map = test::load_map(path);
      CHECK(check_lane_spans_alone(map) > 0);
      for (size_t road = 0; road < map.road_count(); ++road) {
        for (size_t section = 0; section < map.road(road).lane_sections.size(); ++section) {
          ++sections;
          widths_only += map.section_widths_only(road, section) ? 1 : 0;
        }
      }
    }
    // Most sections' lanes are given by widths.
    CHECK(widths_only > sections / 2);
  }
}
