// One pass reports every error of a document: a missing map or catalog, a bad value or an
// unknown element does not hide the errors after it. Deprecated attributes written together with
// their replacement, Set/Modify actions that do not suit their variable's type, and echoed values
// are checked too.

#include <catch2/catch.hpp>
#include <string>

#include "corsa/core/strings.h"
#include "corsa/xosc/scenario.h"
#include "scenario_text.h"
#include "temp_dir.h"

using namespace corsa::xosc;
using corsa::test::line_of;
using corsa::test::ScenarioText;

namespace {

std::vector<corsa::Diagnostic> errors_of(const corsa::test::TempDir& dir, const std::string& xml,
                                         bool with_map = true) {
  if (with_map) corsa::test::write_text(dir.path() / "map.xodr", corsa::test::minimal_xodr());
  corsa::test::write_text(dir.path() / "s.xosc", xml);
  corsa::Diagnostics diagnostics;
  try {
    load_scenario(dir.path() / "s.xosc", {}, diagnostics);
  } catch (const corsa::InputError& error) {
    return error.diagnostics();
  }
  return {};
}

bool has(const std::vector<corsa::Diagnostic>& errors, int line, const std::string& text) {
  for (const auto& error : errors) {
    if (error.line == line && error.message.find(text) != std::string::npos) return true;
  }
  return false;
}

std::string describe(const std::vector<corsa::Diagnostic>& errors) {
  std::string text;
  for (const auto& error : errors) text += error.format() + "\n";
  return text;
}

std::string variable_action(const std::string& name, const std::string& variable,
                            const std::string& inner) {
  return "<Action name=\"" + name + "\"><GlobalAction><VariableAction variableRef=\"" + variable +
         "\">" + inner + "</VariableAction></GlobalAction></Action>\n";
}

}  // namespace

TEST_CASE("a missing map and catalog do not hide the errors after them", "[xosc][errors]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.parameters =
      "<ParameterDeclaration name=\"Speed\" parameterType=\"double\" value=\"fast\"/>\n"
      "<ParameterDeclaration name=\"Limit\" parameterType=\"double\" value=\"61\">\n"
      "<ConstraintGroup><ValueConstraint rule=\"lessThan\" value=\"60\"/></ConstraintGroup>\n"
      "</ParameterDeclaration>\n";
  text.catalogs = "<VehicleCatalog><Directory path=\"Catalogs/None\"/></VehicleCatalog>\n";
  text.entities +=
      "<ScenarioObject name=\"Other\">\n"
      "<CatalogReference catalogName=\"VehicleCatalog\" entryName=\"car\"/>\n"
      "</ScenarioObject>\n<Unknown/>\n";
  text.init =
      "<Private entityRef=\"Other\">\n"
      "<PrivateAction><TeleportAction><Position>"
      "<WorldPosition x=\"ezert\" y=\"0\" h=\"0\"/></Position></TeleportAction></PrivateAction>\n"
      "<PrivateAction><LongitudinalAction><SpeedAction>\n"
      "<SpeedActionDynamics dynamicsShape=\"jump\" dynamicsDimension=\"time\" value=\"0\"/>\n"
      "<SpeedActionTarget><AbsoluteTargetSpeed value=\"${1 / 0}\"/></SpeedActionTarget>"
      "</SpeedAction></LongitudinalAction></PrivateAction>\n</Private>\n";
  const std::string xml = text.str();
  const auto errors = errors_of(dir, xml, false);
  INFO(describe(errors));
  CHECK(has(errors, line_of(xml, "name=\"Speed\""), "'fast' is not a valid double"));
  CHECK(has(errors, line_of(xml, "name=\"Limit\""), "violates its value constraints"));
  CHECK(has(errors, line_of(xml, "<LogicFile"), "map file 'map.xodr' not found"));
  CHECK(has(errors, line_of(xml, "entryName=\"car\""), "catalog 'VehicleCatalog'"));
  CHECK(has(errors, line_of(xml, "<Unknown/>"), "unknown element <Unknown> in <Entities>"));
  CHECK(has(errors, line_of(xml, "x=\"ezert\""), "'ezert' is not a number"));
  CHECK(has(errors, line_of(xml, "\"jump\""), "'jump' is not a valid DynamicsShape"));
  CHECK(has(errors, line_of(xml, "${1 / 0}"), "division by zero"));
  // The entity whose catalog is missing is still known: its uses add no errors of their own.
  CHECK(errors.size() == 8);
}

