// `corsa validate` end to end: exit codes, human and JSON output.

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "run_corsa.h"
#include "scenario_text.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using corsa::test::run_corsa;

namespace {

const std::string kConformance =
    (fs::path(CORSA_SHARED_DIR) / "conformance" / "asam-osc-1.3").string();

}  // namespace

TEST_CASE("corsa validate accepts the ASAM examples, catalogs, parameter sets and maps",
          "[xosc][cli][e2e]") {
  const auto result = run_corsa({"validate", kConformance + "/CutIn.xosc",
                                 kConformance + "/Catalogs/Vehicles/VehicleCatalog.xosc",
                                 kConformance + "/SlowPrecedingVehicleStochasticParameterSet.xosc",
                                 kConformance + "/Databases/AB_RQ31_Straight.xodr"});
  INFO(result.err);
  CHECK(result.exit_code == 0);
  CHECK_THAT(result.out, Catch::Contains("CutIn.xosc: ok (OpenSCENARIO 1.3 scenario, 3 entities, "
                                         "1 story)"));
  CHECK_THAT(result.out, Catch::Contains("VehicleCatalog.xosc: ok (catalog 'VehicleCatalog', "
                                         "3 entries)"));
  CHECK_THAT(result.out, Catch::Contains("100 variants"));
  CHECK_THAT(result.out, Catch::Contains("AB_RQ31_Straight.xodr: ok (OpenDRIVE map)"));
}

TEST_CASE("corsa validate prints file:line: error: message and exits 2 for a bad file",
          "[xosc][cli][e2e]") {
  corsa::test::TempDir dir;
  corsa::test::ScenarioText text;
  text.road = "<LogicFile filepath=\"nowhere.xodr\"/>";
  const std::string xml = text.str();
  corsa::test::write_text(dir.path() / "bad.xosc", xml);
  const auto result = run_corsa({"validate", (dir.path() / "bad.xosc").string()});
  CHECK(result.exit_code == 2);
  CHECK_THAT(result.err, Catch::StartsWith((dir.path() / "bad.xosc").string() + ":" +
                                           std::to_string(corsa::test::line_of(xml, "<LogicFile")) +
                                           ": error: map file 'nowhere.xodr' not found"));
  CHECK(result.out.empty());
}

TEST_CASE("corsa validate reports an unknown element in a catalog the scenario uses, at its line",
          "[xosc][cli][e2e]") {
  // The scenario's catalog holds its entry and, beside it, an element the schema does not know
  // directly in <Catalog>: exit 2, located in the catalog file.
  corsa::test::TempDir dir;
  const std::string catalog =
      "<?xml version=\"1.0\"?>\n<OpenSCENARIO>\n"
      "<FileHeader revMajor=\"1\" revMinor=\"3\" date=\"2024-01-01T00:00:00\" "
      "description=\"c\" author=\"a\"/>\n<Catalog name=\"Controllers\">\n"
      "<Controller name=\"calm\"><Properties/></Controller>\n<Driver name=\"old\"/>\n"
      "</Catalog>\n</OpenSCENARIO>\n";
  corsa::test::write_text(dir.path() / "Controllers/Controllers.xosc", catalog);
  corsa::test::ScenarioText text;
  text.catalogs = "<ControllerCatalog><Directory path=\"Controllers\"/></ControllerCatalog>\n";
  text.init =
      "<Private entityRef=\"Ego\"><PrivateAction><ControllerAction><AssignControllerAction>"
      "<CatalogReference catalogName=\"Controllers\" entryName=\"calm\"/>"
      "</AssignControllerAction></ControllerAction></PrivateAction></Private>\n";
  corsa::test::write_text(dir.path() / "map.xodr", corsa::test::minimal_xodr());
  corsa::test::write_text(dir.path() / "s.xosc", text.str());
  const auto result = run_corsa({"validate", (dir.path() / "s.xosc").string()});
  CHECK(result.exit_code == 2);
  CHECK_THAT(result.err,
             Catch::Contains((dir.path() / "Controllers/Controllers.xosc").string() + ":" +
                             std::to_string(corsa::test::line_of(catalog, "<Driver")) +
                             ": error: unknown element <Driver> in <Catalog>"));
}

