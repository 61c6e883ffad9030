// `corsa convert ngii` end to end: the summary line, the corrections report, located errors with
// exit code 2 and no output left behind, and the converted K-City map driven by `corsa run`
// through junctions (scenarios/ngii/kcity_three_junctions.xosc).

#include <array>
#include <catch2/catch.hpp>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "corsa/core/atomic_file.h"
#include "corsa/core/strings.h"
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
  CHECK(rows[0] == std::vector<std::string>{"link_id", "field", "old_value", "new_value", "reason",
                                            "record", "kind"});
  for (size_t i = 1; i < rows.size(); ++i) {
    CHECK_THAT(rows[i][0], Catch::StartsWith("A219BS01"));
  }
}

TEST_CASE("both areas convert without a warning; repairs are one note line, each with --verbose",
          "[ngii][cli][notes]") {
  for (const char* area : {"kcity", "seoul_sangam_testbed"}) {
    INFO(area);
    corsa::test::TempDir dir;
    const fs::path report = dir.path() / "fixes.csv";
    const auto plain = run_corsa({"convert", "ngii", ngii_area(area).string(), "-o",
                                  (dir.path() / "a.xodr").string(), "--report", report.string()});
    REQUIRE(plain.exit_code == 0);
    CHECK(plain.err.find("warning") == std::string::npos);
    // One line on stderr counts the located notes (the progress bar goes elsewhere when not a
    // terminal).
    CHECK_THAT(plain.err, Catch::Contains(" located notes (source defects repaired or left out"));
    CHECK(plain.err.find(": record ") == std::string::npos);
    // --verbose prints one located line per repaired defect, as the report lists them.
    const auto verbose = run_corsa({"convert", "ngii", ngii_area(area).string(), "-o",
                                    (dir.path() / "b.xodr").string(), "--verbose"});
    REQUIRE(verbose.exit_code == 0);
    size_t defects = 0;
    for (const auto& row : read_csv(report)) {
      defects += row.back() == "defect";
    }
    size_t located = 0;
    for (size_t at = verbose.err.find("A2_LINK.dbf: record "); at != std::string::npos;
         at = verbose.err.find("A2_LINK.dbf: record ", at + 1)) {
      located += verbose.err.compare(verbose.err.find(": ", at + 12) + 2, 6, "note: ") == 0 &&
                 verbose.err.find("' -> '", at) < verbose.err.find('\n', at);
    }
    CHECK(defects > 300);
    CHECK(located == defects);
    CHECK(corsa::test::slurp(dir.path() / "a.xodr") == corsa::test::slurp(dir.path() / "b.xodr"));
  }
}