TEST_CASE("two errors in one element are both reported", "[xosc][errors]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.init =
      "<Private entityRef=\"Ego\">\n"
      "<PrivateAction><TeleportAction><Position>"
      "<WorldPosition x=\"left\" y=\"$Nowhere\" h=\"${sqrt(-1)}\"/></Position></TeleportAction>"
      "</PrivateAction>\n</Private>\n";
  const std::string xml = text.str();
  const auto errors = errors_of(dir, xml);
  INFO(describe(errors));
  const int line = line_of(xml, "x=\"left\"");
  CHECK(has(errors, line, "'left' is not a number"));
  CHECK(has(errors, line, "undefined parameter '$Nowhere'"));
  CHECK(has(errors, line, "sqrt"));
  CHECK(errors.size() == 3);
}

TEST_CASE("every parameter that violates its constraints is reported", "[xosc][errors]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  const char* rules[] = {"equalTo",     "notEqualTo",  "lessThan",
                         "lessOrEqual", "greaterThan", "greaterOrEqual"};
  for (const char* rule : rules) {
    // A value each rule refuses against 5.
    const std::string r = rule;
    const char* value = r == "equalTo" || r == "lessOrEqual" ? "7"
                        : r == "greaterOrEqual"              ? "3"
                                                             : "5";
    text.parameters += "<ParameterDeclaration name=\"p_" + r + "\" parameterType=\"int\" value=\"" +
                       value + "\">\n" + "<ConstraintGroup><ValueConstraint rule=\"" + r +
                       "\" value=\"5\"/></ConstraintGroup></ParameterDeclaration>\n";
  }
  text.parameters +=
      "<ParameterDeclaration name=\"bad_bound\" parameterType=\"unsignedShort\" "
      "value=\"1\">\n<ConstraintGroup><ValueConstraint rule=\"equalTo\" "
      "value=\"many\"/></ConstraintGroup></ParameterDeclaration>\n";
  const std::string xml = text.str();
  const auto errors = errors_of(dir, xml);
  INFO(describe(errors));
  for (const char* rule : rules) {
    CHECK(has(errors, line_of(xml, "name=\"p_" + std::string(rule) + "\""),
              "violates its value constraints"));
  }
  CHECK(has(errors, line_of(xml, "value=\"many\""),
            "constraint value 'many' of parameter 'bad_bound' is not a valid unsignedShort"));
  CHECK(errors.size() == 8);
}

TEST_CASE("a deprecated attribute together with its replacement is an error", "[xosc][errors]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.init =
      "<Private entityRef=\"Ego\">\n"
      "<PrivateAction><TeleportAction><Position>\n"
      "<GeoPosition latitudeDeg=\"10\" latitude=\"0.2\" longitudeDeg=\"10\"/>\n"
      "</Position></TeleportAction></PrivateAction>\n</Private>\n";
  text.stories = corsa::test::story_with(
      "<Event name=\"E\" priority=\"override\"><Action name=\"W\"><GlobalAction>"
      "<EnvironmentAction><Environment name=\"env\"><TimeOfDay animation=\"false\" "
      "dateTime=\"2024-01-01T12:00:00\"/>\n"
      "<Weather cloudState=\"free\" fractionalCloudCover=\"zeroOktas\">\n"
      "<Sun azimuth=\"0\" elevation=\"1\" intensity=\"1000\" illuminance=\"1000\"/>\n"
      "</Weather><RoadCondition frictionScaleFactor=\"1\"/></Environment></EnvironmentAction>"
      "</GlobalAction></Action></Event>\n");
  const std::string xml = text.str();
  const auto errors = errors_of(dir, xml);
  INFO(describe(errors));
  CHECK(has(errors, line_of(xml, "latitude=\"0.2\""),
            "attribute 'latitude' is deprecated and must not be used together with attribute "
            "'latitudeDeg'"));
  CHECK(has(errors, line_of(xml, "cloudState="),
            "attribute 'cloudState' is deprecated and must not be used together with attribute "
            "'fractionalCloudCover'"));
  CHECK(has(errors, line_of(xml, "intensity="), "attribute 'intensity' is deprecated"));
  CHECK(errors.size() == 3);
}

