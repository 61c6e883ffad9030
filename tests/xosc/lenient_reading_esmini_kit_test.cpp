// Rule breaks that kept whole esmini examples from loading, read as meant with a located
// `(read as ...)` warning and refused under --strict: a ClothoidSpline's draft <Segment>, a
// LaneOffsetAction without continuous, <SteadyState> beside a FinalSpeed's speed, a
// FollowTrajectoryAction without its following mode, a Story without Act, an Act without
// ManeuverGroup, revMinor="1+", map and catalog paths from esmini's working folder, a
// controller entry the catalog at hand lacks, an XML declaration after comments, an Action
// without name, an attribute written with other capitals, and a variation file given to
// `corsa run`. Each file also runs through `corsa
// run` (exit 0, the warning at its line) and is refused by `corsa run --strict` (exit 2).

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <variant>

#include "corsa/xosc/scenario.h"
#include "lenient_load.h"
#include "run_corsa.h"
#include "scenario_text.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace corsa::xosc;
using corsa::test::check_both_ways;
using corsa::test::lenient_load;
using corsa::test::line_of;
using corsa::test::Loaded;
using corsa::test::run_corsa;
using corsa::test::ScenarioText;
using corsa::test::warning_with;

namespace {

// A scenario that starts at once and stops itself after 2 s.
ScenarioText stopping_scenario() {
  ScenarioText text;
  text.stop =
      "<ConditionGroup><Condition name=\"End\" delay=\"0\" conditionEdge=\"none\">"
      "<ByValueCondition><SimulationTimeCondition value=\"2\" rule=\"greaterThan\"/>"
      "</ByValueCondition></Condition></ConditionGroup>\n";
  return text;
}

// A straight road of two lanes through the origin, where the test scenarios place Ego.
std::string straight_xodr() {
  return "<?xml version=\"1.0\"?>\n<OpenDRIVE>\n<header revMajor=\"1\" revMinor=\"6\"/>\n"
         "<road id=\"1\" length=\"400\" junction=\"-1\">\n"
         "<planView><geometry s=\"0\" x=\"-100\" y=\"0\" hdg=\"0\" length=\"400\"><line/>"
         "</geometry></planView>\n"
         "<lanes><laneSection s=\"0\"><left><lane id=\"1\" type=\"driving\"><width "
         "sOffset=\"0\" a=\"3.5\" b=\"0\" c=\"0\" d=\"0\"/></lane></left><center><lane "
         "id=\"0\" type=\"none\"/></center><right><lane id=\"-1\" type=\"driving\"><width "
         "sOffset=\"0\" a=\"3.5\" b=\"0\" c=\"0\" d=\"0\"/></lane></right></laneSection>"
         "</lanes>\n</road>\n</OpenDRIVE>\n";
}

// `corsa run` runs the scenario at `path` (exit 0) with the warning `text` at `line`, and
// `corsa run --strict` refuses it (exit 2) with that text as an error at the same line.
void check_cli(const fs::path& path, const std::string& text, int line) {
  const std::string at = path.filename().string() + ":" + std::to_string(line) + ": ";
  const auto run = run_corsa({"run", path.string(), "--quiet", "--duration", "10"});
  INFO(run.err);
  CHECK(run.exit_code == 0);
  CHECK_THAT(run.err, Catch::Contains(at + "warning: " + text));
  const auto strict = run_corsa({"run", "--strict", path.string(), "--quiet"});
  INFO(strict.err);
  CHECK(strict.exit_code == 2);
  CHECK_THAT(strict.err, Catch::Contains(at + "error: " + text));
}

// The scenario written as s.xosc (with its map) into `dir`, checked through `corsa run`.
void check_cli_text(const corsa::test::TempDir& dir, const std::string& xml,
                    const std::string& text, int line) {
  corsa::test::write_text(dir.path() / "map.xodr", straight_xodr());
  corsa::test::write_text(dir.path() / "s.xosc", xml);
  check_cli(dir.path() / "s.xosc", text, line);
}

// A FollowTrajectoryAction on Ego at 0 s holding `shape` (the inner XML of <Shape>).
std::string trajectory_story(const std::string& shape) {
  return corsa::test::story_with(
      "<Event name=\"E\" priority=\"override\"><Action name=\"Follow\"><PrivateAction>"
      "<RoutingAction><FollowTrajectoryAction><TrajectoryRef>"
      "<Trajectory name=\"T\" closed=\"false\"><Shape>\n" +
      shape +
      "</Shape></Trajectory></TrajectoryRef><TimeReference><None/></TimeReference>"
      "<TrajectoryFollowingMode followingMode=\"position\"/></FollowTrajectoryAction>"
      "</RoutingAction></PrivateAction></Action></Event>\n");
}

// The first action of the first event of the loaded scenario's first story, a PrivateAction.
const PrivateAction& first_private_action(const Loaded& loaded) {
  const auto& event =
      loaded.scenario->storyboard.stories[0].acts[0].maneuver_groups[0].maneuvers[0].events[0];
  return std::get<PrivateAction>(event.actions[0].action);
}

}  // namespace

