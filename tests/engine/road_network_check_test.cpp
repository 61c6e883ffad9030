// Road and lane references checked against the map while a scenario is read (what `corsa
// validate` does): every wrong one reported at its line in one pass, also in events a run never
// reaches, with the same words a run stops with.

#include "corsa/engine/road_network_check.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/xosc/scenario.h"
#include "engine_fixture.h"

namespace {

/// A scenario over fixtures/straight.xodr (road 1, 1000 m, lanes 3..-4) whose positions are
/// `init` (the Init's TeleportAction) and `story` (an event that waits for 1e6 s).
std::string road_check_scenario(const std::string& road_network, const std::string& init,
                                const std::string& story) {
  return R"(<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" description="roads" author="Corsa tests"/>
  <CatalogLocations/>
  )" + road_network +
         R"(
  <Entities>
    <ScenarioObject name="Car">
      <Vehicle name="Car_model" vehicleCategory="car">
        <Performance maxSpeed="70" maxAcceleration="10" maxDeceleration="10"/>
        <BoundingBox><Center x="1.4" y="0" z="0.75"/><Dimensions width="1.8" length="4.5" height="1.5"/></BoundingBox>
        <Axles>
          <FrontAxle maxSteering="0.5" wheelDiameter="0.6" trackWidth="1.6" positionX="2.8" positionZ="0.3"/>
          <RearAxle maxSteering="0" wheelDiameter="0.6" trackWidth="1.6" positionX="0" positionZ="0.3"/>
        </Axles>
      </Vehicle>
    </ScenarioObject>
  </Entities>
  <Storyboard>
    <Init><Actions><Private entityRef="Car">
      <PrivateAction><TeleportAction><Position>)" +
         init + R"(</Position></TeleportAction></PrivateAction>
    </Private></Actions></Init>
    <Story name="S"><Act name="A"><ManeuverGroup maximumExecutionCount="1" name="G">
      <Actors selectTriggeringEntities="false"><EntityRef entityRef="Car"/></Actors>
      <Maneuver name="M"><Event name="E" priority="override"><Action name="Jump">
        <PrivateAction><TeleportAction><Position>)" +
         story + R"(</Position></TeleportAction></PrivateAction>
      </Action>
      <StartTrigger><ConditionGroup><Condition name="late" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="1e6" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StartTrigger>
      </Event></Maneuver>
    </ManeuverGroup>
    <StartTrigger><ConditionGroup><Condition name="go" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="0" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StartTrigger>
    </Act></Story>
    <StopTrigger/>
  </Storyboard>
</OpenSCENARIO>
)";
}

const std::string kRoadCheckMap =
    R"(<RoadNetwork><LogicFile filepath="straight.xodr"/></RoadNetwork>)";
constexpr int kRoadCheckInitLine = 20;   ///< line of the Init's position in road_check_scenario
constexpr int kRoadCheckStoryLine = 25;  ///< line of the story's position

/// The errors of loading `text` with the map check (none: an empty list); its warnings go to
/// `diagnostics`.
std::vector<corsa::Diagnostic> road_check_errors(const std::string& text,
                                                 corsa::Diagnostics& diagnostics,
                                                 bool strict = false) {
  corsa::xosc::LoadOptions options;
  options.strict = strict;
  options.road_network_check = std::make_shared<corsa::engine::MapReferenceCheck>(strict);
  try {
    corsa::xosc::parse_scenario(text, corsa::test::engine_fixture("roads.xosc"), options,
                                diagnostics);
  } catch (const corsa::InputError& error) {
    return error.diagnostics();
  }
  return {};
}

std::vector<corsa::Diagnostic> road_check_errors(const std::string& text) {
  corsa::Diagnostics diagnostics;
  return road_check_errors(text, diagnostics);
}

/// The diagnostics of `all` that are warnings, as `file:line: warning: message`.
std::vector<std::string> road_check_warnings(const corsa::Diagnostics& all) {
  std::vector<std::string> warnings;
  for (const corsa::Diagnostic& d : all.all()) {
    if (d.severity == corsa::Severity::kWarning) {
      std::ostringstream text;
      text << d;
      warnings.push_back(text.str());
    }
  }
  return warnings;
}

}  // namespace