TEST_CASE("variable Set and Modify actions are checked against the variable's type",
          "[xosc][errors]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.variables =
      "<VariableDeclaration name=\"Flag\" variableType=\"boolean\" value=\"false\"/>\n"
      "<VariableDeclaration name=\"Label\" variableType=\"string\" value=\"x\"/>\n"
      "<VariableDeclaration name=\"Count\" variableType=\"unsignedInt\" value=\"3\"/>\n";
  text.stories = corsa::test::story_with(
      "<Event name=\"E\" priority=\"override\">\n" +
      variable_action("A1", "Flag", "<SetAction value=\"perhaps\"/>") +
      variable_action("A2", "Count", "<SetAction value=\"-1\"/>") +
      variable_action("A3", "Label",
                      "<ModifyAction><Rule><AddValue value=\"1\"/></Rule></ModifyAction>") +
      variable_action("A4", "Count",
                      "<ModifyAction><Rule><MultiplyByValue value=\"2\"/></Rule></ModifyAction>") +
      variable_action("A5", "Nothing", "<SetAction value=\"1\"/>") + "</Event>\n");
  const std::string xml = text.str();
  const auto errors = errors_of(dir, xml);
  INFO(describe(errors));
  CHECK(has(errors, line_of(xml, "\"A1\""),
            "value 'perhaps' cannot be set on variable 'Flag' of type boolean"));
  CHECK(has(errors, line_of(xml, "\"A2\""),
            "value '-1' cannot be set on variable 'Count' of type unsignedInt"));
  CHECK(has(errors, line_of(xml, "\"A3\""),
            "variable 'Label' is of type string; a ModifyAction needs a numeric type"));
  CHECK(has(errors, line_of(xml, "\"A5\""), "undefined variable 'Nothing'"));
  CHECK(errors.size() == 4);
}

TEST_CASE("values echoed in messages are clipped to 200 bytes", "[xosc][errors]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  const std::string huge(100000, 'z');
  text.parameters =
      "<ParameterDeclaration name=\"P\" parameterType=\"double\" value=\"" + huge + "\"/>\n";
  const auto errors = errors_of(dir, text.str());
  REQUIRE(errors.size() == 1);
  CHECK_THAT(errors[0].message, Catch::Contains(std::string(corsa::kClipBytes, 'z') + "..."));
  CHECK(errors[0].message.size() < 400);
}

TEST_CASE("the load reports at most 500 errors", "[xosc][errors]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  for (int i = 0; i < 2000; ++i) text.entities += "<Junk/>\n";
  const auto errors = errors_of(dir, text.str());
  REQUIRE(errors.size() == 501);
  CHECK_THAT(errors.back().message, Catch::StartsWith("too many errors"));
}