TEST_CASE("a ClothoidSpline's draft Segment is read as its ClothoidSplineSegment",
          "[xosc][lenient]") {
  ScenarioText text = stopping_scenario();
  text.stories = trajectory_story(
      "<ClothoidSpline>\n"
      "<Segment curvStart=\"0.01\" length=\"15\"><PositionStart><WorldPosition x=\"0\" y=\"0\" "
      "h=\"0\"/></PositionStart></Segment>\n"
      "<Segment curvStart=\"0\" curvEnd=\"0.02\" length=\"5\" hOffset=\"0.1\"/>\n"
      "<Segment curvEnd=\"-0.01\" length=\"8\"/>\n"
      "</ClothoidSpline>\n");
  const std::string xml = text.str();
  const int first = line_of(xml, "<Segment curvStart=\"0.01\"");
  const int third = line_of(xml, "<Segment curvEnd=");
  check_both_ways(xml, "<Segment> in <ClothoidSpline> (a draft name)", first);
  corsa::test::TempDir dir;
  const Loaded loaded = lenient_load(dir, xml);
  REQUIRE(loaded.scenario);
  // A curvature left out continues the curve: an end the segment's start (an arc), a start the
  // previous segment's end.
  CHECK_THAT(warning_with(loaded, "curvEnd left out").message,
             Catch::Contains("(read as <ClothoidSplineSegment curvatureStart=\"0.01\" "
                             "curvatureEnd=\"0.01\">, curvEnd left out: its start curvature)"));
  const auto continued = warning_with(loaded, "curvStart left out");
  CHECK(continued.line == third);
  CHECK_THAT(continued.message, Catch::Contains("curvatureStart=\"0.02\" curvatureEnd=\"-0.01\""));
  const auto& follow = std::get<FollowTrajectoryAction>(first_private_action(loaded));
  const auto& spline = std::get<ClothoidSpline>(follow.trajectory.shape);
  REQUIRE(spline.segments.size() == 3);
  CHECK(spline.segments[0].curvature_end == 0.01);
  CHECK(spline.segments[1].h_offset == 0.1);
  CHECK(spline.segments[2].curvature_start == 0.02);
  CHECK(spline.segments[2].length == 8.0);
  check_cli_text(dir, xml, "<Segment> in <ClothoidSpline> (a draft name)", first);
  // The first segment has nothing to continue: without a start curvature it is an error.
  std::string no_start = xml;
  no_start.replace(no_start.find("curvStart=\"0.01\" "), 17, "");
  const Loaded refused = lenient_load(dir, no_start);
  REQUIRE(!refused.errors.empty());
  CHECK_THAT(refused.errors[0].message, Catch::Contains("needs curvStart"));
}

TEST_CASE("a LaneOffsetAction without continuous is read as not continuous", "[xosc][lenient]") {
  ScenarioText text = stopping_scenario();
  text.stories = corsa::test::story_with(
      "<Event name=\"E\" priority=\"override\"><Action name=\"Offset\"><PrivateAction>"
      "<LateralAction>\n<LaneOffsetAction>\n<LaneOffsetActionDynamics dynamicsShape=\"linear\" "
      "maxLateralAcc=\"1\"/><LaneOffsetTarget><AbsoluteTargetLaneOffset value=\"1\"/>"
      "</LaneOffsetTarget></LaneOffsetAction></LateralAction></PrivateAction></Action>"
      "</Event>\n");
  const std::string xml = text.str();
  const int line = line_of(xml, "<LaneOffsetAction>");
  check_both_ways(xml, "<LaneOffsetAction> without continuous", line);
  corsa::test::TempDir dir;
  const Loaded loaded = lenient_load(dir, xml);
  REQUIRE(loaded.scenario);
  CHECK(!std::get<LaneOffsetAction>(first_private_action(loaded)).continuous);
  CHECK_THAT(warning_with(loaded, "without continuous").message,
             Catch::EndsWith("(read as continuous=\"false\")"));
  check_cli_text(dir, xml, "<LaneOffsetAction> without continuous", line);
}

