// End to end: `corsa map info|query|render|mesh` on real files.

#include <catch2/catch.hpp>
#include <cmath>

#include "corsa/core/strings.h"
#include "run_corsa.h"

using corsa::test::run_corsa;

namespace {

std::string shared(const std::string& name) {
  return std::string(CORSA_SHARED_DIR) + "/data/xodr/" + name;
}

std::vector<double> numbers(std::string_view line) {
  std::vector<double> values;
  for (const auto field : corsa::split(corsa::trim(line), ',')) {
    values.push_back(corsa::parse_double(field).value_or(NAN));
  }
  return values;
}

}  // namespace

TEST_CASE("corsa map info summarises a map", "[xodr][cli]") {
  const auto result = run_corsa({"map", "info", shared("Town04.xodr")});
  CHECK(result.exit_code == 0);
  CHECK(result.out.find("roads:         276 (223 in junctions)") != std::string::npos);
  CHECK(result.out.find("junctions:     27, default 27") != std::string::npos);
  CHECK(result.out.find("geometry:      arc 380 line 900") != std::string::npos);
  CHECK(result.out.find("georeference:  +proj=tmerc") != std::string::npos);
  CHECK(result.out.find("  driving        ") != std::string::npos);
  CHECK(result.out.find("warnings:      0") != std::string::npos);
}

TEST_CASE("corsa map info lists the load's warnings", "[xodr][cli]") {
  const auto result = run_corsa({"map", "info", shared("Ex_Slip_Lane.xodr")});
  CHECK(result.exit_code == 0);
  CHECK(result.err.find("Ex_Slip_Lane.xodr:333: warning:") != std::string::npos);
  CHECK(result.out.find("warnings:      2") != std::string::npos);
}

TEST_CASE("corsa map query evaluates road,s,t and inverts with --to-lane", "[xodr][cli]") {
  const auto forward = run_corsa({"map", "query", shared("straight_500m.xodr")},
                                 "# road,s,t\n1,100,-1.75\n\n1,250.5,2\n");
  REQUIRE(forward.exit_code == 0);
  const auto lines = corsa::split(corsa::trim(forward.out), '\n');
  REQUIRE(lines.size() == 2);
  const auto first = numbers(lines[0]);
  REQUIRE(first.size() == 4);
  std::string xy;
  for (const auto line : lines) {
    const auto v = numbers(line);
    xy += corsa::format_double(v[0]) + "," + corsa::format_double(v[1]) + "\n";
  }
  const auto back = run_corsa({"map", "query", shared("straight_500m.xodr"), "--to-lane"}, xy);
  REQUIRE(back.exit_code == 0);
  const auto back_lines = corsa::split(corsa::trim(back.out), '\n');
  REQUIRE(back_lines.size() == 2);
  const auto fields = corsa::split(back_lines[0], ',');
  REQUIRE(fields.size() == 4);
  CHECK(fields[0] == "1");
  CHECK(fields[1] == "-1");
  CHECK(corsa::parse_double(fields[2]).value() == Approx(100.0).margin(1e-6));
  CHECK(corsa::parse_double(fields[3]).value() == Approx(-1.75).margin(1e-6));
}

TEST_CASE("corsa map query reads --in files and leaves far points empty", "[xodr][cli]") {
  corsa::test::TempDir dir;
  const auto input = dir.path() / "q.csv";
  std::ofstream(input) << "1e6,1e6\n";
  const auto result =
      run_corsa({"map", "query", shared("straight_500m.xodr"), "--to-lane", "--in", input});
  CHECK(result.exit_code == 0);
  CHECK(result.out == ",,,\n");
}

TEST_CASE("corsa map query rejects bad lines with file:line and prints nothing", "[xodr][cli]") {
  const auto unknown = run_corsa({"map", "query", shared("straight_500m.xodr")}, "1,10,0\nx,1,2\n");
  CHECK(unknown.exit_code == 2);
  CHECK(unknown.out.empty());
  CHECK(unknown.err.find("<stdin>:2: error: no road 'x'") != std::string::npos);
  const auto text = run_corsa({"map", "query", shared("straight_500m.xodr")}, "1,ten,0\n");
  CHECK(text.exit_code == 2);
  CHECK(text.err.find("<stdin>:1: error: 'ten' is not a number") != std::string::npos);
  const auto range = run_corsa({"map", "query", shared("straight_500m.xodr")}, "1,900,0\n");
  CHECK(range.exit_code == 2);
  CHECK(range.err.find("outside road '1'") != std::string::npos);
}

TEST_CASE("corsa map reports bad maps and usage with exit 2", "[xodr][cli]") {
  corsa::test::TempDir dir;
  const auto bad = dir.path() / "bad.xodr";
  std::ofstream(bad) << "<OpenDRIVE>\n<header revMajor=\"1\" revMinor=\"4\"/>\n<road id=\"1\"";
  const auto result = run_corsa({"map", "info", bad});
  CHECK(result.exit_code == 2);
  CHECK(result.err.find("bad.xodr:3: error:") != std::string::npos);
  CHECK(run_corsa({"map", "frobnicate", bad}).exit_code == 2);
  CHECK(run_corsa({"map"}).exit_code == 2);
  CHECK(run_corsa({"map", "--help"}).exit_code == 0);
  CHECK(run_corsa({"map", "info", "--help"}).out.find("map info MAP.xodr") != std::string::npos);
}

TEST_CASE("corsa map holes counts the holes in a map's junctions by kind", "[xodr][cli][holes]") {
  // Town04: mouth wedges between its connecting roads (paved), the 109 m² gore of an on-ramp
  // (kept as an island) and a patch beside a kerbed island (kept).
  const auto result = run_corsa({"map", "holes", shared("Town04.xodr"), "--list"});
  CHECK(result.exit_code == 0);
  CHECK(result.out.find("junction holes: 36, paved 34 (184.2 m2), large 1 (108.7 m2), kerbed 1 "
                        "(11.2 m2), occupied 0 (0.0 m2)") != std::string::npos);
  CHECK(result.out.find("junction,kind,area_m2,width_m,x,y,z\n") != std::string::npos);
  CHECK(result.out.find("459,large,108.65,6.30,319.52,195.43,0.00\n") != std::string::npos);
}