TEST_CASE("LightState values out of their ranges are located errors, all in one pass",
          "[xosc][errors][lights]") {
  corsa::test::TempDir dir;
  auto light_event = [](const std::string& name, const std::string& transition,
                        const std::string& state) {
    return "<Event name=\"" + name + "\" priority=\"parallel\">\n<Action name=\"" + name +
           "\"><PrivateAction><AppearanceAction><LightStateAction" + transition +
           "><LightType><VehicleLight vehicleLightType=\"lowBeam\"/></LightType>\n" + state +
           "</LightStateAction></AppearanceAction></PrivateAction></Action>\n</Event>\n";
  };
  ScenarioText text;
  text.stories = corsa::test::story_with(
      light_event("Dim", " transitionTime=\"-1\"",
                  "<LightState mode=\"on\" luminousIntensity=\"-5\"/>\n") +
      light_event("Rgb", "",
                  "<LightState mode=\"on\"><Color colorType=\"other\">\n"
                  "<ColorRgb red=\"1.5\" green=\"0.5\" blue=\"-0.1\"/></Color></LightState>\n") +
      light_event("Cmyk", "",
                  "<LightState mode=\"on\"><Color colorType=\"other\">\n"
                  "<ColorCmyk cyan=\"0\" magenta=\"2\" yellow=\"0\" key=\"0\"/></Color>"
                  "</LightState>\n") +
      light_event("Fine", " transitionTime=\"0.5\"",
                  "<LightState mode=\"on\" luminousIntensity=\"0\"><Color colorType=\"red\">\n"
                  "<ColorRgb red=\"1\" green=\"0\" blue=\"0\"/></Color></LightState>\n"));
  const std::string xml = text.str();
  const auto errors = errors_of(dir, xml);
  INFO(describe(errors));
  CHECK(errors.size() == 5);
  CHECK(
      has(errors, line_of(xml, "transitionTime=\"-1\""), "transitionTime -1 must not be negative"));
  CHECK(has(errors, line_of(xml, "luminousIntensity=\"-5\""),
            "luminousIntensity -5 must not be negative"));
  CHECK(has(errors, line_of(xml, "red=\"1.5\""), "red 1.5 is outside [0, 1]"));
  CHECK(has(errors, line_of(xml, "red=\"1.5\""), "blue -0.1 is outside [0, 1]"));
  CHECK(has(errors, line_of(xml, "magenta=\"2\""), "magenta 2 is outside [0, 1]"));
}

TEST_CASE("a DOCTYPE's internal entity is expanded and the errors after it are all reported",
          "[xosc][errors]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.variables =
      "<VariableDeclaration name=\"Flag\" variableType=\"boolean\" value=\"maybe\"/>\n"
      "<VariableDeclaration name=\"Count\" variableType=\"unsignedInt\" value=\"-3\"/>\n";
  text.parameters =
      "<ParameterDeclaration name=\"Label\" parameterType=\"string\" value=\"car &tag;\"/>\n";
  std::string xml = text.str();
  const std::string root = "<OpenSCENARIO>";
  xml.insert(xml.find(root), "<!DOCTYPE OpenSCENARIO [ <!ENTITY tag \"one\" > ]>\n");
  const auto errors = errors_of(dir, xml);
  INFO(describe(errors));
  CHECK(has(errors, line_of(xml, "name=\"Flag\""), "'maybe' is not a valid boolean"));
  CHECK(has(errors, line_of(xml, "name=\"Count\""), "'-3' is not a valid unsignedInt"));
  CHECK(errors.size() == 2);

  // The entity's value is read where it is used: here the name of the entity Init refers to.
  std::string named = ScenarioText{}.str();
  const size_t ego = named.find("<ScenarioObject name=\"Ego\"");
  REQUIRE(ego != std::string::npos);
  named.replace(named.find("\"Ego\"", ego), 5, "\"&who;\"");
  named.insert(named.find(root), "<!DOCTYPE OpenSCENARIO [<!ENTITY who 'Ego'>]>");
  corsa::test::write_text(dir.path() / "named.xosc", named);
  corsa::Diagnostics diagnostics;
  const Scenario scenario = load_scenario(dir.path() / "named.xosc", {}, diagnostics);
  CHECK(scenario.entities.find_object("Ego") != nullptr);
}

