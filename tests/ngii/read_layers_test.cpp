#include <catch2/catch.hpp>
#include <filesystem>

#include "corsa/ngii/layers.h"
#include "cp949.h"
#include "ngii_fixtures.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using corsa::Diagnostics;
using corsa::InputError;
using corsa::ngii::read_layers;
using corsa::test::ngii_area;

namespace {

/// The error a bad input gives, formatted as the CLI prints it.
std::string error_of(const fs::path& path) {
  Diagnostics diagnostics;
  try {
    read_layers(path, diagnostics);
  } catch (const InputError& error) {
    return error.diagnostic().format();
  }
  return "no error";
}

size_t count_filled(const std::vector<corsa::ngii::Link>& links, bool right) {
  size_t n = 0;
  for (const auto& link : links) {
    n += !(right ? link.right_id : link.left_id).empty();
  }
  return n;
}

}  // namespace

TEST_CASE("the K-City layers are read with their counts, CRS and heights", "[ngii][import]") {
  Diagnostics diagnostics;
  const auto layers = read_layers(ngii_area("kcity"), diagnostics);
  CHECK(layers.nodes.size() == 712);
  CHECK(layers.links.size() == 809);
  CHECK(layers.marks.size() == 1574);
  CHECK(layers.lights.size() == 81);
  CHECK_THAT(layers.crs.proj_string, Catch::Contains("+proj=utm") && Catch::Contains("+zone=52"));
  CHECK(layers.crs.authority == "EPSG:32652");
  CHECK(layers.crs.name == "WGS 84 / UTM zone 52N");
  // The data README: 180 R / 190 L filled in K-City; Z between 22.97 and 33.23 m.
  CHECK(count_filled(layers.links, true) == 180);
  CHECK(count_filled(layers.links, false) == 190);
  double z_min = 1e9, z_max = -1e9;
  size_t vertices = 0;
  for (const auto& link : layers.links) {
    for (const auto& p : link.points) {
      z_min = std::min(z_min, p.z);
      z_max = std::max(z_max, p.z);
    }
    vertices += link.points.size();
  }
  CHECK(vertices == 74119);
  CHECK(z_min == Approx(22.97).margin(0.01));
  CHECK(z_max == Approx(33.23).margin(0.01));
  const auto& first = layers.links.front();
  CHECK(first.id == "A219BS010001");
  CHECK(first.link_type == "6");
  CHECK(first.max_speed == 40);
  CHECK(first.lane_no == 1);
  CHECK(first.length_attr == Approx(207.32));
  CHECK(layers.lights.front().link_id == "A219BS010645");
}

TEST_CASE("Sangam's odd field-name case (L_LinKID, R_linkID, PostID) is tolerated",
          "[ngii][import]") {
  Diagnostics diagnostics;
  const auto layers = read_layers(ngii_area("seoul_sangam_testbed"), diagnostics);
  CHECK(layers.nodes.size() == 1754);
  CHECK(layers.links.size() == 1882);
  // 27 B2 records have no geometry (the first is 1819): skipped with one warning naming it.
  CHECK(layers.marks.size() == 3620 - 27);
  bool warned = false;
  for (const auto& diagnostic : diagnostics.all()) {
    warned = warned || (diagnostic.record == 1819 &&
                        diagnostic.file.find("B2_SURFACELINEMARK.shp") != std::string::npos);
  }
  CHECK(warned);
  CHECK(layers.lights.size() == 448);
  CHECK(count_filled(layers.links, true) == 1004);
  CHECK(count_filled(layers.links, false) == 1019);
  size_t marks_with_right = 0;
  for (const auto& mark : layers.marks) {
    marks_with_right += !mark.right_link.empty();
  }
  CHECK(marks_with_right == 1945 - 3);  // 3 of the 27 skipped marks had an R_linkID
  CHECK(layers.crs.authority == "EPSG:32652");
}

TEST_CASE("a path to A2_LINK.shp works like its folder", "[ngii][import]") {
  Diagnostics diagnostics;
  const auto layers = read_layers(ngii_area("kcity") / "A2_LINK.shp", diagnostics);
  CHECK(layers.links.size() == 809);
  CHECK(layers.dir == ngii_area("kcity"));
}

