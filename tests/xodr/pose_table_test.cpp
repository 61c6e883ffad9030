// The road pose read from the map's packed table (xodr/src/pose_table.h) against the same
// arithmetic on the Road records themselves: the reference line, the profiles, the lane offset
// (inside a section and at its end) and the world pose, to the bit, on every shared map.

#include "pose_table.h"

#include <algorithm>
#include <bit>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <vector>

#include "corsa/xodr/map.h"
#include "corsa/xodr/map_parts.h"
#include "geometry_local.h"
#include "road_eval.h"
#include "xodr_test_util.h"

using namespace corsa::xodr;

namespace {

bool same_bits(double a, double b) {
  return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b);
}

double clamp_to_road(const Road& road, double s) {
  return s < 0.0 ? 0.0 : s > road.length ? road.length : s;
}

// The reference line point from the Road's planView records, the cosine and sine of the
// record's heading computed here.
RefPoint record_reference(const Road& road, double s) {
  s = clamp_to_road(road, s);
  const size_t g = detail::record_index(road.plan_view, s, [](const Geometry& x) { return x.s; });
  const Geometry& geometry = road.plan_view[g];
  return detail::to_world(geometry, std::cos(geometry.hdg), std::sin(geometry.hdg),
                          detail::evaluate_local(geometry, s - geometry.s));
}

// The lane offset a section's lanes use at s, from the Road's records (section_lane_offset's
// rule: at the section's end the last record starting strictly before s).
double record_section_offset(const Map& map, size_t road_index, size_t section, double s) {
  const Road& road = map.road(road_index);
  const auto& records = road.lane_offsets;
  const double end =
      section + 1 < road.lane_sections.size() ? road.lane_sections[section + 1].s : road.length;
  if (records.empty() || s < end || s <= road.lane_sections[section].s) {
    return detail::poly_value(records, clamp_to_road(road, s));
  }
  const auto it = std::lower_bound(records.begin(), records.end(), s,
                                   [](const Poly3& p, double value) { return p.s < value; });
  return it == records.begin() ? 0.0 : std::prev(it)->value(s);
}

// The world pose from the Road's records, the operations of Map::world_pose in their order.
WorldPose record_world_pose(const Map& map, size_t road_index, double s, double t) {
  const Road& road = map.road(road_index);
  const RefPoint ref = record_reference(road, s);
  const double cs = clamp_to_road(road, s);
  const double roll = detail::poly_value(road.superelevation, cs);
  const bool level = roll == 0.0 && !std::signbit(roll);
  const double cos_r = level ? 1.0 : std::cos(roll);
  const double sin_r = level ? 0.0 : std::sin(roll);
  const double elevation = detail::poly_value(road.elevation, cs);
  const double slope = detail::poly_slope(road.elevation, cs);
  const double horizontal = t * cos_r - 0.0 * sin_r;
  WorldPose pose;
  pose.x = ref.x - std::sin(ref.hdg) * horizontal;
  pose.y = ref.y + std::cos(ref.hdg) * horizontal;
  pose.z = elevation + t * sin_r + 0.0 * cos_r +
           (road.shapes.empty() ? 0.0 : map.shape_height(road_index, s, t));
  pose.h = ref.hdg;
  pose.p = -(slope == 0.0 ? slope : std::atan(slope));
  pose.r = roll;
  return pose;
}

// Every record start of the road and of its sections, the points just before and halfway to the
// next, and s beyond both ends.
std::vector<double> sample_s(const Road& road) {
  std::vector<double> starts = {0.0, road.length};
  for (const Geometry& g : road.plan_view) {
    starts.push_back(g.s);
  }
  for (const auto* records : {&road.lane_offsets, &road.elevation, &road.superelevation}) {
    for (const Poly3& p : *records) {
      starts.push_back(p.s);
    }
  }
  for (const LaneSection& section : road.lane_sections) {
    starts.push_back(section.s);
  }
  std::sort(starts.begin(), starts.end());
  std::vector<double> out = {-1.0, road.length + 1.0};
  for (size_t i = 0; i < starts.size(); ++i) {
    out.push_back(starts[i]);
    out.push_back(std::nextafter(starts[i], -1e300));
    if (i + 1 < starts.size()) {
      out.push_back(starts[i] + 0.5 * (starts[i + 1] - starts[i]));
    }
  }
  return out;
}