TEST_CASE("text in an element that holds only elements is an error at the text's line",
          "[xosc][errors]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.catalogs = "<VehicleCatalog>\n  StrayWords\n  <Directory path=\".\"/>\n</VehicleCatalog>\n";
  text.init =
      "<Private entityRef=\"Ego\">\n"
      "<PrivateAction><TeleportAction><Position>"
      "<WorldPosition x=\"left\" y=\"0\" h=\"0\"/></Position></TeleportAction></PrivateAction>\n"
      "</Private>\n";
  const std::string xml = text.str();
  const auto errors = errors_of(dir, xml);
  INFO(describe(errors));
  CHECK(has(errors, line_of(xml, "StrayWords"),
            "text 'StrayWords' in <VehicleCatalog>, which holds only elements"));
  CHECK(has(errors, line_of(xml, "x=\"left\""), "'left' is not a number"));
  CHECK(errors.size() == 2);
}

TEST_CASE(
    "an element of a choice with two children is an error at that element, and the "
    "second child's errors are reported",
    "[xosc][errors]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.variables = "<VariableDeclaration name=\"Count\" variableType=\"int\" value=\"3\"/>\n";
  text.stories = corsa::test::story_with(
      "<Event name=\"E\" priority=\"override\">\n"
      "<Action name=\"Both\">\n"
      "<GlobalAction><VariableAction variableRef=\"Count\"><SetAction value=\"4\"/>"
      "</VariableAction></GlobalAction>\n"
      "<PrivateAction><LongitudinalAction><SpeedAction>"
      "<SpeedActionDynamics dynamicsShape=\"step\" dynamicsDimension=\"time\" value=\"0\"/>"
      "<SpeedActionTarget><AbsoluteTargetSpeed value=\"fast\"/></SpeedActionTarget>"
      "</SpeedAction></LongitudinalAction></PrivateAction>\n"
      "</Action>\n</Event>\n");
  const std::string xml = text.str();
  const auto errors = errors_of(dir, xml);
  INFO(describe(errors));
  CHECK(has(errors, line_of(xml, "<Action name=\"Both\""),
            "<Action> takes one child, found <GlobalAction> (line " +
                std::to_string(line_of(xml, "<GlobalAction>")) + ") and <PrivateAction> (line " +
                std::to_string(line_of(xml, "<PrivateAction><Longitudinal")) + ")"));
  CHECK(has(errors, line_of(xml, "value=\"fast\""), "'fast' is not a number"));
  CHECK(errors.size() == 2);
}

TEST_CASE("children beyond what their parent allows are read for the errors inside them",
          "[xosc][errors]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.init =
      "<Private entityRef=\"Ego\">\n"
      // Two Positions where one is allowed: the second is read as a Position.
      "<PrivateAction><TeleportAction>\n"
      "<Position><WorldPosition x=\"0\" y=\"0\" h=\"0\"/></Position>\n"
      "<Position><WorldPosition x=\"east\" y=\"0\" h=\"0\"/></Position>\n"
      "</TeleportAction></PrivateAction>\n"
      // A PrivateAction holding two actions: the second's kind is read generically (its
      // elements against the schema, its attributes resolved).
      "<PrivateAction>\n"
      "<LongitudinalAction><SpeedAction>"
      "<SpeedActionDynamics dynamicsShape=\"step\" dynamicsDimension=\"time\" value=\"0\"/>"
      "<SpeedActionTarget><AbsoluteTargetSpeed value=\"3\"/></SpeedActionTarget>"
      "</SpeedAction></LongitudinalAction>\n"
      "<LateralAction><LaneChangeAction>\n"
      "<LaneChangeActionDynamics dynamicsShape=\"step\" dynamicsDimension=\"time\" "
      "value=\"$Missing\"/>\n"
      "<Bogus/>\n"
      "<LaneChangeTarget><RelativeTargetLane entityRef=\"Ego\" value=\"1\"/></LaneChangeTarget>"
      "</LaneChangeAction></LateralAction>\n"
      "</PrivateAction>\n"
      "</Private>\n";
  const std::string xml = text.str();
  const auto errors = errors_of(dir, xml);
  INFO(describe(errors));
  CHECK(
      has(errors, line_of(xml, "x=\"east\""), "<TeleportAction> may contain only one <Position>"));
  CHECK(has(errors, line_of(xml, "x=\"east\""), "'east' is not a number"));
  CHECK(has(errors, line_of(xml, "<PrivateAction>\n<Longitudinal"),
            "<PrivateAction> takes one child, found <LongitudinalAction> (line " +
                std::to_string(line_of(xml, "<LongitudinalAction>")) +
                ") and <LateralAction> (line " + std::to_string(line_of(xml, "<LateralAction>")) +
                ")"));
  CHECK(has(errors, line_of(xml, "$Missing"), "undefined parameter '$Missing'"));
  CHECK(has(errors, line_of(xml, "<Bogus/>"), "unknown element <Bogus> in <LaneChangeAction>"));
  CHECK(errors.size() == 5);
}