TEST_CASE("CP949 text is decoded to UTF-8", "[ngii][import][cp949]") {
  corsa::ngii::detail::Cp949Decoder decoder;
  bool invalid = false;
  // 새한항업컨소시엄, the Maker of both areas, as CP949 bytes.
  CHECK(decoder.decode("\xBB\xF5\xC7\xD1\xC7\xD7\xBE\xF7\xC4\xC1\xBC\xD2\xBD\xC3\xBE\xF6",
                       &invalid) == "새한항업컨소시엄");
  CHECK_FALSE(invalid);
  CHECK(decoder.decode("A219BS010001") == "A219BS010001");
  CHECK(decoder.decode("ab\xFF", &invalid) == "ab\xEF\xBF\xBD");
  CHECK(invalid);
}

TEST_CASE("bad layer files give errors naming the file and record", "[ngii][import][errors]") {
  corsa::test::TempDir dir;
  corsa::test::copy_layers(ngii_area("kcity"), dir.path(), {"A1_NODE", "A2_LINK"});
  const fs::path a2 = dir.path() / "A2_LINK";

  SECTION("the copy itself is fine and B2/C1 are optional") {
    Diagnostics diagnostics;
    const auto layers = read_layers(dir.path(), diagnostics);
    CHECK(layers.links.size() == 809);
    CHECK(layers.marks.empty());
    CHECK(layers.lights.empty());
  }
  SECTION("missing .shx") {
    fs::remove(a2.string() + ".shx");
    CHECK_THAT(error_of(dir.path()),
               Catch::Contains("A2_LINK.shx: error: missing Shapefile index"));
  }
  SECTION("missing .dbf") {
    fs::remove(a2.string() + ".dbf");
    CHECK_THAT(error_of(dir.path()), Catch::Contains("A2_LINK.dbf: error: missing"));
  }
  SECTION("missing .prj") {
    fs::remove(a2.string() + ".prj");
    CHECK_THAT(error_of(dir.path()), Catch::Contains("A2_LINK.prj: error: missing projection"));
  }
  SECTION("truncated .shp") {
    corsa::test::truncate_file(a2.string() + ".shp", 900000);
    CHECK_THAT(error_of(dir.path()),
               Catch::Matches(".*A2_LINK\\.shp: record [0-9]+: error: truncated or corrupt.*"));
  }
  SECTION("wrong shape type") {
    for (const char* ext : {".shp", ".shx"}) {
      fs::copy_file(dir.path() / ("A1_NODE" + std::string(ext)), a2.string() + ext,
                    fs::copy_options::overwrite_existing);
    }
    CHECK_THAT(error_of(dir.path()),
               Catch::Contains("A2_LINK.shp: error: wrong shape type 11 (expected PolyLine"));
  }
  SECTION("a missing field") {
    corsa::test::rename_dbf_field(a2.string() + ".dbf", "LaneNo", "LaneNr");
    CHECK_THAT(error_of(dir.path()),
               Catch::Contains("A2_LINK.dbf: error: required field 'LaneNo' is missing"));
  }
  SECTION("a link pointing to an absent node") {
    corsa::test::set_dbf_text(a2.string() + ".dbf", 17, "ToNodeID", "A119XX999999");
    CHECK_THAT(error_of(dir.path()),
               Catch::EndsWith("A2_LINK.dbf: record 17: error: link A219BS010018: ToNodeID "
                               "'A119XX999999' is not a node in A1_NODE.dbf"));
  }
  SECTION("a number field holding text") {
    corsa::test::set_dbf_text(a2.string() + ".dbf", 3, "LaneNo", "x");
    CHECK_THAT(error_of(dir.path()),
               Catch::Contains("A2_LINK.dbf: record 3: error: field 'LaneNo' is not an integer"));
  }
  SECTION("a missing folder") {
    CHECK_THAT(error_of(dir.path() / "nope"), Catch::Contains("nope: error: no such file"));
  }
}