// Compares every road of `map` at its sample points; returns the number of points compared.
size_t check_poses(const Map& map) {
  size_t checked = 0;
  for (size_t road_index = 0; road_index < map.road_count(); ++road_index) {
    const Road& road = map.road(road_index);
    for (const double s : sample_s(road)) {
      INFO("road " << road.id << " s " << s);
      const RefPoint ref = map.reference(road_index, s);
      const RefPoint expected = record_reference(road, s);
      CHECK(same_bits(ref.x, expected.x));
      CHECK(same_bits(ref.y, expected.y));
      CHECK(same_bits(ref.hdg, expected.hdg));
      CHECK(same_bits(ref.curvature, expected.curvature));
      CHECK(same_bits(reference_curvature(map, road_index, s), ref.curvature));
      // The record a curvature is read from: s not clamped.
      const auto after =
          std::upper_bound(road.plan_view.begin(), road.plan_view.end(), s,
                           [](double value, const Geometry& g) { return value < g.s; });
      const Geometry* record = map.plan_record_at(road_index, s);
      if (after == road.plan_view.begin()) {
        CHECK(record == nullptr);
      } else {
        REQUIRE(record != nullptr);
        CHECK(record->s == std::prev(after)->s);
        CHECK(record->shape.index() == std::prev(after)->shape.index());
        CHECK(record->length == std::prev(after)->length);
      }
      const double cs = clamp_to_road(road, s);
      CHECK(same_bits(map.lane_offset(road_index, s), detail::poly_value(road.lane_offsets, cs)));
      CHECK(same_bits(map.elevation(road_index, s), detail::poly_value(road.elevation, cs)));
      CHECK(same_bits(map.superelevation(road_index, s),
                      detail::poly_value(road.superelevation, cs)));
      for (const double t : {0.0, -3.25, 5.5}) {
        const WorldPose pose = map.world_pose(road_index, s, t);
        const WorldPose want = record_world_pose(map, road_index, s, t);
        CHECK(same_bits(pose.x, want.x));
        CHECK(same_bits(pose.y, want.y));
        CHECK(same_bits(pose.z, want.z));
        CHECK(same_bits(pose.h, want.h));
        CHECK(same_bits(pose.p, want.p));
        CHECK(same_bits(pose.r, want.r));
        // The surface alone, also off the surface (h), as the whole pose has it.
        for (const double h : {0.0, 0.75}) {
          const WorldPose whole = map.world_pose(road_index, s, t, h);
          const SurfacePose surface = surface_pose(map, road_index, s, t, h);
          CHECK(same_bits(surface.z, whole.z));
          CHECK(same_bits(surface.p, whole.p));
          CHECK(same_bits(surface.r, whole.r));
        }
      }
      // The section's lane offset for s in the section and at its end (where a record of the
      // next section may start).
      const size_t section = map.section_index(road_index, s);
      for (const double at : {cs, map.section_end(road_index, section)}) {
        CHECK(same_bits(detail::section_lane_offset(map, road_index, section, at),
                        record_section_offset(map, road_index, section, at)));
      }
      ++checked;
    }
  }
  return checked;
}

}  // namespace