TEST_CASE("each use of a parameter whose declaration is in error is an error at the use",
          "[xosc][errors]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.parameters =
      "<ParameterDeclaration name=\"Speed\" parameterType=\"double\" value=\"fast\"/>\n"
      "<ParameterDeclaration name=\"Flag\" parameterType=\"int\" value=\"false\"/>\n"
      "<ParameterDeclaration name=\"Good\" parameterType=\"double\" value=\"3\"/>\n";
  text.init =
      "<Private entityRef=\"Ego\">\n"
      "<PrivateAction><TeleportAction><Position>\n"
      "<WorldPosition x=\"$Speed\" y=\"$Good\" h=\"0\"/></Position></TeleportAction>"
      "</PrivateAction>\n"
      "<PrivateAction><LongitudinalAction><SpeedAction>\n"
      "<SpeedActionDynamics dynamicsShape=\"step\" dynamicsDimension=\"time\" value=\"0\"/>\n"
      "<SpeedActionTarget><AbsoluteTargetSpeed value=\"${$Speed + $Good}\"/>"
      "</SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction>\n"
      "</Private>\n";
  text.stories = corsa::test::story_with(
      "<Event name=\"E\" priority=\"override\">\n"
      "<Action name=\"A\"><PrivateAction><LongitudinalAction><SpeedAction>\n"
      "<SpeedActionDynamics dynamicsShape=\"step\" dynamicsDimension=\"time\" value=\"0\"/>\n"
      "<SpeedActionTarget><AbsoluteTargetSpeed value=\"$Speed\"/></SpeedActionTarget>"
      "</SpeedAction></LongitudinalAction></PrivateAction></Action>\n"
      "</Event>\n");
  // A boolean attribute given the bad int: one error at the use, not a second about its type.
  const std::string actors = "<Actors selectTriggeringEntities=\"false\">";
  text.stories.replace(text.stories.find(actors), actors.size(),
                       "<Actors selectTriggeringEntities=\"$Flag\">");
  const std::string xml = text.str();
  const auto errors = errors_of(dir, xml);
  INFO(describe(errors));
  const std::string speed_line = std::to_string(line_of(xml, "name=\"Speed\""));
  CHECK(has(errors, line_of(xml, "name=\"Speed\""), "'fast' is not a valid double"));
  CHECK(has(errors, line_of(xml, "name=\"Flag\""), "'false' is not a valid int"));
  CHECK(has(errors, line_of(xml, "x=\"$Speed\""),
            "parameter 'Speed' used here has no valid value: its declaration at line " +
                speed_line + " is in error"));
  CHECK(has(errors, line_of(xml, "value=\"${$Speed + $Good}\""),
            "parameter 'Speed' used here has no valid value: its declaration at line " +
                speed_line + " is in error"));
  CHECK(has(errors, line_of(xml, "value=\"$Speed\""),
            "parameter 'Speed' used here has no valid value: its declaration at line " +
                speed_line + " is in error"));
  CHECK(has(errors, line_of(xml, "$Flag"),
            "parameter 'Flag' used here has no valid value: its declaration at line " +
                std::to_string(line_of(xml, "name=\"Flag\"")) + " is in error"));
  CHECK(errors.size() == 6);
}

