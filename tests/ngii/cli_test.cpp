// `corsa convert ngii` end to end: the summary line, the corrections report, located errors with
// exit code 2 and no output left behind, and the converted K-City map driven by `corsa run`
// through junctions (scenarios/ngii/kcity_three_junctions.xosc).

#include <catch2/catch.hpp>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "corsa/xodr/map.h"
#include "corsa/xodr/parser.h"
#include "ngii_fixtures.h"
#include "run_corsa.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using corsa::test::ngii_area;
using corsa::test::run_corsa;

namespace {

/// K-City converted once through the CLI (about a second), shared by the test cases.
struct CliConversion {
  corsa::test::TempDir dir;
  corsa::test::ProcessResult result;
  fs::path map() const { return dir.path() / "kcity.xodr"; }
  fs::path report() const { return dir.path() / "kcity-fixes.csv"; }
};

const CliConversion& kcity_cli() {
  static std::unique_ptr<CliConversion> conversion;
  if (!conversion) {
    conversion = std::make_unique<CliConversion>();
    conversion->result =
        run_corsa({"convert", "ngii", ngii_area("kcity").string(), "-o", conversion->map().string(),
                   "--report", conversion->report().string()});
  }
  return *conversion;
}

std::vector<std::vector<std::string>> read_csv(const fs::path& path) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(corsa::test::slurp(path));
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::istringstream fields(line);
    for (std::string cell; std::getline(fields, cell, ',');) {
      cells.push_back(cell);
    }
    rows.push_back(std::move(cells));
  }
  return rows;
}

/// Runs `corsa convert ngii` on `input` into a fresh output path; checks that it failed with
/// exit 2 and left no output, and returns its stderr.
std::string failed_conversion(const fs::path& input, const fs::path& out_dir) {
  const fs::path output = out_dir / "out.xodr";
  const fs::path report = out_dir / "out.csv";
  const auto result = run_corsa(
      {"convert", "ngii", input.string(), "-o", output.string(), "--report", report.string()});
  CHECK(result.exit_code == 2);
  CHECK_FALSE(fs::exists(output));
  CHECK_FALSE(fs::exists(report));
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(out_dir)) {
    ++files;  // no temporary left behind either
  }
  CHECK(files == 0);
  return result.err;
}

}  // namespace

TEST_CASE("corsa convert ngii writes K-City with a summary line and a corrections report",
          "[ngii][cli]") {
  const CliConversion& cli = kcity_cli();
  REQUIRE(cli.result.exit_code == 0);
  CHECK_THAT(cli.result.out, Catch::StartsWith("converted 809 links -> "));
  for (const char* part : {" roads (", " connecting), ", " lanes, ", " junctions + ",
                           " controllers), ", "fallback 0; ", " source defects, ",
                           " relabelled); largest fit error ", " m (lane centres)"}) {
    CHECK_THAT(cli.result.out, Catch::Contains(part));
  }
  CHECK_THAT(cli.result.out, Catch::Contains("corrections: " + cli.report().string()));
  // The output loads in Corsa without errors or warnings.
  corsa::Diagnostics diagnostics;
  const auto data = corsa::xodr::parse_xodr(cli.map(), diagnostics);
  const auto map = corsa::xodr::Map::build(data, diagnostics);
  CHECK(map.road_count() > 600);
  CHECK(map.junction_count() > 50);
  for (const auto& d : diagnostics.all()) {
    INFO(d.message);
    CHECK(d.severity == corsa::Severity::kNote);
  }
  // The report: a header and one row per repair, each naming an A2 link.
  const auto rows = read_csv(cli.report());
  REQUIRE(rows.size() > 100);
  CHECK(rows[0] ==
        std::vector<std::string>{"link_id", "field", "old_value", "new_value", "reason", "record",
                                 "kind"});
  for (size_t i = 1; i < rows.size(); ++i) {
    CHECK_THAT(rows[i][0], Catch::StartsWith("A219BS01"));
  }
}

TEST_CASE("corsa convert ngii is byte for byte repeatable", "[ngii][cli]") {
  const CliConversion& cli = kcity_cli();
  REQUIRE(cli.result.exit_code == 0);
  corsa::test::TempDir dir;
  const auto again = run_corsa({"convert", "ngii", ngii_area("kcity").string(), "-o",
                                (dir.path() / "k.xodr").string(), "--quiet"});
  REQUIRE(again.exit_code == 0);
  CHECK(again.out.empty());
  CHECK(corsa::test::slurp(dir.path() / "k.xodr") == corsa::test::slurp(cli.map()));
}

