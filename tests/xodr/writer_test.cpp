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

TEST_CASE(
    "user data, objects with outlines and markings, tunnels, bridges and controllers "
    "survive writing and reading",
    "[xodr][writer]") {
  MapData data;
  data.roads.push_back(test::make_road("1", LineGeometry{}, 100.0));
  Road& road = data.roads[0];
  road.user_data.push_back({"ngii:road", "A219BS010001"});
  road.lane_sections[0].lanes.back().user_data = {{"ngii:link", "A"}, {"ngii:link", "B"}};
  Object crosswalk;
  crosswalk.id = "cw1";
  crosswalk.type = "crosswalk";
  crosswalk.s = 40.0;
  Outline outline;
  outline.id = 0;
  outline.fill_type = "asphalt";
  for (int i = 0; i < 4; ++i) {
    outline.corners.push_back(
        OutlineCorner{true, 38.0 + (i / 2) * 4.0, i % 3 == 0 ? -3.0 : 0.0, 0.0, 0.0, i});
  }
  crosswalk.outlines.push_back(outline);
  crosswalk.markings.push_back(ObjectMarking{"white", 0.5, 0.005, 0.5, 0.5, {0, 1}});
  crosswalk.user_data.push_back({"ngii:mark", "B3-1"});
  road.objects.push_back(crosswalk);
  road.tunnels.push_back(Tunnel{"t1", "tunnel", 10.0, 20.0, "underpass", 1.0, 0.0});
  road.bridges.push_back(Bridge{"b1", "bridge", 50.0, 30.0, "steel"});
  Signal signal;
  signal.id = "s1";
  signal.type = "1000001";
  signal.orientation = "+";
  signal.user_data.push_back({"ngii:type", "2"});
  road.signals.push_back(signal);
  data.controllers.push_back(Controller{"c1", "phase 1", 0u, {{"s1", "0"}}, {}, 0});
  Junction junction;
  junction.id = "9";
  junction.controllers.push_back(JunctionController{"c1", "0", 0u});
  data.junctions.push_back(junction);

  const std::string text = write_xodr_text(data);
  CHECK(text.find("unit=") == std::string::npos);  // no empty unit (the 1.7 XSD refuses it)
  corsa::Diagnostics diagnostics;
  const MapData back = parse_xodr_text(text, "back.xodr", diagnostics);
  CHECK(diagnostics.size() == 0);
  REQUIRE(back.roads.size() == 1);
  const Road& r = back.roads[0];
  CHECK(r.user_data.size() == 1);
  CHECK(r.lane_sections[0].lanes.back().user_data.size() == 2);
  CHECK(r.lane_sections[0].lanes.back().user_data[1].value == "B");
  REQUIRE(r.objects.size() == 1);
  REQUIRE(r.objects[0].outlines.size() == 1);
  CHECK(r.objects[0].outlines[0].corners.size() == 4);
  CHECK(r.objects[0].outlines[0].corners[2].u == 42.0);
  CHECK(r.objects[0].outlines[0].fill_type == "asphalt");
  REQUIRE(r.objects[0].markings.size() == 1);
  CHECK(r.objects[0].markings[0].corner_references == std::vector<int>{0, 1});
  REQUIRE(r.tunnels.size() == 1);
  CHECK(r.tunnels[0].type == "underpass");
  REQUIRE(r.bridges.size() == 1);
  CHECK(r.bridges[0].length == 30.0);
  REQUIRE(r.signals.size() == 1);
  CHECK(r.signals[0].user_data.size() == 1);
  REQUIRE(back.controllers.size() == 1);
  CHECK(back.controllers[0].controls.size() == 1);
  CHECK(back.controllers[0].sequence == 0u);
  REQUIRE(back.junctions.size() == 1);
  REQUIRE(back.junctions[0].controllers.size() == 1);
  CHECK(back.junctions[0].controllers[0].id == "c1");
  CHECK(write_xodr_text(back) == text);
}

TEST_CASE("object repeats survive writing and reading, local outline corners too",
          "[xodr][writer]") {
  MapData data;
  data.roads.push_back(test::make_road("1", LineGeometry{}, 100.0));
  Object rail;
  rail.id = "g1";
  rail.type = "barrier";
  rail.s = 10.0;
  rail.t = -4.0;
  rail.height = 0.8;
  ObjectRepeat stretched;
  stretched.s = 10.0;
  stretched.length = 50.0;
  stretched.t_start = -4.0;
  stretched.t_end = -4.5;
  stretched.height_start = stretched.height_end = 0.8;
  stretched.width_start = 0.2;
  rail.repeats.push_back(stretched);
  Outline outline;
  outline.corners = {OutlineCorner{false, -1.0, -0.5, 0.0, 0.8, 0},
                     OutlineCorner{false, 1.0, -0.5, 0.0, 0.8, 1},
                     OutlineCorner{false, 1.0, 0.5, 0.0, 0.8, 2}};
  rail.outlines.push_back(outline);
  data.roads[0].objects.push_back(rail);

  const std::string text = write_xodr_text(data);
  corsa::Diagnostics diagnostics;
  const MapData back = parse_xodr_text(text, "back.xodr", diagnostics);
  CHECK(diagnostics.size() == 0);
  REQUIRE(back.roads[0].objects.size() == 1);
  const Object& o = back.roads[0].objects[0];
  REQUIRE(o.repeats.size() == 1);
  CHECK(o.repeats[0].length == 50.0);
  CHECK(o.repeats[0].t_end == -4.5);
  REQUIRE(o.repeats[0].width_start);
  CHECK(*o.repeats[0].width_end == 0.2);  // written as widthEnd = widthStart
  CHECK_FALSE(o.repeats[0].length_start);
  REQUIRE(o.outlines.size() == 1);
  CHECK_FALSE(o.outlines[0].corners[1].road);
  CHECK(o.outlines[0].corners[1].u == 1.0);
  CHECK(write_xodr_text(back) == text);
}

