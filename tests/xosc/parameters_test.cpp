#include <catch2/catch.hpp>
#include <variant>

#include "corsa/xosc/scenario.h"
#include "scenario_text.h"
#include "temp_dir.h"

using namespace corsa::xosc;
using corsa::test::ScenarioText;

namespace {

Scenario load_text(const corsa::test::TempDir& dir, const std::string& xml,
                   corsa::Diagnostics& diagnostics, const LoadOptions& options = {}) {
  corsa::test::write_text(dir.path() / "map.xodr", corsa::test::minimal_xodr());
  corsa::test::write_text(dir.path() / "s.xosc", xml);
  return load_scenario(dir.path() / "s.xosc", options, diagnostics);
}

double init_x(const Scenario& scenario) {
  const auto& teleport =
      std::get<TeleportAction>(scenario.storyboard.init.privates.at(0).actions.at(0));
  return std::get<WorldPosition>(teleport.position.kind).x;
}

std::string teleport_x(const std::string& x) {
  return "<Private entityRef=\"Ego\"><PrivateAction><TeleportAction><Position>"
         "<WorldPosition x=\"" +
         x +
         "\" y=\"0\"/></Position></TeleportAction></PrivateAction>"
         "</Private>\n";
}

}  // namespace

TEST_CASE("parameters of every type parse and keep their declared text", "[xosc][params]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.parameters =
      "<ParameterDeclaration name=\"B\" parameterType=\"boolean\" value=\"true\"/>\n"
      "<ParameterDeclaration name=\"T\" parameterType=\"dateTime\" "
      "value=\"2024-03-21T12:00:00\"/>\n"
      "<ParameterDeclaration name=\"D\" parameterType=\"double\" value=\"${2 * 1.25}\"/>\n"
      "<ParameterDeclaration name=\"S\" parameterType=\"string\" value=\"hello\"/>\n"
      "<ParameterDeclaration name=\"U\" parameterType=\"unsignedInt\" value=\"4000000000\"/>\n"
      "<ParameterDeclaration name=\"US\" parameterType=\"unsignedShort\" value=\"65535\"/>\n"
      "<ParameterDeclaration name=\"I\" parameterType=\"int\" value=\"${round(-2.5)}\"/>\n"
      "<ParameterDeclaration name=\"Old\" parameterType=\"integer\" value=\"7\"/>\n";
  corsa::Diagnostics diagnostics;
  const Scenario scenario = load_text(dir, text.str(), diagnostics);
  REQUIRE(scenario.parameters.size() == 8);
  CHECK(std::get<bool>(scenario.find_parameter("B")->value.data));
  CHECK(std::get<std::string>(scenario.find_parameter("T")->value.data) == "2024-03-21T12:00:00");
  CHECK(std::get<double>(scenario.find_parameter("D")->value.data) == 2.5);
  CHECK(scenario.find_parameter("D")->declared_text == "${2 * 1.25}");
  CHECK(std::get<std::string>(scenario.find_parameter("S")->value.data) == "hello");
  CHECK(std::get<int64_t>(scenario.find_parameter("U")->value.data) == 4000000000);
  CHECK(std::get<int64_t>(scenario.find_parameter("US")->value.data) == 65535);
  CHECK(std::get<int64_t>(scenario.find_parameter("I")->value.data) == -3);
  CHECK(scenario.find_parameter("Old")->type == ParameterType::kInt);
  // "integer" is the 1.0 spelling of int: accepted with one deprecation warning.
  const auto all = diagnostics.all();
  REQUIRE(all.size() == 1);
  CHECK(all[0].message ==
        "ParameterType value 'integer' is deprecated (an OpenSCENARIO 1.0/1.1 "
        "form); use int");
}

TEST_CASE("an expression giving a fraction for an integer parameter is an error",
          "[xosc][params]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.parameters = "<ParameterDeclaration name=\"N\" parameterType=\"int\" value=\"${7 / 2}\"/>\n";
  corsa::Diagnostics diagnostics;
  CHECK_THROWS_WITH(load_text(dir, text.str(), diagnostics),
                    Catch::Contains("parameter 'N': '3.5' is not a valid int"));
}