TEST_CASE("Positions on roads and lanes the map lacks are errors at their lines, all in one pass",
          "[engine][road_network_check]") {
  const std::string text =
      road_check_scenario(kRoadCheckMap, R"(<LanePosition roadId="7" laneId="-1" s="10"/>)",
                          R"(<LanePosition roadId="1" laneId="-9" s="2000"/>)");
  const auto errors = road_check_errors(text);
  REQUIRE(errors.size() == 2);
  CHECK(errors[0].line == kRoadCheckInitLine);
  CHECK(errors[0].message == "road '7' does not exist in the road network");
  // s beyond the road is read as its end (with a warning), as a run reads it; the lane is missing
  // there too.
  CHECK(errors[1].line == kRoadCheckStoryLine);
  CHECK(errors[1].message == "road '1' has no lane -9 at s = 1000");

  // Without the check the document itself is fine: a run finds the Init's error only.
  corsa::Diagnostics diagnostics;
  CHECK_NOTHROW(corsa::xosc::parse_scenario(text, corsa::test::engine_fixture("roads.xosc"), {},
                                            diagnostics));
}

TEST_CASE("A lane id that is not an integer and a road position on a missing road are errors",
          "[engine][road_network_check]") {
  const auto errors = road_check_errors(
      road_check_scenario(kRoadCheckMap, R"(<LanePosition roadId="1" laneId="-1.5" s="10"/>)",
                          R"(<RoadPosition roadId="nine" s="5" t="0"/>)"));
  REQUIRE(errors.size() == 2);
  CHECK(errors[0].line == kRoadCheckInitLine);
  CHECK(errors[0].message == "laneId '-1.5' is not a lane id (a non-zero integer)");
  CHECK(errors[1].line == kRoadCheckStoryLine);
  CHECK(errors[1].message == "road 'nine' does not exist in the road network");
}

TEST_CASE("Positions on the map's roads and lanes, and the centre lane, pass the check",
          "[engine][road_network_check]") {
  CHECK(road_check_errors(road_check_scenario(kRoadCheckMap,
                                              R"(<LanePosition roadId="1" laneId="-3" s="10"/>)",
                                              R"(<LanePosition roadId="1" laneId="0" s="999"/>)"))
            .empty());
  CHECK(road_check_errors(road_check_scenario(kRoadCheckMap,
                                              R"(<RoadPosition roadId="1" s="0" t="-3"/>)",
                                              R"(<WorldPosition x="5" y="-3"/>)"))
            .empty());
}

TEST_CASE("Road positions in a scenario without a LogicFile are errors at each",
          "[engine][road_network_check]") {
  const auto errors = road_check_errors(
      road_check_scenario("<RoadNetwork/>", R"(<LanePosition roadId="1" laneId="-1" s="10"/>)",
                          R"(<WorldPosition x="5" y="-3"/>)"));
  REQUIRE(errors.size() == 1);
  CHECK(errors[0].line == kRoadCheckInitLine);
  CHECK(errors[0].message ==
        "LanePosition needs a road network, but the scenario has no LogicFile");
}

TEST_CASE("A missing LogicFile is reported once, not again at each position",
          "[engine][road_network_check]") {
  const auto errors = road_check_errors(
      road_check_scenario(R"(<RoadNetwork><LogicFile filepath="no_such_map.xodr"/></RoadNetwork>)",
                          R"(<LanePosition roadId="1" laneId="-1" s="10"/>)",
                          R"(<LanePosition roadId="7" laneId="-1" s="10"/>)"));
  REQUIRE(errors.size() == 1);
  CHECK(errors[0].line == 5);
  CHECK(errors[0].message.starts_with("map file 'no_such_map.xodr' not found"));
}

TEST_CASE("An s past the road's end warns as a run does, at the same line; --strict refuses it",
          "[engine][road_network_check][lenient]") {
  const std::string text =
      road_check_scenario(kRoadCheckMap, R"(<LanePosition roadId="1" laneId="-1" s="1400"/>)",
                          R"(<RoadPosition roadId="1" s="-5" t="0"/>)");
  corsa::Diagnostics diagnostics;
  CHECK(road_check_errors(text, diagnostics).empty());
  const std::string file = corsa::test::engine_fixture("roads.xosc").string();
  CHECK(road_check_warnings(diagnostics) ==
        std::vector<std::string>{
            file + ":20: warning: s = 1400 is outside road '1' (length 1000 m) (read as s = "
                   "1000, the road's end)",
            file + ":25: warning: s = -5 is outside road '1' (length 1000 m) (read as s = 0, "
                   "the road's end)"});

  corsa::Diagnostics strict_diagnostics;
  const auto errors = road_check_errors(text, strict_diagnostics, true);
  REQUIRE(errors.size() == 2);
  CHECK(errors[0].line == kRoadCheckInitLine);
  CHECK(errors[0].message ==
        "s = 1400 is outside road '1' (length 1000 m) (an error under --strict; otherwise read "
        "as s = 1000, the road's end)");
  CHECK(errors[1].line == kRoadCheckStoryLine);
  CHECK(road_check_warnings(strict_diagnostics).empty());
}