TEST_CASE("a SteadyState beside a FinalSpeed's speed is read as that speed's steady state",
          "[xosc][lenient]") {
  ScenarioText text = stopping_scenario();
  text.entities += text.entities;
  text.entities.replace(text.entities.rfind("name=\"Ego\""), 10, "name=\"Lead\"");
  text.init +=
      "<Private entityRef=\"Lead\"><PrivateAction><TeleportAction><Position>"
      "<WorldPosition x=\"0\" y=\"10\" h=\"0\"/></Position></TeleportAction></PrivateAction>"
      "</Private>\n";
  text.stories = corsa::test::story_with(
      "<Event name=\"E\" priority=\"override\"><Action name=\"Sync\"><PrivateAction>"
      "<SynchronizeAction masterEntityRef=\"Lead\">"
      "<TargetPositionMaster><WorldPosition x=\"100\" y=\"10\"/></TargetPositionMaster>"
      "<TargetPosition><WorldPosition x=\"100\" y=\"0\"/></TargetPosition>\n"
      "<FinalSpeed><AbsoluteSpeed value=\"5\"/>\n<SteadyState><TargetDistanceSteadyState "
      "distance=\"5\"/></SteadyState>\n</FinalSpeed></SynchronizeAction></PrivateAction>"
      "</Action></Event>\n");
  const std::string xml = text.str();
  const int line = line_of(xml, "<SteadyState>");
  const std::string what = "<SteadyState> in <FinalSpeed> (a group of the schema, not an element)";
  check_both_ways(xml, what, line);
  corsa::test::TempDir dir;
  const Loaded loaded = lenient_load(dir, xml);
  REQUIRE(loaded.scenario);
  CHECK_THAT(warning_with(loaded, "<SteadyState>").message,
             Catch::EndsWith("(read as <AbsoluteSpeed>'s steady state: "
                             "TargetDistanceSteadyState 5 m)"));
  const auto& sync = std::get<SynchronizeAction>(first_private_action(loaded));
  REQUIRE(sync.final_speed);
  const auto& speed = std::get<AbsoluteSpeed>(*sync.final_speed);
  CHECK(speed.value == 5.0);
  REQUIRE(speed.steady_state);
  CHECK(std::get<TargetDistanceSteadyState>(*speed.steady_state).distance == 5.0);
  check_cli_text(dir, xml, what, line);
  // A steady state given twice is not clear.
  std::string twice = xml;
  twice.replace(twice.find("<AbsoluteSpeed value=\"5\"/>"), 26,
                "<AbsoluteSpeed value=\"5\"><TargetTimeSteadyState time=\"1\"/></AbsoluteSpeed>");
  const Loaded refused = lenient_load(dir, twice);
  REQUIRE(!refused.errors.empty());
  CHECK_THAT(refused.errors[0].message, Catch::Contains("has a steady state of its own"));
}

TEST_CASE("a FollowTrajectoryAction without its following mode is read as follow",
          "[xosc][lenient]") {
  ScenarioText text = stopping_scenario();
  std::string story = trajectory_story(
      "<Polyline><Vertex><Position><WorldPosition x=\"0\" y=\"0\"/></Position></Vertex>"
      "<Vertex><Position><WorldPosition x=\"50\" y=\"0\"/></Position></Vertex></Polyline>\n");
  story.replace(story.find("<TrajectoryFollowingMode followingMode=\"position\"/>"), 51, "");
  story.replace(story.find("<FollowTrajectoryAction>"), 24, "\n<FollowTrajectoryAction>");
  text.stories = story;
  const std::string xml = text.str();
  const int line = line_of(xml, "<FollowTrajectoryAction>");
  const std::string what = "<FollowTrajectoryAction> without <TrajectoryFollowingMode>";
  check_both_ways(xml, what, line);
  corsa::test::TempDir dir;
  const Loaded loaded = lenient_load(dir, xml);
  REQUIRE(loaded.scenario);
  CHECK(std::get<FollowTrajectoryAction>(first_private_action(loaded)).following_mode ==
        FollowingMode::kFollow);
  check_cli_text(dir, xml, what, line);
}

