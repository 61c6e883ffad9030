#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "corsa/core/atomic_file.h"
#include "corsa/core/diagnostic.h"
#include "corsa/suite/suite.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using corsa::InputError;
using corsa::suite::load_suite;
using corsa::suite::Metric;
using corsa::suite::parse_suite_manifest;

namespace {

const fs::path kFixtures = fs::path(CORSA_SOURCE_DIR) / "tests" / "suite" / "fixtures";

// The located error of a manifest given as text (read as if it were fixtures/inline.xml).
std::string error_of(const std::string& xml) {
  try {
    parse_suite_manifest(xml, kFixtures / "inline.xml");
  } catch (const InputError& error) {
    return error.diagnostic().format();
  }
  return "no error";
}

std::string test_with(const std::string& body, const std::string& attributes = "") {
  return "<Suite version=\"1\" name=\"s\">\n"
         "  <Test name=\"t\" scenario=\"../../sweep/fixtures/follow.xosc\"" +
         attributes + ">\n" + body + "  </Test>\n</Suite>\n";
}

}  // namespace

TEST_CASE("a manifest becomes tests with run options, parameters and expectations",
          "[suite][manifest]") {
  const auto suite = load_suite(kFixtures / "suite.xml");
  CHECK(suite.name == "fixture_suite");
  REQUIRE(suite.tests.size() == 2);
  const auto& calm = suite.tests[0];
  CHECK(calm.name == "calm");
  CHECK(calm.scenario == (kFixtures / "../../sweep/fixtures/follow.xosc").lexically_normal());
  CHECK(calm.simulation.dt == 0.02);  // from the suite
  CHECK(calm.simulation.duration == 3600.0);
  CHECK(calm.expect.end_reason == corsa::engine::EndReason::kStopTrigger);
  CHECK(calm.expect.collision == false);
  REQUIRE(calm.expect.metrics.size() == 3);
  CHECK(calm.expect.metrics[0].metric == Metric::kMaxDeceleration);
  CHECK(calm.expect.metrics[0].min == 3.9);
  CHECK(calm.expect.metrics[1].max == std::nullopt);
  REQUIRE(calm.golden);
  CHECK(calm.golden->file == kFixtures / "goldens" / "calm.csv");
  CHECK(calm.golden->every == 20);
  CHECK(calm.golden->tolerances.value[0] == 0.01);
  const auto& crash = suite.tests[1];
  CHECK(crash.ego == "Ego");
  CHECK(crash.simulation.duration == 30.0);
  CHECK(crash.simulation.seed == 3);
  CHECK(crash.parameters == corsa::sweep::ParameterValues{{"Brake_Rate", "0.5"}});
  CHECK_FALSE(crash.golden);
}

TEST_CASE("golden tolerances come from the golden's attributes and Tolerance elements",
          "[suite][manifest]") {
  const auto suite = parse_suite_manifest(
      test_with("    <Golden file=\"g/x.csv\" position=\"0.5\" heading=\"0.1\" speed=\"0.2\">\n"
                "      <Tolerance column=\"y\" value=\"2\"/>\n    </Golden>\n"),
      kFixtures / "inline.xml");
  const auto& golden = *suite.tests.at(0).golden;
  CHECK(golden.file == kFixtures / "g" / "x.csv");
  const auto& t = golden.tolerances;
  CHECK(t.value[*corsa::suite::Tolerances::column("x")] == 0.5);
  CHECK(t.value[*corsa::suite::Tolerances::column("y")] == 2.0);
  CHECK(t.value[*corsa::suite::Tolerances::column("h")] == 0.1);
  CHECK(t.value[*corsa::suite::Tolerances::column("speed")] == 0.2);
  CHECK(t.value[*corsa::suite::Tolerances::column("t")] == 0.5);
}

