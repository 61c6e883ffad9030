// The feature layers the sample areas do not have (B1, B3, C3, C4, C6, A3, A4, A5), on a small
// hand-made area written here with shapelib after the NGII data model 2020 (manual 2023.07
// §9.4): one 100 m lane running east, with its marks, a sign, a crosswalk and an arrow, a guard
// rail, a speed bump, a post, a bridge, a sidewalk and a parking lot.

#include <shapefil.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <map>

#include "corsa/core/atomic_file.h"
#include "corsa/ngii/convert.h"
#include "corsa/xodr/map.h"
#include "corsa/xodr/writer.h"
#include "ngii_fixtures.h"
#include "temp_dir.h"

namespace fs = std::filesystem;

namespace {

constexpr double kX = 300000.0;  // UTM 52N, metres
constexpr double kY = 4100000.0;
constexpr double kZ = 30.0;

struct Record {
  std::vector<std::array<double, 3>> points;
  std::map<std::string, std::string> fields;
};

/// Writes one layer: `type` a SHPT_* code, every field a 30-character string (what NGII's
/// VARCHAR2 fields are; Integer fields read the same text).
void write_layer(const fs::path& dir, const std::string& name, int type,
                 const std::vector<std::string>& fields, const std::vector<Record>& records) {
  const std::string base = (dir / name).string();
  SHPHandle shp = SHPCreate(base.c_str(), type);
  DBFHandle dbf = DBFCreate(base.c_str());
  REQUIRE(shp != nullptr);
  REQUIRE(dbf != nullptr);
  for (const std::string& field : fields) {
    DBFAddField(dbf, field.c_str(), FTString, 30, 0);
  }
  int index = 0;
  for (const Record& r : records) {
    std::vector<double> x, y, z;
    for (const auto& p : r.points) {
      x.push_back(kX + p[0]);
      y.push_back(kY + p[1]);
      z.push_back(kZ + p[2]);
    }
    SHPObject* object =
        SHPCreateSimpleObject(type, static_cast<int>(x.size()), x.data(), y.data(), z.data());
    SHPWriteObject(shp, -1, object);
    SHPDestroyObject(object);
    for (size_t f = 0; f < fields.size(); ++f) {
      const auto it = r.fields.find(fields[f]);
      DBFWriteStringAttribute(dbf, index, static_cast<int>(f),
                              it == r.fields.end() ? "" : it->second.c_str());
    }
    ++index;
  }
  SHPClose(shp);
  DBFClose(dbf);
  fs::copy_file(corsa::test::ngii_area("kcity") / "A2_LINK.prj", dir / (name + ".prj"));
}

std::vector<std::array<double, 3>> rect(double x0, double y0, double x1, double y1,
                                        double z = 0.0) {
  return {{x0, y0, z}, {x0, y1, z}, {x1, y1, z}, {x1, y0, z}, {x0, y0, z}};
}

/// The whole area.
void write_area(const fs::path& dir) {
  write_layer(dir, "A1_NODE", SHPT_POINTZ, {"ID", "NodeType"},
              {{{{0, 0, 0}}, {{"ID", "A1TEST000001"}, {"NodeType", "99"}}},
               {{{100, 0, 0}}, {{"ID", "A1TEST000002"}, {"NodeType", "99"}}}});
  std::vector<std::array<double, 3>> lane;
  for (int x = 0; x <= 100; x += 10) {
    lane.push_back({double(x), 0.0, 0.0});
  }
  write_layer(dir, "A2_LINK", SHPT_ARCZ,
              {"ID", "LinkType", "LaneNo", "R_LinkID", "L_LinkID", "FromNodeID", "ToNodeID",
               "MaxSpeed", "RoadType"},
              {{lane,
                {{"ID", "A2TEST000001"},
                 {"LinkType", "6"},
                 {"LaneNo", "1"},
                 {"FromNodeID", "A1TEST000001"},
                 {"ToNodeID", "A1TEST000002"},
                 {"MaxSpeed", "50"},
                 {"RoadType", "1"}}}});
  write_layer(
      dir, "B2_SURFACELINEMARK", SHPT_ARCZ, {"ID", "Type", "Kind", "R_linkID", "L_linkID"},
      {{{{0, 1.75, 0}, {100, 1.75, 0}},
        {{"ID", "B2TEST000001"}, {"Type", "111"}, {"Kind", "501"}, {"R_linkID", "A2TEST000001"}}},
       {{{0, -1.75, 0}, {100, -1.75, 0}},
        {{"ID", "B2TEST000002"}, {"Type", "211"}, {"Kind", "505"}, {"L_linkID", "A2TEST000001"}}}});
  // A sign board 0.6 m square, 2.5 m up, 3 m right of the lane, facing the traffic.
  write_layer(
      dir, "B1_SAFETYSIGN", SHPT_POLYGONZ, {"ID", "Type", "LinkID", "Ref_Lane", "Remark"},
      {{{{50, -3.0, 2.5}, {50, -3.0, 3.1}, {50, -3.6, 3.1}, {50, -3.6, 2.5}, {50, -3.0, 2.5}},
        {{"ID", "B1TEST000001"},
         {"Type", "3"},
         {"LinkID", "A2TEST000001"},
         {"Ref_Lane", "1"},
         {"Remark", "50"}}}});
  write_layer(
      dir, "B3_SURFACEMARK", SHPT_POLYGONZ, {"ID", "Type", "Kind", "LinkID"},
      {{rect(70, -1.75, 74, 1.75),
        {{"ID", "B3TEST000001"}, {"Type", "5"}, {"Kind", "5321"}, {"LinkID", "A2TEST000001"}}},
       {rect(30, -0.5, 36, 0.5),
        {{"ID", "B3TEST000002"}, {"Type", "1"}, {"Kind", "5371"}, {"LinkID", "A2TEST000001"}}}});
  write_layer(dir, "C3_VEHICLEPROTECTIONSAFETY", SHPT_ARCZ, {"ID", "Type", "isCentral"},
              {{{{0, -2.5, 0}, {50, -2.5, 0}, {100, -2.5, 0}},
                {{"ID", "C3TEST000001"}, {"Type", "2"}, {"isCentral", "0"}}}});
  write_layer(
      dir, "C4_SPEEDBUMP", SHPT_POLYGONZ, {"ID", "Type", "LinkID", "Ref_Lane"},
      {{rect(80, -1.75, 82, 1.75),
        {{"ID", "C4TEST000001"}, {"Type", "1"}, {"LinkID", "A2TEST000001"}, {"Ref_Lane", "1"}}}});
  write_layer(dir, "C6_POSTPOINT", SHPT_POINTZ, {"ID", "Type"},
              {{{{50, -3.3, 0}}, {{"ID", "C6TEST000001"}, {"Type", "2"}}}});
  write_layer(dir, "A3_DRIVEWAYSECTION", SHPT_POLYGONZ, {"ID", "Kind", "RoadType"},
              {{rect(20, -5, 40, 5), {{"ID", "A3TEST000001"}, {"Kind", "1"}, {"RoadType", "3"}}}});
  write_layer(dir, "A4_SUBSIDIARYSECTION", SHPT_POLYGONZ, {"ID", "SubType", "Name"},
              {{rect(0, -5.5, 100, -3.5, 0.15),
                {{"ID", "A4TEST000001"}, {"SubType", "3"}, {"Name", "sidewalk"}}}});
  write_layer(dir, "A5_PARKINGLOT", SHPT_POLYGONZ, {"ID", "Type", "SectionID"},
              {{rect(40, -20, 60, -10), {{"ID", "A5TEST000001"}, {"Type", "1"}}}});
}

const corsa::xodr::Object* find_object(const corsa::xodr::Road& road, const std::string& id) {
  for (const auto& object : road.objects) {
    if (object.id == id) {
      return &object;
    }
  }
  return nullptr;
}

}  // namespace