TEST_CASE("a Story without Act and an Act without ManeuverGroup complete at once",
          "[xosc][lenient]") {
  ScenarioText text = stopping_scenario();
  text.stories =
      "<Story name=\"Frame\">\n</Story>\n"
      "<Story name=\"Swarm\">\n<Act name=\"act\"/>\n</Story>\n";
  const std::string xml = text.str();
  const int story_line = line_of(xml, "<Story name=\"Frame\">");
  const int act_line = line_of(xml, "<Act name=\"act\"/>");
  // Each on its own: check_both_ways looks at the first --strict error.
  ScenarioText story_only = text;
  story_only.stories = "<Story name=\"Frame\">\n</Story>\n";
  check_both_ways(story_only.str(), "<Story> 'Frame' without <Act>", story_line);
  ScenarioText act_only = text;
  act_only.stories = "<Story name=\"Swarm\">\n<Act name=\"act\"/>\n</Story>\n";
  check_both_ways(act_only.str(), "<Act> 'act' without <ManeuverGroup>",
                  line_of(act_only.str(), "<Act name"));
  corsa::test::TempDir dir;
  const Loaded loaded = lenient_load(dir, xml);
  REQUIRE(loaded.scenario);
  const auto& stories = loaded.scenario->storyboard.stories;
  REQUIRE(stories.size() == 2);
  CHECK(stories[0].acts.empty());
  REQUIRE(stories[1].acts.size() == 1);
  CHECK(stories[1].acts[0].maneuver_groups.empty());
  CHECK_THAT(warning_with(loaded, "'Frame'").message,
             Catch::EndsWith("(read as an empty story, which completes at once)"));
  check_cli_text(dir, xml, "<Story> 'Frame' without <Act>", story_line);
  check_cli_text(dir, act_only.str(), "<Act> 'act' without <ManeuverGroup>",
                 line_of(act_only.str(), "<Act name"));
  CHECK(act_line > story_line);
  corsa::test::write_text(dir.path() / "s.xosc", xml);
  // With the storyboard's stop trigger the run goes on to it; without one, the two empty
  // stories end the run at once.
  const auto run = run_corsa({"run", (dir.path() / "s.xosc").string()});
  CHECK_THAT(run.out, Catch::Contains("ended by stop trigger at 2.01 s"));
  ScenarioText endless = text;
  endless.stop.clear();
  corsa::test::write_text(dir.path() / "endless.xosc", endless.str());
  const auto ended = run_corsa({"run", (dir.path() / "endless.xosc").string()});
  CHECK(ended.exit_code == 0);
  CHECK_THAT(ended.out, Catch::Contains("ended by stories complete at 0.00 s"));
}

TEST_CASE("a revision number with a note after it is read as its leading number",
          "[xosc][lenient]") {
  ScenarioText text = stopping_scenario();
  text.version = "1+";
  const std::string xml = text.str();
  const int line = line_of(xml, "<FileHeader");
  const std::string what = "attribute revMinor: '1+' is not an unsignedShort";
  check_both_ways(xml, what, line);
  corsa::test::TempDir dir;
  const Loaded loaded = lenient_load(dir, xml);
  REQUIRE(loaded.scenario);
  CHECK(loaded.scenario->header.rev_minor == 1);
  CHECK_THAT(warning_with(loaded, "revMinor").message,
             Catch::EndsWith("(read as 1, its leading number)"));
  check_cli_text(dir, xml, what, line);
  // Text without a leading number is no revision.
  text.version = "x1";
  const Loaded refused = lenient_load(dir, text.str());
  REQUIRE(!refused.errors.empty());
  CHECK_THAT(refused.errors[0].message, Catch::Contains("'x1' is not a valid unsignedShort"));
}