TEST_CASE("parameters may refer to later ones of the same scope", "[xosc][params]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.parameters =
      "<ParameterDeclaration name=\"A\" parameterType=\"double\" value=\"${$B * 2}\"/>\n"
      "<ParameterDeclaration name=\"B\" parameterType=\"double\" value=\"4\"/>\n";
  text.init = teleport_x("$A");
  corsa::Diagnostics diagnostics;
  CHECK(init_x(load_text(dir, text.str(), diagnostics)) == 8.0);
}

TEST_CASE("inner scopes shadow outer parameters only inside them", "[xosc][params]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.parameters = "<ParameterDeclaration name=\"V\" parameterType=\"double\" value=\"1\"/>\n";
  text.init = teleport_x("$V");
  text.stories =
      "<Story name=\"S\">\n<ParameterDeclarations><ParameterDeclaration name=\"V\" "
      "parameterType=\"double\" value=\"${$V + 10}\"/></ParameterDeclarations>\n"
      "<Act name=\"A\"><ManeuverGroup name=\"G\" maximumExecutionCount=\"1\">"
      "<Actors selectTriggeringEntities=\"false\"/><Maneuver name=\"M\">" +
      corsa::test::speed_event("E", "$V") + "</Maneuver></ManeuverGroup></Act></Story>\n";
  corsa::Diagnostics diagnostics;
  const Scenario scenario = load_text(dir, text.str(), diagnostics);
  CHECK(init_x(scenario) == 1.0);
  const auto& story = scenario.storyboard.stories.at(0);
  REQUIRE(story.parameters.size() == 1);
  // The story's V is declared from the global V: 1 + 10.
  CHECK(std::get<double>(story.parameters[0].value.data) == 11.0);
  const auto& action = std::get<SpeedAction>(std::get<PrivateAction>(
      story.acts[0].maneuver_groups[0].maneuvers[0].events[0].actions[0].action));
  CHECK(std::get<AbsoluteTargetSpeed>(action.target).value == 11.0);
}

TEST_CASE("catalog assignments override the entry's defaults and see the caller's scope",
          "[xosc][params]") {
  corsa::test::TempDir dir;
  corsa::test::write_text(dir.path() / "cat/v.xosc", R"(<?xml version="1.0"?>
<OpenSCENARIO>
<FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" description="c" author="a"/>
<Catalog name="Cars">
<Vehicle name="box" vehicleCategory="van" mass="$Mass">
<ParameterDeclarations>
<ParameterDeclaration name="Length" parameterType="double" value="4"/>
<ParameterDeclaration name="Mass" parameterType="double" value="${$Length * 300}"/>
</ParameterDeclarations>
<BoundingBox><Center x="1" y="0" z="0.8"/><Dimensions width="1.8" length="$Length" height="1.5"/></BoundingBox>
<Performance maxSpeed="50" maxAcceleration="5" maxDeceleration="8"/>
<Axles><RearAxle maxSteering="0" wheelDiameter="0.6" trackWidth="1.5" positionX="0" positionZ="0.3"/></Axles>
</Vehicle>
</Catalog>
</OpenSCENARIO>
)");
  ScenarioText text;
  text.parameters = "<ParameterDeclaration name=\"Long\" parameterType=\"double\" value=\"6\"/>\n";
  text.catalogs = "<VehicleCatalog><Directory path=\"cat\"/></VehicleCatalog>\n";
  text.entities =
      "<ScenarioObject name=\"Ego\"><CatalogReference catalogName=\"Cars\" entryName=\"box\">"
      "<ParameterAssignments><ParameterAssignment parameterRef=\"Length\" value=\"$Long\"/>"
      "</ParameterAssignments></CatalogReference></ScenarioObject>\n"
      "<ScenarioObject name=\"Other\"><CatalogReference catalogName=\"Cars\" entryName=\"box\"/>"
      "</ScenarioObject>\n";
  corsa::Diagnostics diagnostics;
  const Scenario scenario = load_text(dir, text.str(), diagnostics);
  const auto& ego = std::get<Vehicle>(scenario.entities.objects[0].object);
  CHECK(ego.bounding_box.length == 6.0);
  CHECK(ego.mass == 1800.0);  // the entry's own expression sees the assigned Length
  CHECK(ego.parameters[0].overridden);
  const auto& other = std::get<Vehicle>(scenario.entities.objects[1].object);
  CHECK(other.bounding_box.length == 4.0);
  CHECK(other.mass == 1200.0);
}