TEST_CASE("bad NGII input fails with exit 2, the file and record named, and no output",
          "[ngii][cli][errors]") {
  corsa::test::TempDir in;
  corsa::test::TempDir out;
  corsa::test::copy_layers(ngii_area("kcity"), in.path(), {"A1_NODE", "A2_LINK"});
  const std::string a2 = (in.path() / "A2_LINK").string();

  SECTION("a truncated .shp") {
    corsa::test::truncate_file(a2 + ".shp", 900000);
    const std::string err = failed_conversion(in.path(), out.path());
    CHECK_THAT(err, Catch::Contains("A2_LINK.shp: record "));
    CHECK_THAT(err, Catch::Contains(": error: truncated or corrupt"));
  }
  SECTION("a .dbf without a required field") {
    corsa::test::rename_dbf_field(a2 + ".dbf", "FromNodeID", "FromNode");
    CHECK_THAT(failed_conversion(in.path(), out.path()),
               Catch::Contains("A2_LINK.dbf: error: required field 'FromNodeID' is missing"));
  }
  SECTION("a link pointing to an absent node") {
    corsa::test::set_dbf_text(a2 + ".dbf", 40, "FromNodeID", "A119XX000000");
    CHECK_THAT(failed_conversion(in.path(), out.path()),
               Catch::Contains("A2_LINK.dbf: record 40: error: link A219BS010041: FromNodeID "
                               "'A119XX000000' is not a node in A1_NODE.dbf"));
  }
  SECTION("a missing .shx") {
    fs::remove(a2 + ".shx");
    CHECK_THAT(failed_conversion(in.path() / "A2_LINK.shp", out.path()),
               Catch::Contains("A2_LINK.shx: error: missing Shapefile index"));
  }
  SECTION("an unknown source format is a usage error") {
    const auto result =
        run_corsa({"convert", "osm", in.path().string(), "-o", (out.path() / "x.xodr").string()});
    CHECK(result.exit_code != 0);
    CHECK_THAT(result.err, Catch::Contains("unknown source format 'osm'"));
    CHECK_FALSE(fs::exists(out.path() / "x.xodr"));
  }
}

TEST_CASE("a car on the converted K-City map follows its route through four junctions",
          "[ngii][cli][scenario]") {
  const CliConversion& cli = kcity_cli();
  REQUIRE(cli.result.exit_code == 0);
  corsa::test::TempDir dir;
  const fs::path record = dir.path() / "run.csv";
  const auto run =
      run_corsa({"run", "scenarios/ngii/kcity_three_junctions.xosc", "--param",
                 "KCityMap=" + cli.map().string(), "--record", record.string(), "--quiet"});
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  CHECK(run.err.find("warning") == std::string::npos);  // route laid, map clean

  corsa::Diagnostics diagnostics;
  const auto data = corsa::xodr::parse_xodr(cli.map(), diagnostics);
  std::map<std::string, std::string> junction_of;  // road id -> junction id ("-1": none)
  std::map<std::string, std::string> name_of;      // road id -> first source link
  for (const auto& road : data.roads) {
    junction_of[road.id] = road.junction;
    name_of[road.id] = road.name;
  }
  const auto rows = read_csv(record);
  REQUIRE(rows.size() > 100);
  REQUIRE(rows[0].size() >= 13);
  CHECK(rows[0][9] == "road");
  std::vector<std::string> roads;  // road ids in driving order, consecutive repeats dropped
  for (size_t i = 1; i < rows.size(); ++i) {
    REQUIRE(rows[i].size() >= 11);
    CHECK_FALSE(rows[i][9].empty());  // on a lane all the way
    if (roads.empty() || roads.back() != rows[i][9]) {
      roads.push_back(rows[i][9]);
    }
  }
  // It starts on the street of link A219BS010029, alternates ordinary roads and connecting
  // roads, and crosses four different junctions.
  REQUIRE_FALSE(roads.empty());
  CHECK(name_of[roads.front()] == "A219BS010029");
  std::vector<std::string> junctions;
  for (const auto& road : roads) {
    REQUIRE(junction_of.contains(road));
    if (junction_of[road] != "-1") {
      junctions.push_back(junction_of[road]);
    }
  }
  CHECK(junctions.size() >= 3);
  CHECK(std::set<std::string>(junctions.begin(), junctions.end()).size() == junctions.size());
  CHECK(junctions.size() == 4);
  // The run ended because the street ended (the stop trigger), not at the time-out, standing.
  const auto& last = rows.back();
  CHECK(std::stod(last[0]) < 100.0);
  CHECK(std::stod(last[8]) == 0.0);
  CHECK(junction_of[last[9]] == "-1");
}