TEST_CASE("map and catalog paths from esmini's working folder are found from the folders above",
          "[xosc][lenient]") {
  // esmini's layout: resources/xosc/s.xosc names ../resources/xodr/m.xodr, a path from esmini's
  // bin folder, a sibling of resources.
  corsa::test::TempDir dir;
  const fs::path kit = dir.path() / "resources";
  corsa::test::write_text(kit / "xodr" / "m.xodr", straight_xodr());
  corsa::test::write_text(
      kit / "catalogs" / "controllers.xosc",
      "<?xml version=\"1.0\"?>\n<OpenSCENARIO>\n<FileHeader revMajor=\"1\" revMinor=\"3\" "
      "date=\"2024-01-01T00:00:00\" description=\"c\" author=\"corsa\"/>\n"
      "<Catalog name=\"Controllers\">\n<Controller name=\"Plain\"><Properties/></Controller>\n"
      "</Catalog>\n</OpenSCENARIO>\n");
  ScenarioText text = stopping_scenario();
  text.road = "<LogicFile filepath=\"../resources/xodr/m.xodr\"/>";
  text.catalogs =
      "<ControllerCatalog><Directory path=\"../resources/catalogs\"/></ControllerCatalog>\n";
  text.entities.replace(text.entities.find("</ScenarioObject>"), 17,
                        "<ObjectController><CatalogReference catalogName=\"Controllers\" "
                        "entryName=\"Plain\"/></ObjectController>\n</ScenarioObject>");
  const std::string xml = text.str();
  const fs::path scenario = kit / "xosc" / "s.xosc";
  corsa::test::write_text(scenario, xml);
  corsa::Diagnostics diagnostics;
  const Scenario loaded = load_scenario(scenario, {}, diagnostics);
  CHECK(loaded.road_network.logic_file_path == (kit / "xodr" / "m.xodr").lexically_normal());
  REQUIRE(loaded.entities.objects[0].controllers.size() == 1);
  CHECK(loaded.entities.objects[0].controllers[0].controller.name == "Plain");
  bool map_warned = false;
  for (const auto& d : diagnostics.all()) {
    if (d.message.find("map file '../resources/xodr/m.xodr' is not in the scenario's folder") ==
        std::string::npos) {
      continue;
    }
    map_warned = true;
    CHECK(d.line == line_of(xml, "<LogicFile"));
    CHECK_THAT(d.message,
               Catch::Contains("(read as " + (kit / "xodr" / "m.xodr").lexically_normal().string() +
                               ", the same path from 1 folder up"));
  }
  CHECK(map_warned);
  check_cli(scenario, "map file '../resources/xodr/m.xodr' is not in the scenario's folder",
            line_of(xml, "<LogicFile"));
  check_cli(scenario, "catalog directory '../resources/catalogs' is not in the scenario's folder",
            line_of(xml, "<Directory"));
  // Missing everywhere stays a located error.
  fs::remove(kit / "xodr" / "m.xodr");
  const auto missing = run_corsa({"run", scenario.string()});
  CHECK(missing.exit_code == 2);
  CHECK_THAT(missing.err,
             Catch::Contains("s.xosc:" + std::to_string(line_of(xml, "<LogicFile")) +
                             ": error: map file '../resources/xodr/m.xodr' not found (looked for " +
                             (kit / "resources" / "xodr" / "m.xodr").string() +
                             ", and for the same path from the 3 folders above)"));
}

