// Writer: MapData -> .xodr -> MapData gives back the same map (numbers exactly).

#include "corsa/xodr/writer.h"

#include <catch2/catch.hpp>

#include "corsa/core/atomic_file.h"
#include "corsa/xodr/parser.h"
#include "temp_dir.h"
#include "xodr_test_util.h"

using namespace corsa::xodr;

namespace {

bool same_poly(const std::vector<Poly3>& a, const std::vector<Poly3>& b) {
  if (a.size() != b.size()) {
    return false;
  }
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].s != b[i].s || a[i].a != b[i].a || a[i].b != b[i].b || a[i].c != b[i].c ||
        a[i].d != b[i].d) {
      return false;
    }
  }
  return true;
}

void check_same_road(const Road& a, const Road& b) {
  INFO("road " << a.id);
  CHECK(a.id == b.id);
  CHECK(a.name == b.name);
  CHECK(a.length == b.length);
  CHECK(a.junction == b.junction);
  CHECK(a.rule == b.rule);
  CHECK(a.predecessor.element_id == b.predecessor.element_id);
  CHECK(a.successor.contact_point == b.successor.contact_point);
  REQUIRE(a.plan_view.size() == b.plan_view.size());
  for (size_t i = 0; i < a.plan_view.size(); ++i) {
    const Geometry& g = a.plan_view[i];
    const Geometry& h = b.plan_view[i];
    CHECK((g.s == h.s && g.x == h.x && g.y == h.y && g.hdg == h.hdg && g.length == h.length));
    CHECK(g.shape.index() == h.shape.index());
    // Same shape parameters: the same point at the end.
    const RefPoint pg = evaluate_geometry(g, g.length);
    const RefPoint ph = evaluate_geometry(h, h.length);
    CHECK((pg.x == ph.x && pg.y == ph.y && pg.hdg == ph.hdg));
  }
  CHECK(same_poly(a.elevation, b.elevation));
  CHECK(same_poly(a.superelevation, b.superelevation));
  CHECK(same_poly(a.lane_offsets, b.lane_offsets));
  REQUIRE(a.lane_sections.size() == b.lane_sections.size());
  for (size_t k = 0; k < a.lane_sections.size(); ++k) {
    const LaneSection& x = a.lane_sections[k];
    const LaneSection& y = b.lane_sections[k];
    CHECK(x.s == y.s);
    REQUIRE(x.lanes.size() == y.lanes.size());
    for (size_t i = 0; i < x.lanes.size(); ++i) {
      CHECK(x.lanes[i].id == y.lanes[i].id);
      CHECK(x.lanes[i].type == y.lanes[i].type);
      CHECK(x.lanes[i].successors == y.lanes[i].successors);
      CHECK(x.lanes[i].predecessors == y.lanes[i].predecessors);
      CHECK(same_poly(x.lanes[i].widths, y.lanes[i].widths));
      CHECK(x.lanes[i].road_marks.size() == y.lanes[i].road_marks.size());
      CHECK(x.lanes[i].heights.size() == y.lanes[i].heights.size());
    }
  }
  CHECK(a.signals.size() == b.signals.size());
  CHECK(a.objects.size() == b.objects.size());
  CHECK(a.types.size() == b.types.size());
}

}  // namespace

TEST_CASE("maps written and read back are the same maps", "[xodr][writer]") {
  for (const char* name : {"Ex_Line-Spiral-Arc.xodr", "e6mini.xodr", "Ex_Slip_Lane.xodr",
                           "lane_gap_example_issue_119.xodr", "fabriksgatan.xodr",
                           "Ex_Entry_Exit.xodr", "Town03.xodr"}) {
    INFO(name);
    corsa::Diagnostics diagnostics;
    const MapData original = parse_xodr(test::shared_map(name), diagnostics);
    const std::string text = write_xodr_text(original);
    corsa::Diagnostics again;
    const MapData copy = parse_xodr_text(text, "copy.xodr", again);
    CHECK(again.size() == 0);  // our own output has nothing unknown
    REQUIRE(copy.roads.size() == original.roads.size());
    for (size_t i = 0; i < original.roads.size(); ++i) {
      check_same_road(original.roads[i], copy.roads[i]);
    }
    REQUIRE(copy.junctions.size() == original.junctions.size());
    for (size_t i = 0; i < original.junctions.size(); ++i) {
      CHECK(copy.junctions[i].connections.size() == original.junctions[i].connections.size());
      CHECK(copy.junctions[i].type == original.junctions[i].type);
    }
    CHECK(copy.header.geo_reference == original.header.geo_reference);
    CHECK(copy.header.offset_x == original.header.offset_x);
    // Writing the copy gives the same bytes: the output is a fixed point and deterministic.
    CHECK(write_xodr_text(copy) == text);
  }
}

TEST_CASE("a written map evaluates identically", "[xodr][writer]") {
  corsa::Diagnostics diagnostics;
  const Map original = test::load_map(test::shared_map("Town04.xodr"));
  const Map copy = Map::build(
      parse_xodr_text(write_xodr_text(original.data()), "copy", diagnostics), diagnostics);
  for (uint32_t road = 0; road < original.road_count(); road += 7) {
    for (const double f : {0.0, 0.3, 0.9}) {
      const double s = f * original.road(road).length;
      const WorldPose a = original.world_pose(road, s, -2.0);
      const WorldPose b = copy.world_pose(road, s, -2.0);
      CHECK((a.x == b.x && a.y == b.y && a.z == b.z && a.h == b.h));
    }
  }
  CHECK(copy.lane_graph().join_count() == original.lane_graph().join_count());
}

TEST_CASE("write_xodr writes the file atomically", "[xodr][writer]") {
  corsa::test::TempDir dir;
  MapData data;
  data.header.name = "a <quoted> & \"escaped\" name";
  data.header.geo_reference = "+proj=utm +zone=32 ]]> odd";
  data.roads.push_back(test::make_road("1", LineGeometry{}, 100.0));
  const auto path = dir.path() / "out.xodr";
  write_xodr(data, path);
  CHECK(dir.entries() == 1);
  corsa::Diagnostics diagnostics;
  const MapData back = parse_xodr(path, diagnostics);
  CHECK(back.header.name == data.header.name);
  CHECK(back.header.geo_reference == data.header.geo_reference);
  REQUIRE(back.roads.size() == 1);
  CHECK(back.roads[0].lane_sections[0].lanes.size() == 3);
  CHECK(back.roads[0].lane_sections[0].lanes[0].type_name == "driving");
  // Missing folders are created (AtomicFile); a path through a regular file cannot be written.
  CHECK_THROWS_AS(write_xodr(data, path / "deeper.xodr"), corsa::InputError);
}