TEST_CASE("The check's warning for an s past the road's end is the run's, word for word",
          "[engine][road_network_check][lenient]") {
  const auto file = corsa::test::engine_fixture("compat_esmini_readings.xosc");
  corsa::xosc::LoadOptions options;
  options.road_network_check = std::make_shared<corsa::engine::MapReferenceCheck>(false);
  corsa::Diagnostics checked;
  corsa::xosc::load_scenario(file, options, checked);
  const auto check_warnings = road_check_warnings(checked);

  corsa::test::FixtureRun run(file);
  run.run();
  std::vector<std::string> run_outside;
  for (const std::string& warning : road_check_warnings(run.diagnostics())) {
    if (warning.find("is outside road") != std::string::npos) run_outside.push_back(warning);
  }
  REQUIRE(run_outside.size() == 1);
  CHECK(std::count(check_warnings.begin(), check_warnings.end(), run_outside[0]) == 1);
}

TEST_CASE(
    "Every lenient reading a run makes that the document tells is warned about at load "
    "with the run's words at the run's lines, and refused under --strict by both",
    "[engine][road_network_check][lenient]") {
  const auto file = corsa::test::engine_fixture("lenient_run_readings.xosc");
  corsa::xosc::LoadOptions validate;
  validate.road_network_check = std::make_shared<corsa::engine::MapReferenceCheck>(false);
  corsa::Diagnostics checked;
  corsa::xosc::load_scenario(file, validate, checked);
  const auto check_warnings = road_check_warnings(checked);

  corsa::test::FixtureRun run(file);
  run.run();
  std::vector<std::string> run_readings;
  for (const std::string& warning : road_check_warnings(run.diagnostics())) {
    if (warning.find("(read as") != std::string::npos) run_readings.push_back(warning);
  }
  const std::string name = file.string();
  CHECK(run_readings ==
        std::vector<std::string>{
            name + ":44: warning: s = 1200 is outside road '1' (length 1000 m) (read as s = "
                   "1000, the road's end)",
            name + ":48: warning: entity 'Unplaced' has no initial position (no TeleportAction "
                   "in Init) (read as the start of the trajectory it follows)",
            name + ":54: warning: the first ClothoidSplineSegment has no PositionStart (read as "
                   "a start at the entity following it)"});
  std::vector<std::string> sorted_check = check_warnings;
  std::sort(sorted_check.begin(), sorted_check.end());
  std::vector<std::string> sorted_run = run_readings;
  std::sort(sorted_run.begin(), sorted_run.end());
  CHECK(sorted_check == sorted_run);
  // Without the map check (run, sweep) the load says nothing of them: the run does.
  corsa::Diagnostics plain;
  corsa::xosc::load_scenario(file, {}, plain);
  CHECK(road_check_warnings(plain).empty());

  // --strict: the load refuses all three at their lines, in one pass.
  validate.strict = true;
  validate.road_network_check = std::make_shared<corsa::engine::MapReferenceCheck>(true);
  std::vector<int> lines;
  try {
    corsa::Diagnostics strict_diagnostics;
    corsa::xosc::load_scenario(file, validate, strict_diagnostics);
  } catch (const corsa::InputError& error) {
    for (const corsa::Diagnostic& d : error.diagnostics()) {
      CHECK_THAT(d.message, Catch::Contains("(an error under --strict; otherwise read as"));
      lines.push_back(d.line);
    }
  }
  std::sort(lines.begin(), lines.end());
  CHECK(lines == std::vector<int>{44, 48, 54});
  corsa::engine::SimulationOptions strict;
  strict.strict = true;
  CHECK_THROWS_WITH(corsa::test::FixtureRun(file, strict).run(),
                    Catch::Contains("an error under --strict"));
}