TEST_CASE("schema violations in a manifest are located", "[suite][manifest]") {
  const std::string file = (kFixtures / "inline.xml").string();
  CHECK(error_of(test_with("    <Expect endReason=\"crashed\"/>\n")) ==
        file +
            ":3: error: attribute 'endReason' of <Expect> is 'crashed'; expected one of "
            "'stopTrigger', 'duration', 'storiesComplete' [in Suite/Test/Expect]");
  CHECK(error_of(test_with("    <Expect/>\n    <Parameter name=\"a\" value=\"1\"/>\n"))
            .find(file + ":4: error: element <Parameter> is not allowed") == 0);
  CHECK(error_of(test_with("    <Metric name=\"min_ttc\" min=\"1\"/>\n"))
            .find(":3: error: element <Metric> is not allowed in <Test>") != std::string::npos);
  CHECK(error_of("<Suite version=\"1\" name=\"s\">\n  <Test scenario=\"x\"/>\n</Suite>\n")
            .find(":2: error: <Test> needs the attribute 'name'") != std::string::npos);
  CHECK(error_of("<Suite version=\"2\" name=\"s\"/>").find("attribute 'version'") !=
        std::string::npos);
  CHECK(error_of("<Suite version=\"1\" name=\"s\"></Suite>").find("is missing <Test>") !=
        std::string::npos);
  // Steps are at least 0.1 ms: dt="1e-300" ran until killed.
  CHECK(error_of(test_with("", " dt=\"0\"")).find("below the minimum") != std::string::npos);
  CHECK(error_of(test_with("", " dt=\"1e-300\"")).find("below the minimum") != std::string::npos);
  CHECK(error_of("<Suite version=\"1\" name=\"s\">\n<Test").find(":2: error: not well-formed") !=
        std::string::npos);
  CHECK(error_of("<Tests/>").find("expected the root element <Suite>") != std::string::npos);
}

TEST_CASE("manifest errors beyond the schema are located too", "[suite][manifest]") {
  CHECK(error_of(test_with("    <Expect>\n      <Metric name=\"min_ttc\"/>\n    </Expect>\n"))
            .find(":4: error: <Metric> needs min, max or both") != std::string::npos);
  CHECK(error_of(test_with("    <Expect>\n      <Metric name=\"min_ttc\" min=\"3\" max=\"1\"/>\n"
                           "    </Expect>\n"))
            .find(":4: error: <Metric> min is above max") != std::string::npos);
  CHECK(error_of(test_with("    <Golden>\n      <Tolerance column=\"x\" value=\"1\"/>\n"
                           "      <Tolerance column=\"x\" value=\"2\"/>\n    </Golden>\n"))
            .find(":5: error: tolerance of column 'x' given twice") != std::string::npos);
  CHECK(error_of(test_with("    <Parameter name=\"Gap\" value=\"1\"/>\n"
                           "    <Parameter name=\"Gap\" value=\"2\"/>\n"))
            .find(":4: error: parameter 'Gap' is set twice") != std::string::npos);
  CHECK(error_of("<Suite version=\"1\" name=\"s\">\n"
                 "  <Test name=\"a\" scenario=\"../../sweep/fixtures/follow.xosc\"/>\n"
                 "  <Test name=\"a\" scenario=\"../../sweep/fixtures/follow.xosc\"/>\n</Suite>\n")
            .find(":3: error: test name 'a' is used twice") != std::string::npos);
  CHECK(error_of("<Suite version=\"1\" name=\"s\">\n  <Test name=\"a\" scenario=\"gone.xosc\"/>\n"
                 "</Suite>\n")
            .find(":2: error: scenario 'gone.xosc' of test 'a' not found") != std::string::npos);
}

TEST_CASE("a folder without a manifest runs its scenarios with their goldens", "[suite][folder]") {
  corsa::test::TempDir dir;
  const fs::path sweep_fixtures = fs::path(CORSA_SOURCE_DIR) / "tests" / "sweep" / "fixtures";
  // The scenario refers to its map and catalogs relatively: give the copies the same neighbours.
  fs::create_symlink(sweep_fixtures / "catalogs", dir.path() / "catalogs");
  std::string scenario = corsa::read_file(sweep_fixtures / "follow.xosc");
  const std::string map = "../../../scenarios/maps/motorway_2km.xodr";
  scenario.replace(scenario.find(map), map.size(),
                   (fs::path(CORSA_SOURCE_DIR) / "scenarios/maps/motorway_2km.xodr").string());
  corsa::write_file_atomic(dir.path() / "b_second.xosc", scenario);
  corsa::write_file_atomic(dir.path() / "a_first.xosc", scenario);
  fs::copy_file(sweep_fixtures / "grid.xosc", dir.path() / "c_distribution.xosc");
  fs::create_directories(dir.path() / "goldens");
  corsa::write_file_atomic(dir.path() / "goldens" / "b_second.csv", "x");
  const auto suite = load_suite(dir.path());
  REQUIRE(suite.tests.size() == 2);
  CHECK(suite.manifest.empty());
  CHECK(suite.tests[0].name == "a_first");
  CHECK_FALSE(suite.tests[0].golden);
  CHECK(suite.tests[1].name == "b_second");
  REQUIRE(suite.tests[1].golden);
  CHECK(suite.tests[1].golden->file.filename() == "b_second.csv");

  corsa::test::TempDir empty;
  CHECK_THROWS_WITH(load_suite(empty.path()), Catch::Contains("no suite.xml and no scenario"));
  CHECK_THROWS_WITH(load_suite(empty.path() / "nope.xml"),
                    Catch::Contains("no such suite folder or manifest"));
}