TEST_CASE("corsa validate --json reports every file for tools", "[xosc][cli][e2e]") {
  corsa::test::TempDir dir;
  corsa::test::write_text(dir.path() / "broken.xosc", "<OpenSCENARIO>\n<FileHeader>\n");
  const auto result = run_corsa({"validate", "--json", kConformance + "/TrailerConnect.xosc",
                                 (dir.path() / "broken.xosc").string()});
  CHECK(result.exit_code == 2);
  CHECK_THAT(result.out, Catch::StartsWith("{\"valid\":false,\"files\":[{\"file\":"));
  CHECK_THAT(result.out, Catch::Contains("\"kind\":\"scenario\",\"valid\":true"));
  CHECK_THAT(result.out, Catch::Contains("\"severity\":\"warning\""));
  CHECK_THAT(result.out, Catch::Contains("\"kind\":\"openscenario\",\"valid\":false"));
  CHECK_THAT(result.out, Catch::Contains("\"message\":\"malformed XML"));
}

TEST_CASE("corsa validate applies --param and rejects malformed ones", "[xosc][cli][e2e]") {
  const std::string scenario = kConformance + "/TrailerConnect.xosc";
  CHECK(run_corsa({"validate", scenario, "--param", "Speed=6"}).exit_code == 0);
  const auto wrong = run_corsa({"validate", scenario, "--param", "Speed=fast"});
  CHECK(wrong.exit_code == 2);
  CHECK_THAT(wrong.err, Catch::Contains("--param: error: parameter 'Speed': 'fast' is not a valid "
                                        "double"));
  const auto malformed = run_corsa({"validate", scenario, "--param", "Speed"});
  CHECK(malformed.exit_code == 2);
  CHECK_THAT(malformed.err, Catch::Contains("--param expects NAME=VALUE"));
}

TEST_CASE("corsa validate reports an unreadable file and a non-OpenSCENARIO document",
          "[xosc][cli][e2e]") {
  corsa::test::TempDir dir;
  corsa::test::write_text(dir.path() / "other.xosc", "<?xml version=\"1.0\"?>\n<Scenario/>\n");
  const auto result = run_corsa(
      {"validate", (dir.path() / "missing.xosc").string(), (dir.path() / "other.xosc").string()});
  CHECK(result.exit_code == 2);
  CHECK_THAT(result.err, Catch::Contains("missing.xosc"));
  CHECK_THAT(result.err, Catch::Contains("other.xosc:2: error: not an OpenSCENARIO document: the "
                                         "root element is <Scenario>"));
}

TEST_CASE("corsa validate --json stays valid UTF-8 whatever bytes the file holds",
          "[xosc][cli][e2e]") {
  corsa::test::TempDir dir;
  // Latin-1 bytes where UTF-8 is declared, quoted back by the error message.
  corsa::test::write_text(
      dir.path() / "latin1.xosc",
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<OpenSCENARIO>\n"
      "  <FileHeader revMajor=\"1\" revMinor=\"\xff\xfe\" date=\"2024-01-01T00:00:00\" "
      "description=\"d\" author=\"a\"/>\n</OpenSCENARIO>\n");
  const auto result = run_corsa({"validate", "--json", (dir.path() / "latin1.xosc").string()});
  INFO(result.out);
  CHECK(result.exit_code == 2);
  CHECK_THAT(result.out, Catch::Contains("\\ufffd\\ufffd"));
  CHECK(result.out.find('\xff') == std::string::npos);
  CHECK(result.out.find('\xfe') == std::string::npos);
}

TEST_CASE(
    "corsa validate warns about a run's lenient readings and refuses them with --strict, "
    "as corsa run --strict does",
    "[xosc][cli][e2e][lenient]") {
  const std::string file =
      (fs::path(CORSA_SOURCE_DIR) / "tests/engine/fixtures/lenient_run_readings.xosc").string();
  const auto lenient = run_corsa({"validate", file});
  INFO(lenient.err);
  CHECK(lenient.exit_code == 0);
  CHECK_THAT(
      lenient.err,
      Catch::Contains(file + ":44: warning: s = 1200 is outside road '1'") &&
          Catch::Contains(file + ":48: warning: entity 'Unplaced' has no initial position") &&
          Catch::Contains(file + ":54: warning: the first ClothoidSplineSegment has no "
                                 "PositionStart"));

  const auto strict = run_corsa({"validate", "--strict", file});
  INFO(strict.err);
  CHECK(strict.exit_code == 2);
  CHECK_THAT(strict.err, Catch::Contains(file + ":44: error: s = 1200 is outside road '1'") &&
                             Catch::Contains(file + ":48: error: entity 'Unplaced'") &&
                             Catch::Contains(file + ":54: error: the first ClothoidSplineSegment"));
  CHECK(strict.err.find("warning") == std::string::npos);

  const auto run = run_corsa({"run", "--strict", file});
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Catch::Contains(file + ":44: error: s = 1200 is outside road '1'"));
}