TEST_CASE("a controller entry the catalog at hand lacks is read as a controller the engine lacks",
          "[xosc][lenient]") {
  corsa::test::TempDir dir;
  corsa::test::write_text(
      dir.path() / "catalogs" / "controllers.xosc",
      "<?xml version=\"1.0\"?>\n<OpenSCENARIO>\n<FileHeader revMajor=\"1\" revMinor=\"3\" "
      "date=\"2024-01-01T00:00:00\" description=\"c\" author=\"corsa\"/>\n"
      "<Catalog name=\"ControllerCatalog\">\n<Controller name=\"Plain\"><Properties/>"
      "</Controller>\n</Catalog>\n</OpenSCENARIO>\n");
  ScenarioText text = stopping_scenario();
  text.catalogs = "<ControllerCatalog><Directory path=\"catalogs\"/></ControllerCatalog>\n";
  text.entities.replace(text.entities.find("</ScenarioObject>"), 17,
                        "<ObjectController>\n<CatalogReference catalogName=\"ControllerCatalog\" "
                        "entryName=\"followReference\"><ParameterAssignments><ParameterAssignment "
                        "parameterRef=\"DesiredSpeed\" value=\"25\"/></ParameterAssignments>"
                        "</CatalogReference></ObjectController>\n</ScenarioObject>");
  text.init.replace(text.init.find("</Private>"), 10,
                    "<PrivateAction><ControllerAction><ActivateControllerAction "
                    "longitudinal=\"true\" lateral=\"true\"/></ControllerAction></PrivateAction>"
                    "</Private>");
  const std::string xml = text.str();
  const int line = line_of(xml, "<CatalogReference catalogName=\"ControllerCatalog\"");
  const std::string what =
      "catalog 'ControllerCatalog' (" +
      (dir.path() / "catalogs" / "controllers.xosc").lexically_normal().string() +
      ") has no controller entry 'followReference'";
  corsa::test::write_text(dir.path() / "map.xodr", straight_xodr());
  corsa::test::write_text(dir.path() / "s.xosc", xml);
  corsa::Diagnostics diagnostics;
  const Scenario loaded = load_scenario(dir.path() / "s.xosc", {}, diagnostics);
  const auto& controller = loaded.entities.objects[0].controllers.at(0).controller;
  CHECK(controller.name == "followReference");
  REQUIRE(controller.catalog);
  CHECK(controller.catalog->assignments.size() == 1);
  CHECK(controller.properties.properties.empty());
  check_cli(dir.path() / "s.xosc", what, line);
  // The summary names the controller the acc controller stood in for.
  const auto run = run_corsa({"run", (dir.path() / "s.xosc").string(), "--quiet", "--summary",
                              (dir.path() / "summary.json").string()});
  CHECK(run.exit_code == 0);
  CHECK_THAT(corsa::test::slurp(dir.path() / "summary.json"),
             Catch::Contains("\"substitute_for\": \"followReference\""));
  // esmini's NaturalDriver, which the engine emulates, runs as itself, the reference's
  // ParameterAssignments read as its properties (DesiredSpeed as desiredSpeed).
  std::string natural = xml;
  natural.replace(natural.find("followReference"), 15, "NaturalDriver");
  corsa::test::write_text(dir.path() / "n.xosc", natural);
  const auto natural_run = run_corsa({"run", (dir.path() / "n.xosc").string(), "--quiet",
                                      "--summary", (dir.path() / "natural.json").string()});
  CHECK(natural_run.exit_code == 0);
  CHECK_THAT(natural_run.err,
             Catch::Contains("n.xosc:" + std::to_string(line) +
                             ": warning: controller entry 'NaturalDriver' is not in the catalog: "
                             "its ParameterAssignments are read as esmini's NaturalDriver "
                             "properties"));
  // The properties nothing assigns keep esmini's defaults, said once at the reference.
  CHECK_THAT(natural_run.err,
             Catch::Contains("n.xosc:" + std::to_string(line) +
                             ": warning: controller entry 'NaturalDriver' is not in the catalog "
                             "and nothing gives its desiredDistance, laneChangeDuration, "
                             "lookAheadDistance, maxDec, maxAcc, laneChangeDelay, thw, "
                             "maxImposedBraking, laneChangeAccGain, politeness, route: esmini's "
                             "defaults"));
  CHECK_THAT(corsa::test::slurp(dir.path() / "natural.json"),
             !Catch::Contains("\"substitute_for\": \"NaturalDriver\""));
  // A vehicle entry the catalog lacks stays an error: nothing could stand in for it.
  std::string vehicle = xml;
  vehicle.replace(vehicle.find("<ControllerCatalog>"), 0,
                  "<VehicleCatalog><Directory path=\"catalogs\"/></VehicleCatalog>\n");
  corsa::test::write_text(
      dir.path() / "catalogs" / "vehicles.xosc",
      "<?xml version=\"1.0\"?>\n<OpenSCENARIO>\n<FileHeader revMajor=\"1\" revMinor=\"3\" "
      "date=\"2024-01-01T00:00:00\" description=\"c\" author=\"corsa\"/>\n"
      "<Catalog name=\"VehicleCatalog\">\n</Catalog>\n</OpenSCENARIO>\n");
  const size_t start = vehicle.find("<Vehicle name=\"car\"");
  vehicle.replace(start, vehicle.find("</Vehicle>") + 10 - start,
                  "<CatalogReference catalogName=\"VehicleCatalog\" entryName=\"bus\"/>");
  const Loaded refused = lenient_load(dir, vehicle);
  REQUIRE(!refused.errors.empty());
  CHECK_THAT(refused.errors[0].message, Catch::Contains("has no entry 'bus'"));
}