TEST_CASE("the feature layers become signals, objects and bridge records", "[ngii][features]") {
  corsa::test::TempDir dir;
  write_area(dir.path());
  corsa::Diagnostics diagnostics;
  const auto layers = corsa::ngii::read_layers(dir.path(), diagnostics);
  CHECK_FALSE(diagnostics.has_errors());
  REQUIRE(layers.features.size() == 9);
  const auto conversion = corsa::ngii::convert(layers, {}, diagnostics);
  const auto map = corsa::xodr::Map::build(conversion.map, diagnostics);
  for (const auto& d : diagnostics.all()) {
    INFO(d.format());
    CHECK(d.severity != corsa::Severity::kError);
  }
  REQUIRE(conversion.map.roads.size() == 1);
  const auto& road = conversion.map.roads.front();
  CHECK(conversion.summary.signs == 1);
  CHECK(conversion.summary.objects == 7);

  // B1: a static signal at the board, 2.5 m up, a 50 km/h limit.
  REQUIRE(road.signals.size() == 1);
  const auto& sign = road.signals.front();
  CHECK(sign.id == "B1TEST000001");
  CHECK_FALSE(sign.dynamic);
  const auto at = map.world_pose(0, sign.s, sign.t);
  const double x0 = conversion.map.header.offset_x, y0 = conversion.map.header.offset_y;
  CHECK(at.x + x0 - kX == Approx(50.0).margin(0.05));
  CHECK(at.y + y0 - kY == Approx(-3.3).margin(0.05));
  CHECK(sign.z_offset == Approx(2.5).margin(0.05));
  REQUIRE(sign.value);
  CHECK(*sign.value == 50.0);
  CHECK(sign.unit == "km/h");

  // B3: the crosswalk with its outline (4 corners, road coordinates) and zebra markings.
  const auto* crosswalk = find_object(road, "B3TEST000001");
  REQUIRE(crosswalk != nullptr);
  CHECK(crosswalk->type == "crosswalk");
  REQUIRE(crosswalk->outlines.size() == 1);
  REQUIRE(crosswalk->outlines[0].corners.size() == 4);
  double s_min = 1e9, s_max = -1e9;
  for (const auto& c : crosswalk->outlines[0].corners) {
    s_min = std::min(s_min, c.u);
    s_max = std::max(s_max, c.u);
  }
  CHECK(s_min == Approx(70.0).margin(0.2));
  CHECK(s_max == Approx(74.0).margin(0.2));
  CHECK_FALSE(crosswalk->markings.empty());
  const auto* arrow = find_object(road, "B3TEST000002");
  REQUIRE(arrow != nullptr);
  CHECK(arrow->type == "roadMark");
  CHECK(arrow->subtype == "5371");

  // C3: a guard rail along the road, 0.8 m high, an open outline.
  const auto* rail = find_object(road, "C3TEST000001");
  REQUIRE(rail != nullptr);
  CHECK(rail->type == "railing");
  REQUIRE(rail->outlines.size() == 1);
  CHECK_FALSE(rail->outlines[0].closed);
  CHECK(rail->outlines[0].corners.size() == 3);
  CHECK(rail->outlines[0].corners[0].height == 0.8);

  // C4, C6, A4, A5.
  const auto* bump = find_object(road, "C4TEST000001");
  REQUIRE(bump != nullptr);
  CHECK(bump->subtype == "speedBump");
  const auto* post = find_object(road, "C6TEST000001");
  REQUIRE(post != nullptr);
  CHECK(post->type == "pole");
  CHECK(post->s == Approx(50.0).margin(0.2));
  const auto* walk = find_object(road, "A4TEST000001");
  REQUIRE(walk != nullptr);
  CHECK(walk->outlines[0].fill_type == "pavement");
  const auto* parking = find_object(road, "A5TEST000001");
  REQUIRE(parking != nullptr);
  CHECK(parking->type == "parkingSpace");

  // A3: a bridge record over s 20..40.
  REQUIRE(road.bridges.size() == 1);
  CHECK(road.bridges[0].s == Approx(20.0).margin(1.1));
  CHECK(road.bridges[0].s + road.bridges[0].length == Approx(40.0).margin(1.1));

  // Written and read back, and valid against the ASAM OpenDRIVE 1.7 XSD.
  const fs::path out = dir.path() / "features.xodr";
  corsa::xodr::write_xodr(conversion.map, out);
  corsa::Diagnostics again;
  const auto back = corsa::xodr::Map::load(out, again);
  CHECK(back.road(0).objects.size() == 7);
  CHECK(again.size() == 0);
  const std::string xsd = fs::canonical(fs::path(CORSA_SHARED_DIR) / "schemas" / "asam" /
                                        "OpenDRIVE_1.7" / "opendrive_17_core.xsd")
                              .string();
  const std::string command = std::string(CORSA_XMLLINT) + " --noout --schema " + xsd + " " +
                              out.string() + " 2> " + (dir.path() / "xmllint.txt").string();
  const int status = std::system(command.c_str());
  INFO(corsa::read_file(dir.path() / "xmllint.txt"));
  CHECK(status == 0);
}

TEST_CASE("a feature layer missing a required field is refused with the file named",
          "[ngii][features][errors]") {
  corsa::test::TempDir dir;
  write_area(dir.path());
  corsa::test::rename_dbf_field(dir.path() / "B3_SURFACEMARK.dbf", "Kind", "Sort");
  corsa::Diagnostics diagnostics;
  try {
    corsa::ngii::read_layers(dir.path(), diagnostics);
    FAIL("no error");
  } catch (const corsa::InputError& e) {
    CHECK_THAT(std::string(e.what()),
               Catch::Contains("B3_SURFACEMARK.dbf: error: required field 'Kind' is missing"));
  }
}