TEST_CASE("a signal's lane validities survive writing and reading; its 1.8 length is not written",
          "[xodr][writer]") {
  MapData data;
  data.roads.push_back(test::make_road("1", LineGeometry{}, 100.0));
  Signal stop;
  stop.id = "s1";
  stop.s = 40.0;
  stop.t = -3.5;
  stop.orientation = "+";
  stop.country = "DE";
  stop.type = "294";
  stop.subtype = "-1";
  stop.width = 7.0;
  stop.length = 0.5;
  stop.validities = {LaneValidity{-2, -1}, LaneValidity{1, 1}};
  data.roads[0].signals.push_back(stop);

  const std::string text = write_xodr_text(data);
  corsa::Diagnostics diagnostics;
  const MapData back = parse_xodr_text(text, "back.xodr", diagnostics);
  CHECK(diagnostics.size() == 0);
  REQUIRE(back.roads[0].signals.size() == 1);
  const Signal& g = back.roads[0].signals[0];
  CHECK(g.length == 0.0);  // the 1.7 schema has no signal length
  CHECK(text.find("length=\"0.5") == std::string::npos);
  REQUIRE(g.validities.size() == 2);
  CHECK(g.validities[0].from_lane == -2);
  CHECK(g.validities[0].to_lane == -1);
  CHECK(g.validities[1].to_lane == 1);
  CHECK(write_xodr_text(back) == text);
}

TEST_CASE("an outline mixing cornerRoad and cornerLocal is refused", "[xodr][writer]") {
  MapData data;
  data.roads.push_back(test::make_road("1", LineGeometry{}, 100.0));
  Object o;
  o.id = "o1";
  o.type = "obstacle";
  Outline outline;
  outline.corners = {OutlineCorner{true, 5.0, 1.0, 0.0, 1.0, 0},
                     OutlineCorner{false, 1.0, 0.0, 0.0, 1.0, 1}};
  o.outlines.push_back(outline);
  data.roads[0].objects.push_back(o);
  corsa::Diagnostics diagnostics;
  CHECK_THROWS_WITH(parse_xodr_text(write_xodr_text(data), "mixed.xodr", diagnostics),
                    Catch::Contains("mixes cornerRoad and cornerLocal"));
}

TEST_CASE("the compat writer gives each lane one predecessor and one successor", "[xodr][writer]") {
  MapData data;
  data.roads.push_back(test::make_road("1", LineGeometry{}, 100.0));
  Lane& lane = data.roads[0].lane_sections[0].lanes.back();
  lane.successors = {-1, -2};
  WriteOptions options;
  options.single_lane_links = true;
  const std::string text = write_xodr_text(data, options);
  CHECK(text.find("<successor id=\"-1\"/>") != std::string::npos);
  CHECK(text.find("<successor id=\"-2\"/>") == std::string::npos);
  CHECK(write_xodr_text(data).find("<successor id=\"-2\"/>") != std::string::npos);
}

TEST_CASE("a junction's priorities are read, written and read back; one naming no road is refused",
          "[xodr][writer][junction]") {
  MapData data;
  Junction junction;
  junction.id = "7";
  junction.connections.push_back(Connection{"0", "1", "10", "", ContactPoint::kStart, {}, 0});
  junction.priorities.push_back(JunctionPriority{"10", "11", 0});
  junction.priorities.push_back(JunctionPriority{"", "12", 0});
  data.junctions.push_back(junction);
  const std::string text = write_xodr_text(data);
  CHECK(text.find("<priority high=\"10\" low=\"11\"/>") != std::string::npos);
  corsa::Diagnostics diagnostics;
  const MapData copy = parse_xodr_text(text, "copy.xodr", diagnostics);
  CHECK(diagnostics.size() == 0);
  REQUIRE(copy.junctions.size() == 1);
  REQUIRE(copy.junctions[0].priorities.size() == 2);
  CHECK(copy.junctions[0].priorities[0].high == "10");
  CHECK(copy.junctions[0].priorities[0].low == "11");
  CHECK(copy.junctions[0].priorities[0].line > 0);
  CHECK(copy.junctions[0].priorities[1].high.empty());
  CHECK(copy.junctions[0].priorities[1].low == "12");
  std::string bad = text;
  bad.replace(bad.find("<priority high=\"10\" low=\"11\"/>"), 30, "<priority/>");
  CHECK_THROWS_WITH(
      parse_xodr_text(bad, "bad.xodr", diagnostics),
      Catch::Contains("bad.xodr:") && Catch::Contains("needs attribute 'high' or 'low'"));
}