TEST_CASE("the packed road poses are the Road records' to the bit", "[xodr][pose]") {
  SECTION("a road with profiles and a lane offset starting at its second section") {
    Road road = test::make_road("1", ArcGeometry{0.01}, 100.0);
    Geometry line;
    line.s = 100.0;
    line.length = 50.0;
    line.x = std::sin(1.0) / 0.01;  // where the arc ends
    line.y = (1.0 - std::cos(1.0)) / 0.01;
    line.hdg = 1.0;
    line.shape = LineGeometry{};
    road.plan_view.push_back(line);
    road.length = 150.0;
    road.elevation = {Poly3{0.0, 1.0, 0.02, 0.0, 0.0}, Poly3{80.0, 2.6, 0.01, -1e-4, 1e-6}};
    road.superelevation = {Poly3{20.0, 0.0, 0.001, 0.0, 0.0}};
    LaneSection second = road.lane_sections.front();
    second.s = 60.0;
    road.lane_sections.push_back(second);
    road.lane_offsets = {Poly3{0.0, 0.5, 0.0, 0.0, 0.0}, Poly3{60.0, -0.25, 0.01, 0.0, 0.0}};
    MapData data;
    data.roads.push_back(road);
    corsa::Diagnostics diagnostics;
    const Map map = Map::build(std::move(data), diagnostics);
    CHECK(check_poses(map) > 20);
    // At the first section's end its lanes keep the first record's offset.
    CHECK(detail::section_lane_offset(map, 0, 0, 60.0) == 0.5);
    CHECK(detail::section_lane_offset(map, 0, 1, 60.0) == -0.25);
    CHECK(map.elevation(0, 90.0) == Approx(2.6 + 0.1 - 0.01 + 0.001));
  }
  SECTION("laneOffset and superelevation records of +0, read without the records") {
    // Road 0: every record +0 (the flags set), the superelevation's starting past s = 0. Road 1:
    // the same but for one -0 coefficient in each, which keeps the flags off (only records of
    // four +0 are read as +0 without evaluating them).
    Road zero = test::make_road("zero", LineGeometry{}, 80.0);
    zero.lane_offsets = {Poly3{0.0, 0.0, 0.0, 0.0, 0.0}, Poly3{30.0, 0.0, 0.0, 0.0, 0.0}};
    zero.superelevation = {Poly3{10.0, 0.0, 0.0, 0.0, 0.0}};
    zero.elevation = {Poly3{0.0, 2.0, 0.05, 0.0, 0.0}};
    LaneSection second = zero.lane_sections.front();
    second.s = 30.0;
    zero.lane_sections.push_back(second);
    Road negative = zero;
    negative.id = "negative";
    negative.lane_offsets[1].a = -0.0;
    negative.superelevation[0].b = -0.0;
    MapData data;
    data.roads = {zero, negative};
    detail::PoseTable table;
    table.build(data.roads);
    CHECK(table.road(0).zero_offsets);
    CHECK(table.road(0).level);
    CHECK_FALSE(table.road(1).zero_offsets);
    CHECK_FALSE(table.road(1).level);
    corsa::Diagnostics diagnostics;
    const Map map = Map::build(std::move(data), diagnostics);
    CHECK(check_poses(map) > 20);
    CHECK(std::signbit(map.world_pose(0, 50.0, 1.0).r) == false);
    CHECK(std::signbit(detail::section_lane_offset(map, 0, 1, 50.0)) == false);
  }
  SECTION("a paramPoly3 road with a tilted, sloped surface, longer than its record") {
    // Beyond its record the road goes on straight (curvature 0); within it the curvature is
    // read without the heading.
    ParamPoly3Geometry curve;
    curve.range = ParamRange::kArcLength;
    curve.bu = 1.0;
    curve.cu = 1e-4;
    curve.du = -2e-6;
    curve.cv = 4e-3;
    curve.dv = -1e-5;
    Road road = test::make_road("p", curve, 90.0);
    road.length = 100.0;
    road.elevation = {Poly3{0.0, 1.0, 0.03, 0.0, 1e-6}};
    road.superelevation = {Poly3{0.0, 0.02, 1e-4, 0.0, 0.0}};
    MapData data;
    data.roads.push_back(road);
    corsa::Diagnostics diagnostics;
    const Map map = Map::build(std::move(data), diagnostics);
    CHECK(check_poses(map) > 8);
    CHECK(reference_curvature(map, 0, 45.0) > 0.0);
    CHECK(reference_curvature(map, 0, 95.0) == 0.0);
  }
  SECTION("the shared maps") {
    for (const auto& path : test::all_shared_maps()) {
      INFO(path.string());
      CHECK(check_poses(test::load_map(path)) > 0);
    }
  }
}