TEST_CASE("a map object without s runs placed by its repeat, and --strict refuses the map",
          "[xosc][lenient][cli]") {
  corsa::test::TempDir dir;
  const std::string map =
      "<?xml version=\"1.0\"?>\n<OpenDRIVE>\n<header revMajor=\"1\" revMinor=\"4\"/>\n"
      "<road id=\"1\" length=\"100\" junction=\"-1\">\n"
      "<planView><geometry s=\"0\" x=\"0\" y=\"0\" hdg=\"0\" length=\"100\"><line/></geometry>"
      "</planView>\n"
      "<lanes><laneSection s=\"0\"><center><lane id=\"0\" type=\"none\"/></center><right>"
      "<lane id=\"-1\" type=\"driving\"><width sOffset=\"0\" a=\"3.5\" b=\"0\" c=\"0\" d=\"0\"/>"
      "</lane></right></laneSection></lanes>\n"
      "<objects>\n<object type=\"barrier\" id=\"8\" length=\"5\">\n"
      "<repeat s=\"20\" length=\"55\" distance=\"0\" tStart=\"-5\" tEnd=\"-9\"/>\n</object>\n"
      "</objects>\n</road>\n</OpenDRIVE>\n";
  corsa::test::write_text(dir.path() / "crest.xodr", map);
  ScenarioText text = stopping_scenario();
  text.road = "<LogicFile filepath=\"crest.xodr\"/>";
  corsa::test::write_text(dir.path() / "s.xosc", text.str());
  const std::string at = "crest.xodr:" + std::to_string(line_of(map, "<object ")) + ": ";
  const std::string what = "<object> '8' without s and t";
  const auto run = run_corsa({"run", (dir.path() / "s.xosc").string(), "--quiet"});
  INFO(run.err);
  CHECK(run.exit_code == 0);
  CHECK_THAT(run.err, Catch::Contains(at + "warning: " + what + " (read as s 20, t -5: "));
  const auto strict = run_corsa({"run", "--strict", (dir.path() / "s.xosc").string()});
  INFO(strict.err);
  CHECK(strict.exit_code == 2);
  CHECK_THAT(strict.err, Catch::Contains(at + "error: " + what +
                                         " (an error under --strict; otherwise read as s 20"));
  // `corsa validate --strict` refuses the map itself too.
  const auto validate = run_corsa({"validate", "--strict", (dir.path() / "crest.xodr").string()});
  CHECK(validate.exit_code == 2);
  CHECK(run_corsa({"validate", (dir.path() / "crest.xodr").string()}).exit_code == 0);
}

TEST_CASE("an XML declaration after comments is read as the file's own", "[xosc][lenient]") {
  const std::string xml =
      "<!-- a licence note before the declaration -->\n" + stopping_scenario().str();
  const std::string what = "XML declaration after comments";
  check_both_ways(xml, what, 2);
  corsa::test::TempDir dir;
  const Loaded loaded = lenient_load(dir, xml);
  REQUIRE(loaded.scenario);
  CHECK_THAT(warning_with(loaded, what).message,
             Catch::EndsWith("(read as the file's own declaration)"));
  check_cli_text(dir, xml, what, 2);
  // After an element, a declaration is no declaration: still malformed.
  const std::string after = "<a/>\n" + stopping_scenario().str();
  const Loaded refused = lenient_load(dir, after);
  REQUIRE(!refused.errors.empty());
  CHECK_THAT(refused.errors[0].message, Catch::Contains("malformed XML"));
}

TEST_CASE("an Action without name is read as an unnamed action", "[xosc][lenient]") {
  ScenarioText text = stopping_scenario();
  text.stories = corsa::test::story_with(
      "<Event name=\"E\" priority=\"override\">\n<Action><PrivateAction><LongitudinalAction>"
      "<SpeedAction><SpeedActionDynamics dynamicsShape=\"step\" value=\"0\" "
      "dynamicsDimension=\"time\"/><SpeedActionTarget><AbsoluteTargetSpeed value=\"5\"/>"
      "</SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Action>"
      "</Event>\n");
  const std::string xml = text.str();
  const int line = line_of(xml, "<Action>");
  const std::string what = "<Action> without name";
  check_both_ways(xml, what, line);
  corsa::test::TempDir dir;
  const Loaded loaded = lenient_load(dir, xml);
  REQUIRE(loaded.scenario);
  CHECK(std::holds_alternative<SpeedAction>(first_private_action(loaded)));
  CHECK(loaded.scenario->storyboard.stories[0]
            .acts[0]
            .maneuver_groups[0]
            .maneuvers[0]
            .events[0]
            .actions[0]
            .name.empty());
  check_cli_text(dir, xml, what, line);
}

TEST_CASE("an attribute written with other capitals is read as the attribute it misspells",
          "[xosc][lenient]") {
  ScenarioText text = stopping_scenario();
  text.stop +=
      "<ConditionGroup><Condition name=\"Far\" delay=\"0\" conditionEdge=\"none\">"
      "<ByEntityCondition><TriggeringEntities triggeringEntitiesRule=\"any\"><EntityRef "
      "entityRef=\"Ego\"/></TriggeringEntities><EntityCondition>\n<RelativeDistanceCondition "
      "entityRef=\"Ego\" relativeDistanceType=\"longitudinal\" value=\"100\" freeSpace=\"true\" "
      "rule=\"greaterThan\"/></EntityCondition></ByEntityCondition></Condition>"
      "</ConditionGroup>\n";
  const std::string xml = text.str();
  const int line = line_of(xml, "<RelativeDistanceCondition");
  const std::string what =
      "attribute 'freeSpace' of <RelativeDistanceCondition> misspells "
      "freespace";
  check_both_ways(xml, what, line);
  corsa::test::TempDir dir;
  const Loaded loaded = lenient_load(dir, xml);
  REQUIRE(loaded.scenario);
  CHECK_THAT(warning_with(loaded, what).message, Catch::EndsWith("(read as freespace)"));
  for (const auto& warning : loaded.warnings) {
    CHECK_THAT(warning.message, !Catch::Contains("unknown attribute"));
  }
  check_cli_text(dir, xml, what, line);
}