TEST_CASE("catalog entries do not see the scenario's parameters under --strict", "[xosc][params]") {
  corsa::test::TempDir dir;
  corsa::test::write_text(dir.path() / "cat/c.xosc", R"(<?xml version="1.0"?>
<OpenSCENARIO>
<FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" description="c" author="a"/>
<Catalog name="Ctl">
<Controller name="driver"><Properties><Property name="gain" value="$Gain"/></Properties></Controller>
</Catalog>
</OpenSCENARIO>
)");
  ScenarioText text;
  text.parameters = "<ParameterDeclaration name=\"Gain\" parameterType=\"double\" value=\"2\"/>\n";
  text.catalogs = "<ControllerCatalog><Directory path=\"cat\"/></ControllerCatalog>\n";
  text.entities.insert(text.entities.find("</ScenarioObject>"),
                       "<ObjectController><CatalogReference catalogName=\"Ctl\" "
                       "entryName=\"driver\"/></ObjectController>\n");
  // §9.4: an entry sees its own declarations only. Leniently the scenario's parameter of that
  // name is read with a warning (esmini's catalogs rely on it); --strict refuses it, at its use.
  corsa::Diagnostics diagnostics;
  LoadOptions strict;
  strict.strict = true;
  try {
    load_text(dir, text.str(), diagnostics, strict);
    FAIL("loaded");
  } catch (const corsa::InputError& error) {
    CHECK_THAT(error.diagnostic().message,
               Catch::StartsWith("parameter '$Gain' is not declared in its catalog entry"));
    CHECK(error.diagnostic().file == (dir.path() / "cat/c.xosc").string());
    CHECK(error.diagnostic().line == 5);
  }
}

TEST_CASE("1.0 spellings load with one deprecation warning each", "[xosc][params][deprecated]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.version = "0";
  text.init =
      "<GlobalAction><EnvironmentAction><Environment name=\"E\">"
      "<TimeOfDay animation=\"false\" dateTime=\"2020-01-01T12:00:00\"/>"
      "<Weather cloudState=\"free\"><Sun azimuth=\"0\" elevation=\"1\" intensity=\"1000\"/>"
      "<Precipitation precipitationType=\"rain\" intensity=\"0.5\"/></Weather>"
      "<RoadCondition "
      "frictionScaleFactor=\"1\"/></Environment></EnvironmentAction></GlobalAction>\n"
      "<Private entityRef=\"Ego\"><PrivateAction><ActivateControllerAction longitudinal=\"true\"/>"
      "</PrivateAction></Private>\n";
  text.stories = corsa::test::story_with(
      "<Event name=\"E\" priority=\"overwrite\"><Action name=\"A\"><PrivateAction>"
      "<TeleportAction><Position><GeoPosition latitude=\"0.5\" longitude=\"0.25\"/></Position>"
      "</TeleportAction></PrivateAction></Action></Event>\n");
  corsa::Diagnostics diagnostics;
  const Scenario scenario = load_text(dir, text.str(), diagnostics);
  CHECK(scenario.header.rev_minor == 0);
  const auto& environment =
      std::get<EnvironmentAction>(scenario.storyboard.init.global_actions.at(0)).environment;
  CHECK(environment.weather->sun->illuminance == 1000.0);
  CHECK(environment.weather->cloud_state == CloudState::kFree);
  const auto& event =
      scenario.storyboard.stories[0].acts[0].maneuver_groups[0].maneuvers[0].events[0];
  CHECK(event.priority == Priority::kOverride);
  const auto& geo = std::get<GeoPosition>(
      std::get<TeleportAction>(std::get<PrivateAction>(event.actions[0].action)).position.kind);
  CHECK(*geo.latitude_deg == Approx(0.5 * 180.0 / 3.141592653589793));
  CHECK(diagnostics.count(corsa::Severity::kWarning) == 7);
  CHECK(diagnostics.count(corsa::Severity::kError) == 0);
}