TEST_CASE("corsa convert ngii --strict refuses every repair with its record and writes nothing",
          "[ngii][cli][notes][errors]") {
  corsa::test::TempDir out;
  const fs::path output = out.path() / "k.xodr";
  const auto result = run_corsa(
      {"convert", "ngii", ngii_area("kcity").string(), "-o", output.string(), "--strict"});
  CHECK(result.exit_code == 2);
  CHECK_FALSE(fs::exists(output));
  CHECK_THAT(result.err,
             Catch::Contains("A2_LINK.dbf: record 0: error: link A219BS010001: geometry '260 "
                             "vertices' -> '259 vertices': duplicate consecutive vertices removed "
                             "(refused by --strict)"));
  // Every one, in one pass.
  size_t errors = 0;
  for (size_t at = result.err.find(": error: "); at != std::string::npos;
       at = result.err.find(": error: ", at + 1)) {
    ++errors;
  }
  CHECK(errors > 300);
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

namespace {

using Edge = std::pair<std::pair<std::string, int>, std::pair<std::string, int>>;

/// The lane-to-lane links a reader of OpenDRIVE 1.4 follows (libOpenDRIVE's routing graph): the
/// first <predecessor>/<successor> of each lane across road links of type road with a contact
/// point, and junction connections that name a connectingRoad.
std::set<Edge> legacy_edges(const corsa::xodr::MapData& data) {
  std::set<Edge> edges;
  for (const auto& road : data.roads) {
    for (const auto& lane : road.lane_sections.front().lanes) {
      if (!lane.successors.empty() &&
          road.successor.element_type == corsa::xodr::LinkElement::kRoad &&
          road.successor.contact_point != corsa::xodr::ContactPoint::kNone) {
        edges.insert({{road.id, lane.id}, {road.successor.element_id, lane.successors.front()}});
      }
      if (!lane.predecessors.empty() &&
          road.predecessor.element_type == corsa::xodr::LinkElement::kRoad &&
          road.predecessor.contact_point != corsa::xodr::ContactPoint::kNone) {
        edges.insert(
            {{road.predecessor.element_id, lane.predecessors.front()}, {road.id, lane.id}});
      }
    }
  }
  for (const auto& junction : data.junctions) {
    for (const auto& c : junction.connections) {
      for (const auto& link : c.lane_links) {
        if (!c.connecting_road.empty()) {
          edges.insert({{c.incoming_road, link.from}, {c.connecting_road, link.to}});
        }
      }
    }
  }
  return edges;
}

/// Every join of the lane graph from the end of one road to the start of another.
std::set<Edge> graph_edges(const corsa::xodr::Map& map) {
  std::set<Edge> edges;
  const auto& graph = map.lane_graph();
  for (corsa::xodr::LaneNode node = 0; node < graph.size(); ++node) {
    const auto& from = graph.info(node).lane;
    for (const auto& end : graph.successors(node)) {
      const auto& to = graph.info(end.node).lane;
      if (end.at_start && to.road != from.road) {
        edges.insert({{map.road(from.road).id, from.lane}, {map.road(to.road).id, to.lane}});
      }
    }
  }
  return edges;
}

}  // namespace

TEST_CASE("with --compat 1.4 a pre-1.7 reader follows every lane link", "[ngii][cli][compat]") {
  const CliConversion& cli = kcity_cli();
  REQUIRE(cli.result.exit_code == 0);
  corsa::test::TempDir dir;
  const auto old = dir.path() / "kcity-1.4.xodr";
  const auto run = run_corsa({"convert", "ngii", ngii_area("kcity").string(), "-o", old.string(),
                              "--compat", "1.4", "--quiet"});
  REQUIRE(run.exit_code == 0);
  corsa::Diagnostics diagnostics;
  const auto modern = corsa::xodr::Map::load(cli.map(), diagnostics);
  const std::set<Edge> all = graph_edges(modern);
  REQUIRE(all.size() > 900);
  // The default output uses linkedRoad (direct junctions): such a reader misses those links.
  const std::set<Edge> from_modern = legacy_edges(modern.data());
  size_t missed_modern = 0;
  for (const Edge& e : all) {
    missed_modern += !from_modern.contains(e);
  }
  CHECK(missed_modern > 100);
  const auto compat_data = corsa::xodr::parse_xodr(old, diagnostics);
  CHECK(compat_data.header.rev_minor == 4);
  const std::set<Edge> from_compat = legacy_edges(compat_data);
  // Corsa reads it without warnings, and a pre-1.7 reader follows every join of that lane
  // graph: the default output's, except that a lane only a second <connection> feeds in 1.8
  // (K-City's A219BS010320) is a connecting road of its own, one <connection> for each.
  corsa::Diagnostics again;
  const auto reloaded = corsa::xodr::Map::load(old, again);
  const std::set<Edge> compat_graph = graph_edges(reloaded);
  CHECK(again.size() == 0);
  CHECK(compat_graph.size() == all.size());
  std::vector<std::string> missed;
  for (const Edge& e : compat_graph) {
    if (!from_compat.contains(e)) {
      missed.push_back(e.first.first + ":" + std::to_string(e.first.second) + " -> " +
                       e.second.first + ":" + std::to_string(e.second.second));
    }
  }
  INFO((missed.empty() ? std::string("none") : missed.front()));
  CHECK(missed.empty());
  // No connecting road is entered through more than one <connection> at either end (OpenDRIVE
  // 1.7 §10.3 allows one per connecting road; a road with lanes in both directions is entered at
  // both ends, one each). The legacy form of a direct junction names ordinary roads, which
  // several roads may merge into: not counted.
  std::map<std::string, std::array<size_t, 2>> connections_per_road;  // at start, at end
  for (const auto& road : compat_data.roads) {
    if (road.junction != "-1") {
      connections_per_road[road.id] = {0, 0};
    }
  }
  for (const auto& junction : compat_data.junctions) {
    for (const auto& c : junction.connections) {
      if (connections_per_road.contains(c.connecting_road)) {
        ++connections_per_road[c.connecting_road]
                              [c.contact_point == corsa::xodr::ContactPoint::kEnd ? 1 : 0];
      }
    }
  }
  REQUIRE(connections_per_road.size() > 300);
  for (const auto& [road, count] : connections_per_road) {
    INFO(road);
    CHECK(count[0] <= 1);
    CHECK(count[1] <= 1);
  }
  const auto bad = run_corsa({"convert", "ngii", ngii_area("kcity").string(), "-o",
                              (dir.path() / "x.xodr").string(), "--compat", "1.5"});
  CHECK(bad.exit_code == 2);
  CHECK_THAT(bad.err, Catch::Contains("--compat takes 1.4"));
}

TEST_CASE("corsa convert ngii --placements lists where every A2 link went", "[ngii][cli]") {
  corsa::test::TempDir dir;
  const auto csv = dir.path() / "placements.csv";
  const auto run =
      run_corsa({"convert", "ngii", ngii_area("kcity").string(), "-o",
                 (dir.path() / "k.xodr").string(), "--placements", csv.string(), "--quiet"});
  REQUIRE(run.exit_code == 0);
  const auto rows = read_csv(csv);
  REQUIRE(rows.size() > 800);
  CHECK(rows[0] == std::vector<std::string>{"link_id", "road_id", "lane_section", "lane_id",
                                            "s_start", "s_end"});
  corsa::Diagnostics diagnostics;
  const auto map = corsa::xodr::Map::load(dir.path() / "k.xodr", diagnostics);
  std::set<std::string> links;
  for (size_t i = 1; i < rows.size(); ++i) {
    REQUIRE(rows[i].size() == 6);
    links.insert(rows[i][0]);
    const auto road = map.find_road(rows[i][1]);
    REQUIRE(road);
    const double s0 = std::stod(rows[i][4]), s1 = std::stod(rows[i][5]);
    CHECK(s0 <= s1);
    CHECK(s1 <= map.road(*road).length + 1e-3);
    // The lane names that link in its provenance.
    const auto* lane = map.lane(corsa::xodr::LaneRef{static_cast<uint32_t>(*road),
                                                     static_cast<uint32_t>(std::stoi(rows[i][2])),
                                                     std::stoi(rows[i][3])});
    REQUIRE(lane != nullptr);
    bool named = false;
    for (const auto& d : lane->user_data) {
      named = named || (d.code == "ngii:link" && d.value == rows[i][0]);
    }
    CHECK(named);
  }
  CHECK(links.size() == 809);
}

TEST_CASE("a .shx whose entries do not point at the .shp records is refused",
          "[ngii][cli][errors]") {
  corsa::test::TempDir in;
  corsa::test::TempDir out;
  corsa::test::copy_layers(ngii_area("kcity"), in.path(), {"A1_NODE", "A2_LINK"});
  // The entries of the index in reverse order: every shape would meet another record's
  // attributes.
  const auto shx = in.path() / "A2_LINK.shx";
  std::vector<char> bytes = corsa::test::read_bytes(shx);
  const size_t entries = (bytes.size() - 100) / 8;
  std::vector<char> reversed(bytes.begin(), bytes.begin() + 100);
  for (size_t i = entries; i-- > 0;) {
    reversed.insert(reversed.end(), bytes.begin() + 100 + 8 * static_cast<std::ptrdiff_t>(i),
                    bytes.begin() + 108 + 8 * static_cast<std::ptrdiff_t>(i));
  }
  corsa::test::write_bytes(shx, reversed);
  const std::string err = failed_conversion(in.path(), out.path());
  CHECK_THAT(err, Catch::Contains("A2_LINK.shx: record 0: error: the index says offset"));
  CHECK_THAT(err, Catch::Contains("but A2_LINK.shp has record 1"));
}

TEST_CASE("map query --to-lane with z resolves Sangam's stacked roads", "[ngii][cli][query]") {
  corsa::test::TempDir dir;
  const auto map_path = dir.path() / "sangam.xodr";
  REQUIRE(run_corsa({"convert", "ngii", ngii_area("seoul_sangam_testbed").string(), "-o",
                     map_path.string(), "--quiet"})
              .exit_code == 0);
  corsa::Diagnostics diagnostics;
  const auto map = corsa::xodr::Map::load(map_path, diagnostics);
  // A point in the middle of the underground road's lane, and the road above it.
  const corsa::xodr::Road* under = nullptr;
  for (const auto& road : map.data().roads) {
    for (const auto& tunnel : road.tunnels) {
      if (tunnel.type == "underpass" && under == nullptr) {
        under = &road;
      }
    }
  }
  REQUIRE(under != nullptr);
  // A point on the underground road's lane with another road's lane above it.
  const size_t index = *map.find_road(under->id);
  corsa::xodr::WorldPose pose;
  bool found = false;
  for (double s = 0.0; s < under->length && !found; s += 2.0) {
    const auto span = map.lane_span(index, s, -1);
    REQUIRE(span);
    pose = map.world_pose(index, s, span->t_center());
    corsa::xodr::LocateOptions high;
    high.z = pose.z + 20.0;
    const auto top = map.locate(pose.x, pose.y, high);
    found = top && top->road != index && top->distance == 0.0 &&
            map.world_pose(top->road, top->s, top->t).z > pose.z + 3.0;
  }
  REQUIRE(found);
  const std::string query = corsa::format_double(pose.x) + "," + corsa::format_double(pose.y);
  const auto file = dir.path() / "q.csv";
  corsa::write_file_atomic(file, query + "," + corsa::format_double(pose.z) + "\n" + query + "," +
                                     corsa::format_double(pose.z + 20.0) + "\n" + query + "\n");
  const auto run =
      run_corsa({"map", "query", map_path.string(), "--to-lane", "--in", file.string()});
  REQUIRE(run.exit_code == 0);
  std::istringstream lines(run.out);
  std::string low, high, plain;
  std::getline(lines, low);
  std::getline(lines, high);
  std::getline(lines, plain);
  CHECK_THAT(low, Catch::StartsWith(under->id + ",-1,"));
  CHECK_THAT(high, !Catch::StartsWith(under->id + ","));
  CHECK_FALSE(high.empty());
}