TEST_CASE("a use of a parameter given a bad value from outside names where the value came from",
          "[xosc][errors]") {
  corsa::test::TempDir dir;
  // A catalog entry whose parameter the reference assigns a bad value, used in the entry.
  corsa::test::write_text(dir.path() / "Catalogs/Vehicles/v.xosc", R"(<?xml version="1.0"?>
<OpenSCENARIO>
<FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" description="c" author="a"/>
<Catalog name="Vehicles">
<Vehicle name="car" vehicleCategory="car">
<ParameterDeclarations><ParameterDeclaration name="Width" parameterType="double" value="2"/>
</ParameterDeclarations>
<BoundingBox><Center x="1.4" y="0" z="0.9"/>
<Dimensions width="$Width" length="5" height="1.8"/></BoundingBox>
<Performance maxSpeed="69" maxAcceleration="10" maxDeceleration="10"/>
<Axles><FrontAxle maxSteering="0.5" wheelDiameter="0.8" trackWidth="1.7" positionX="3" positionZ="0.4"/>
<RearAxle maxSteering="0" wheelDiameter="0.8" trackWidth="1.7" positionX="0" positionZ="0.4"/></Axles>
</Vehicle>
</Catalog>
</OpenSCENARIO>
)");
  ScenarioText text;
  text.parameters = "<ParameterDeclaration name=\"Speed\" parameterType=\"double\" value=\"3\"/>\n";
  text.catalogs = "<VehicleCatalog><Directory path=\"Catalogs/Vehicles\"/></VehicleCatalog>\n";
  text.entities +=
      "<ScenarioObject name=\"Other\">\n"
      "<CatalogReference catalogName=\"Vehicles\" entryName=\"car\">\n"
      "<ParameterAssignments><ParameterAssignment parameterRef=\"Width\" value=\"wide\"/>"
      "</ParameterAssignments>\n</CatalogReference>\n</ScenarioObject>\n";
  text.init =
      "<Private entityRef=\"Ego\">\n"
      "<PrivateAction><TeleportAction><Position>\n"
      "<WorldPosition x=\"$Speed\" y=\"0\" h=\"0\"/></Position></TeleportAction></PrivateAction>\n"
      "</Private>\n";
  const std::string xml = text.str();
  corsa::test::write_text(dir.path() / "map.xodr", corsa::test::minimal_xodr());
  corsa::test::write_text(dir.path() / "s.xosc", xml);
  LoadOptions options;
  options.parameters = {{"Speed", "quick"}};
  std::vector<corsa::Diagnostic> errors;
  corsa::Diagnostics diagnostics;
  try {
    load_scenario(dir.path() / "s.xosc", options, diagnostics);
  } catch (const corsa::InputError& error) {
    errors = error.diagnostics();
  }
  INFO(describe(errors));
  CHECK(has(errors, 0, "parameter 'Speed': 'quick' is not a valid double"));
  CHECK(has(errors, line_of(xml, "x=\"$Speed\""),
            "parameter 'Speed' used here has no valid value: the value assigned to it by --param "
            "is in error"));
  const int assignment = line_of(xml, "parameterRef=\"Width\"");
  CHECK(has(errors, assignment, "parameter 'Width': 'wide' is not a valid double"));
  const std::string scenario_file = (dir.path() / "s.xosc").string();
  bool at_use = false;
  for (const auto& error : errors) {
    at_use =
        at_use || (error.line == 9 && error.file.find("v.xosc") != std::string::npos &&
                   error.message.find("parameter 'Width' used here has no valid value: the value "
                                      "assigned to it at line " +
                                      std::to_string(assignment) + " of ") != std::string::npos &&
                   error.message.find(scenario_file) != std::string::npos);
  }
  CHECK(at_use);
  CHECK(errors.size() == 4);
}