TEST_CASE("variables and parameter actions refer to declared names only", "[xosc][params]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.parameters = "<ParameterDeclaration name=\"P\" parameterType=\"int\" value=\"1\"/>\n";
  text.variables = "<VariableDeclaration name=\"Count\" variableType=\"int\" value=\"0\"/>\n";
  text.init =
      "<GlobalAction><VariableAction variableRef=\"Count\"><ModifyAction><Rule>"
      "<AddValue value=\"1\"/></Rule></ModifyAction></VariableAction></GlobalAction>\n"
      "<GlobalAction><ParameterAction parameterRef=\"P\"><SetAction value=\"2\"/>"
      "</ParameterAction></GlobalAction>\n";
  corsa::Diagnostics diagnostics;
  const Scenario scenario = load_text(dir, text.str(), diagnostics);
  REQUIRE(scenario.variables.size() == 1);
  CHECK(std::get<int64_t>(scenario.find_variable("Count")->value.data) == 0);
  const auto& modify = std::get<VariableModifyAction>(scenario.storyboard.init.global_actions[0]);
  CHECK(modify.rule == ModifyRule::kAddValue);
  CHECK(modify.value == 1.0);
  CHECK(std::get<ParameterSetAction>(scenario.storyboard.init.global_actions[1]).value == "2");

  text.init =
      "<GlobalAction><VariableAction variableRef=\"Missing\"><SetAction value=\"1\"/>"
      "</VariableAction></GlobalAction>\n";
  CHECK_THROWS_WITH(load_text(dir, text.str(), diagnostics),
                    Catch::Contains("undefined variable 'Missing'"));
}

TEST_CASE("values compare like ParameterCondition does", "[xosc][params]") {
  const Value three = *parse_value(ParameterType::kInt, "3");
  const Value pi = *parse_value(ParameterType::kDouble, "3.14");
  CHECK(compare_values(three, Rule::kLessThan, pi));
  CHECK(compare_values(pi, Rule::kGreaterOrEqual, three));
  CHECK_FALSE(compare_values(three, Rule::kEqualTo, pi));
  const Value a = *parse_value(ParameterType::kString, "abc");
  CHECK(compare_values(a, Rule::kEqualTo, *parse_value(ParameterType::kString, "abc")));
  CHECK_FALSE(compare_values(a, Rule::kGreaterThan, *parse_value(ParameterType::kString, "abb")));
  const Value early = *parse_value(ParameterType::kDateTime, "2024-01-01T08:00:00");
  const Value late = *parse_value(ParameterType::kDateTime, "2024-01-01T17:30:00");
  CHECK(compare_values(early, Rule::kLessThan, late));
  CHECK_FALSE(parse_value(ParameterType::kDateTime, "2024-01-01 08:00"));
  CHECK_FALSE(parse_value(ParameterType::kBoolean, "yes"));
  CHECK(parse_value(ParameterType::kInt, "-2147483648"));
  CHECK_FALSE(parse_value(ParameterType::kInt, "2147483648"));
  CHECK_FALSE(parse_value(ParameterType::kUnsignedInt, "-1"));
}

TEST_CASE("traffic signal controllers are kept and references to unknown ones warn",
          "[xosc][params]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.road =
      "<LogicFile filepath=\"map.xodr\"/>\n<TrafficSignals>\n"
      "<TrafficSignalController name=\"north\" delay=\"2\">"
      "<Phase name=\"go\" duration=\"30\"><TrafficSignalState trafficSignalId=\"7\" "
      "state=\"off;off;on\"/></Phase><Phase name=\"stop\" duration=\"40\"/>"
      "</TrafficSignalController>\n</TrafficSignals>";
  text.init =
      "<GlobalAction><InfrastructureAction><TrafficSignalAction>"
      "<TrafficSignalControllerAction trafficSignalControllerRef=\"north\" phase=\"go\"/>"
      "</TrafficSignalAction></InfrastructureAction></GlobalAction>\n"
      "<GlobalAction><InfrastructureAction><TrafficSignalAction>"
      "<TrafficSignalControllerAction trafficSignalControllerRef=\"north\" phase=\"amber\"/>"
      "</TrafficSignalAction></InfrastructureAction></GlobalAction>\n";
  corsa::Diagnostics diagnostics;
  const Scenario scenario = load_text(dir, text.str(), diagnostics);
  REQUIRE(scenario.road_network.traffic_signal_controllers.size() == 1);
  const auto& controller = scenario.road_network.traffic_signal_controllers[0];
  CHECK(controller.delay == 2.0);
  REQUIRE(controller.phases.size() == 2);
  CHECK(controller.phases[0].states.at(0).traffic_signal_id == "7");
  const auto all = diagnostics.all();
  REQUIRE(all.size() == 1);
  CHECK(all[0].message == "traffic signal controller 'north' has no phase 'amber'");
}