TEST_CASE("an empty TimeReference is read as None", "[xosc][lenient]") {
  ScenarioText text = stopping_scenario();
  text.stories = trajectory_story(
      "<Polyline><Vertex><Position><WorldPosition x=\"0\" y=\"0\" h=\"0\"/></Position></Vertex>\n"
      "<Vertex><Position><WorldPosition x=\"20\" y=\"0\" "
      "h=\"0\"/></Position></Vertex></Polyline>\n");
  const std::string none = "<TimeReference><None/></TimeReference>";
  std::string xml = text.str();
  REQUIRE(xml.find(none) != std::string::npos);
  xml.replace(xml.find(none), none.size(), "<TimeReference>\n</TimeReference>");
  check_both_ways(xml, "<TimeReference> without <None> or <Timing>",
                  line_of(xml, "<TimeReference>"));
  corsa::test::TempDir dir;
  const Loaded loaded = corsa::test::lenient_load(dir, xml);
  REQUIRE(loaded.scenario);
  const auto& follow = std::get<FollowTrajectoryAction>(first_private_action(loaded));
  CHECK_FALSE(follow.time_reference.timing.has_value());
}

namespace {

std::string summary_text(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

TEST_CASE("corsa run given a parameter value distribution runs its scenario's first variant",
          "[xosc][lenient][cli]") {
  // esmini's cut-in_parameter_set.xosc is a variation file, not a scenario: `corsa run` runs the
  // scenario it names with its first variant (Speed = 7 of 7, 9), warned at the
  // <ParameterValueDistribution> line; --param still wins; --strict refuses it.
  corsa::test::TempDir dir;
  ScenarioText text = stopping_scenario();
  text.parameters = "<ParameterDeclaration name=\"Speed\" parameterType=\"double\" value=\"5\"/>\n";
  corsa::test::write_text(dir.path() / "map.xodr", straight_xodr());
  corsa::test::write_text(dir.path() / "s.xosc", text.str());
  const std::string distribution =
      "<?xml version=\"1.0\"?>\n<OpenSCENARIO>\n<FileHeader revMajor=\"1\" revMinor=\"2\" "
      "date=\"2024-01-01T00:00:00\" description=\"d\" author=\"a\"/>\n"
      "<ParameterValueDistribution>\n<ScenarioFile filepath=\"s.xosc\"/>\n<Deterministic>"
      "<DeterministicSingleParameterDistribution parameterName=\"Speed\"><DistributionSet>"
      "<Element value=\"7\"/><Element value=\"9\"/></DistributionSet>"
      "</DeterministicSingleParameterDistribution></Deterministic>\n"
      "</ParameterValueDistribution>\n</OpenSCENARIO>\n";
  const fs::path path = dir.path() / "set.xosc";
  corsa::test::write_text(path, distribution);
  const std::string at =
      "set.xosc:" + std::to_string(line_of(distribution, "<ParameterValueDistribution>")) + ": ";
  const std::string text_of_warning =
      "a parameter value distribution, not a scenario: `corsa sweep` runs its 2 variants";
  const std::string summary = (dir.path() / "summary.json").string();
  const auto run = run_corsa({"run", path.string(), "--quiet", "--summary", summary});
  INFO(run.err);
  CHECK(run.exit_code == 0);
  CHECK_THAT(run.err, Catch::Contains(at + "warning: " + text_of_warning +
                                      " (read as a run of its scenario 's.xosc' with the first "
                                      "variant: Speed=7)"));
  CHECK_THAT(summary_text(summary), Catch::Contains("\"Speed\": \"7\""));
  const auto given =
      run_corsa({"run", path.string(), "--quiet", "--param", "Speed=9", "--summary", summary});
  CHECK(given.exit_code == 0);
  CHECK_THAT(summary_text(summary), Catch::Contains("\"Speed\": \"9\""));
  const auto strict = run_corsa({"run", "--strict", path.string(), "--quiet"});
  INFO(strict.err);
  CHECK(strict.exit_code == 2);
  CHECK_THAT(strict.err, Catch::Contains(at + "error: " + text_of_warning));
}