TEST_CASE("an error in an attribute of a tag written over several lines is at its own line",
          "[xosc][errors][lines]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  // The bad tag opens on a line with a comment holding a tag of the same name and after two
  // other tags; a quoted '>' and an entity come before the bad attribute on its 3rd line. A
  // one-line tag of the same name before it has its own error.
  text.init =
      "<Private entityRef=\"Ego\">\n"
      "<PrivateAction><TeleportAction><Position><WorldPosition x=\"1\" y=\"oops\"/></Position>"
      "</TeleportAction></PrivateAction>\n"
      "<!-- <WorldPosition x=\"0\" h=\"not this\"/> --><PrivateAction><TeleportAction>"
      "<Position><WorldPosition x=\"0\"\n"
      "    y=\"0\" z='a>&amp;b'\n"
      "    h=\"wide\"/></Position></TeleportAction></PrivateAction>\n"
      "</Private>\n";
  const std::string xml = text.str();
  const auto errors = errors_of(dir, xml);
  INFO(describe(errors));
  const int tag_line = line_of(xml, "<!-- <WorldPosition");
  REQUIRE(tag_line > 0);
  CHECK(has(errors, line_of(xml, "y=\"oops\""), "attribute y: 'oops' is not a number"));
  CHECK(has(errors, tag_line + 1, "attribute z: 'a>&b' is not a number"));
  CHECK(has(errors, tag_line + 2, "attribute h: 'wide' is not a number"));
  CHECK(errors.size() == 3);
}

TEST_CASE("a reference to an unknown storyboard element is at the line it is written on",
          "[xosc][errors][lines]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.stories = corsa::test::story_with(corsa::test::speed_event("Go"));
  // The condition's tag runs over three lines; the unknown event is named on the second, and a
  // second condition on one line names another unknown element after a known one.
  text.stop =
      "<ConditionGroup>\n"
      "<Condition name=\"a\" delay=\"0\" conditionEdge=\"none\"><ByValueCondition>"
      "<StoryboardElementStateCondition storyboardElementType=\"event\"\n"
      "    storyboardElementRef=\"Stop\"\n"
      "    state=\"completeState\"/></ByValueCondition></Condition>\n"
      "<Condition name=\"b\" delay=\"0\" conditionEdge=\"none\"><ByValueCondition>"
      "<StoryboardElementStateCondition storyboardElementType=\"event\" "
      "storyboardElementRef=\"Go\" state=\"completeState\"/></ByValueCondition></Condition>"
      "<Condition name=\"c\" delay=\"0\" conditionEdge=\"none\"><ByValueCondition>"
      "<StoryboardElementStateCondition storyboardElementType=\"act\" "
      "storyboardElementRef=\"Gone\" state=\"completeState\"/></ByValueCondition></Condition>\n"
      "</ConditionGroup>\n";
  const std::string xml = text.str();
  const auto errors = errors_of(dir, xml);
  INFO(describe(errors));
  const int tag_line = line_of(xml, "storyboardElementType=\"event\"\n");
  REQUIRE(tag_line > 0);
  CHECK(line_of(xml, "storyboardElementRef=\"Stop\"") == tag_line + 1);
  CHECK(has(errors, tag_line + 1, "unknown event 'Stop' in StoryboardElementStateCondition"));
  CHECK(has(errors, line_of(xml, "storyboardElementRef=\"Gone\""),
            "unknown act 'Gone' in StoryboardElementStateCondition"));
  CHECK(errors.size() == 2);
}

TEST_CASE("an unknown parameter in a later line of a tag is reported at that line",
          "[xosc][errors][lines]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.init =
      "<Private entityRef=\"Ego\">\n"
      "<PrivateAction><TeleportAction><Position><WorldPosition\n"
      "    x=\"0\"\n"
      "    y=\"$Nowhere\"\n"
      "    h=\"0\"/></Position></TeleportAction></PrivateAction>\n"
      "</Private>\n";
  const std::string xml = text.str();
  const auto errors = errors_of(dir, xml);
  INFO(describe(errors));
  REQUIRE(errors.size() == 1);
  CHECK(errors[0].line == line_of(xml, "y=\"$Nowhere\""));
  CHECK(errors[0].message.find("Nowhere") != std::string::npos);
}
