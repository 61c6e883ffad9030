// One test per class of bad input: each asserts the message and the file:line it points at.

#include <catch2/catch.hpp>
#include <string>

#include "corsa/xosc/scenario.h"
#include "scenario_text.h"
#include "temp_dir.h"

using namespace corsa::xosc;
using corsa::test::line_of;
using corsa::test::ScenarioText;

namespace {

/// Writes the scenario (and a map next to it), loads it, and returns the error it raised.
corsa::Diagnostic load_error(const corsa::test::TempDir& dir, const std::string& xml,
                             const LoadOptions& options = {}) {
  corsa::test::write_text(dir.path() / "map.xodr", corsa::test::minimal_xodr());
  corsa::test::write_text(dir.path() / "s.xosc", xml);
  corsa::Diagnostics diagnostics;
  try {
    load_scenario(dir.path() / "s.xosc", options, diagnostics);
  } catch (const corsa::InputError& error) {
    return error.diagnostic();
  }
  FAIL("the scenario loaded without error");
  return {};
}

const char* kVehicleCatalog = R"(<?xml version="1.0"?>
<OpenSCENARIO>
<FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" description="c" author="a"/>
<Catalog name="VehicleCatalog">
<Vehicle name="small" vehicleCategory="car">
<ParameterDeclarations><ParameterDeclaration name="Length" parameterType="double" value="4"/></ParameterDeclarations>
<BoundingBox><Center x="1" y="0" z="0.8"/><Dimensions width="1.8" length="$Length" height="1.5"/></BoundingBox>
<Performance maxSpeed="50" maxAcceleration="5" maxDeceleration="8"/>
<Axles><RearAxle maxSteering="0" wheelDiameter="0.6" trackWidth="1.5" positionX="0" positionZ="0.3"/></Axles>
</Vehicle>
</Catalog>
</OpenSCENARIO>
)";

std::string catalog_entity(const std::string& entry, const std::string& assignments = "") {
  return "<ScenarioObject name=\"Ego\">\n<CatalogReference catalogName=\"VehicleCatalog\" "
         "entryName=\"" +
         entry + "\">" + assignments + "</CatalogReference>\n</ScenarioObject>\n";
}

}  // namespace

TEST_CASE("malformed XML names the tag and the lines it was opened and closed at",
          "[xosc][errors]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.entities += "<ScenarioObject name=\"X\">\n<Vehicle>\n</ScenarioObject>\n";
  const std::string xml = text.str();
  const auto error = load_error(dir, xml);
  const int opened = line_of(xml, "<Vehicle>\n</ScenarioObject>");
  CHECK(error.message == "malformed XML: <Vehicle> opened at line " + std::to_string(opened) +
                             " is closed by </ScenarioObject> at line " +
                             std::to_string(opened + 1));
  CHECK(error.line == opened + 1);
  CHECK(error.file == (dir.path() / "s.xosc").string());
}

TEST_CASE("an unknown element is an error naming it and its parent", "[xosc][errors]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.entities += "<Spaceship name=\"X\"/>\n";
  const std::string xml = text.str();
  const auto error = load_error(dir, xml);
  CHECK_THAT(error.message, Catch::StartsWith("unknown element <Spaceship> in <Entities>"));
  CHECK(error.line == line_of(xml, "<Spaceship"));
  CHECK(error.format().find("[in OpenSCENARIO/Entities/Spaceship]") != std::string::npos);
}

TEST_CASE("a value of the wrong type is an error at its element", "[xosc][errors]") {
  corsa::test::TempDir dir;
  SECTION("an attribute") {
    ScenarioText text;
    text.init =
        "<Private entityRef=\"Ego\"><PrivateAction><TeleportAction><Position>\n"
        "<WorldPosition x=\"fast\" y=\"0\"/>\n"
        "</Position></TeleportAction></PrivateAction></Private>\n";
    const std::string xml = text.str();
    const auto error = load_error(dir, xml);
    CHECK(error.message == "attribute x: 'fast' is not a number");
    CHECK(error.line == line_of(xml, "<WorldPosition"));
  }
  SECTION("a parameter declaration") {
    ScenarioText text;
    text.parameters =
        "<ParameterDeclaration name=\"Count\" parameterType=\"unsignedShort\" "
        "value=\"70000\"/>\n";
    const std::string xml = text.str();
    const auto error = load_error(dir, xml);
    CHECK(error.message == "parameter 'Count': '70000' is not a valid unsignedShort");
    CHECK(error.line == line_of(xml, "name=\"Count\""));
  }
  SECTION("an enumeration") {
    ScenarioText text;
    text.stories = corsa::test::story_with(
        "<Event name=\"E\" priority=\"sometimes\">\n<Action name=\"A\"><PrivateAction>"
        "<TeleportAction><Position><WorldPosition x=\"0\" y=\"0\"/></Position></TeleportAction>"
        "</PrivateAction></Action>\n</Event>\n");
    const std::string xml = text.str();
    const auto error = load_error(dir, xml);
    CHECK(error.message == "attribute priority: 'sometimes' is not a valid Priority");
    CHECK(error.line == line_of(xml, "priority=\"sometimes\""));
  }
}

TEST_CASE("lane numbers beyond any road are an error at their element", "[xosc][errors]") {
  // A lane section holds at most 128 lanes; dLane = INT_MIN would overflow the engine's lane
  // arithmetic (negated, or added to a lane id).
  corsa::test::TempDir dir;
  SECTION("a RelativeLanePosition's dLane") {
    ScenarioText text;
    text.init +=
        "<Private entityRef=\"Ego\"><PrivateAction><TeleportAction><Position>\n"
        "<RelativeLanePosition entityRef=\"Ego\" dLane=\"-2147483648\" ds=\"0\"/>\n"
        "</Position></TeleportAction></PrivateAction></Private>\n";
    const std::string xml = text.str();
    const auto error = load_error(dir, xml);
    CHECK(error.message ==
          "attribute dLane: -2147483648 is beyond physical sense (|value| <= 1000 lanes)");
    CHECK(error.line == line_of(xml, "<RelativeLanePosition"));
  }
  SECTION("a RelativeTargetLane's value, given by a parameter") {
    ScenarioText text;
    text.parameters =
        "<ParameterDeclaration name=\"Lanes\" parameterType=\"int\" value=\"1001\"/>\n";
    text.stories = corsa::test::story_with(
        "<Event name=\"E\" priority=\"override\">\n<Action name=\"A\"><PrivateAction>"
        "<LateralAction><LaneChangeAction><LaneChangeActionDynamics dynamicsShape=\"step\" "
        "value=\"0\" dynamicsDimension=\"time\"/><LaneChangeTarget>\n"
        "<RelativeTargetLane entityRef=\"Ego\" value=\"$Lanes\"/>\n"
        "</LaneChangeTarget></LaneChangeAction></LateralAction></PrivateAction></Action>\n"
        "</Event>\n");
    const std::string xml = text.str();
    const auto error = load_error(dir, xml);
    CHECK(error.message ==
          "attribute value: 1001 is beyond physical sense (|value| <= 1000 lanes)");
    CHECK(error.line == line_of(xml, "<RelativeTargetLane"));
  }
}

TEST_CASE("an undefined parameter is an error at the attribute's element", "[xosc][errors]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.init =
      "<Private entityRef=\"Ego\"><PrivateAction><TeleportAction><Position>\n"
      "<WorldPosition x=\"$Nowhere\" y=\"0\"/>\n"
      "</Position></TeleportAction></PrivateAction></Private>\n";
  const std::string xml = text.str();
  const auto error = load_error(dir, xml);
  CHECK(error.message == "undefined parameter '$Nowhere'");
  CHECK(error.line == line_of(xml, "$Nowhere"));
}

TEST_CASE("a bad expression is an error with the reason and column", "[xosc][errors]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.parameters = "<ParameterDeclaration name=\"Gap\" parameterType=\"double\" value=\"0\"/>\n";
  text.init =
      "<Private entityRef=\"Ego\"><PrivateAction><TeleportAction><Position>\n"
      "<WorldPosition x=\"${10 / $Gap}\" y=\"0\"/>\n"
      "</Position></TeleportAction></PrivateAction></Private>\n";
  const std::string xml = text.str();
  const auto error = load_error(dir, xml);
  CHECK(error.message == "bad expression '${10 / $Gap}': division by zero (column 6)");
  CHECK(error.line == line_of(xml, "${10"));
}

TEST_CASE("a missing catalog entry names both the catalog and the entry", "[xosc][errors]") {
  corsa::test::TempDir dir;
  corsa::test::write_text(dir.path() / "Catalogs/Vehicles/VehicleCatalog.xosc", kVehicleCatalog);
  ScenarioText text;
  text.catalogs = "<VehicleCatalog><Directory path=\"Catalogs/Vehicles\"/></VehicleCatalog>\n";
  SECTION("unknown entry") {
    text.entities = catalog_entity("huge");
    const std::string xml = text.str();
    const auto error = load_error(dir, xml);
    CHECK_THAT(error.message, Catch::StartsWith("catalog 'VehicleCatalog' ("));
    CHECK_THAT(error.message, Catch::EndsWith("VehicleCatalog.xosc) has no entry 'huge'"));
    CHECK(error.line == line_of(xml, "<CatalogReference"));
  }
  SECTION("unknown catalog") {
    text.entities =
        "<ScenarioObject name=\"Ego\">\n<CatalogReference catalogName=\"Trucks\" "
        "entryName=\"big\"/>\n</ScenarioObject>\n";
    const std::string xml = text.str();
    const auto error = load_error(dir, xml);
    CHECK(error.message ==
          "catalog 'Trucks' (for entry 'big') is not in any catalog directory of "
          "<CatalogLocations>");
    CHECK(error.line == line_of(xml, "<CatalogReference"));
  }
  SECTION("an assignment to a parameter the entry does not declare") {
    text.entities =
        catalog_entity("small",
                       "\n<ParameterAssignments><ParameterAssignment parameterRef=\"Width\" "
                       "value=\"3\"/></ParameterAssignments>\n");
    const std::string xml = text.str();
    const auto error = load_error(dir, xml);
    CHECK(error.message == "vehicle declares no parameter 'Width'");
    CHECK(error.line == line_of(xml, "<ParameterAssignment "));
  }
}

TEST_CASE("an unknown element directly in a catalog a scenario uses is an error at its line",
          "[xosc][errors]") {
  // 1.3 Catalog is a sequence of Vehicle, Controller, Pedestrian, MiscObject, Environment,
  // Maneuver, Trajectory and Route: a misspelt entry is outside the schema, reported in the
  // catalog file as any unknown element is, although the scenario uses another entry.
  corsa::test::TempDir dir;
  std::string catalog = kVehicleCatalog;
  const std::string misspelt = "<Vehicel name=\"big\" vehicleCategory=\"truck\"/>\n";
  catalog.insert(catalog.find("</Catalog>"), misspelt);
  corsa::test::write_text(dir.path() / "Catalogs/Vehicles/VehicleCatalog.xosc", catalog);
  ScenarioText text;
  text.catalogs = "<VehicleCatalog><Directory path=\"Catalogs/Vehicles\"/></VehicleCatalog>\n";
  text.entities = catalog_entity("small");
  const auto error = load_error(dir, text.str());
  CHECK_THAT(error.message, Catch::StartsWith("unknown element <Vehicel> in <Catalog> (expected "
                                              "Vehicle, Controller, "));
  CHECK(error.file == (dir.path() / "Catalogs/Vehicles/VehicleCatalog.xosc").string());
  CHECK(error.line == line_of(catalog, "<Vehicel"));
}

TEST_CASE("an unresolved entity reference is an error at the reference", "[xosc][errors]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.init +=
      "<Private entityRef=\"Ghost\"><PrivateAction><TeleportAction><Position>"
      "<WorldPosition x=\"0\" y=\"0\"/></Position></TeleportAction></PrivateAction>"
      "</Private>\n";
  const std::string xml = text.str();
  const auto error = load_error(dir, xml);
  CHECK(error.message == "entityRef: unknown entity 'Ghost'");
  CHECK(error.line == line_of(xml, "entityRef=\"Ghost\""));
}

TEST_CASE("cyclic parameter use is an error naming the cycle", "[xosc][errors]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.parameters =
      "<ParameterDeclaration name=\"A\" parameterType=\"double\" value=\"${$B + 1}\"/>\n"
      "<ParameterDeclaration name=\"B\" parameterType=\"double\" value=\"$C\"/>\n"
      "<ParameterDeclaration name=\"C\" parameterType=\"double\" value=\"$A\"/>\n";
  const std::string xml = text.str();
  const auto error = load_error(dir, xml);
  CHECK(error.message == "cyclic parameter use: A -> B -> C -> A");
  CHECK(error.line == line_of(xml, "name=\"A\""));
}

TEST_CASE("a missing map file is an error at the LogicFile", "[xosc][errors]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.road = "<LogicFile filepath=\"maps/gone.xodr\"/>";
  const std::string xml = text.str();
  const auto error = load_error(dir, xml);
  CHECK_THAT(error.message, Catch::StartsWith("map file 'maps/gone.xodr' not found (looked for "));
  CHECK_THAT(error.message, Catch::Contains((dir.path() / "maps/gone.xodr").string()));
  CHECK(error.line == line_of(xml, "<LogicFile"));
}

TEST_CASE("storyboard references must name exactly one element", "[xosc][errors]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  SECTION("unknown") {
    text.stories = corsa::test::story_with(corsa::test::speed_event("Go"));
    text.stop = corsa::test::state_condition("event", "Stop");
    const std::string xml = text.str();
    const auto error = load_error(dir, xml);
    CHECK(error.message == "unknown event 'Stop' in StoryboardElementStateCondition");
    CHECK(error.line == line_of(xml, "storyboardElementRef=\"Stop\""));
  }
  SECTION("ambiguous, then qualified") {
    text.stories = corsa::test::story_with(corsa::test::speed_event("Go"), "S1") +
                   corsa::test::story_with(corsa::test::speed_event("Go"), "S2");
    text.stop = corsa::test::state_condition("event", "Go");
    const std::string xml = text.str();
    const auto error = load_error(dir, xml);
    const std::string file = (dir.path() / "s.xosc").string();
    const size_t second_story = xml.find("<Story name=\"S2\"");
    CHECK(error.message ==
          "ambiguous event reference 'Go' (matches S1::A::G::M::Go (" + file + ":" +
              std::to_string(line_of(xml, "<Event name=\"Go\"")) + ") and S2::A::G::M::Go (" +
              file + ":" +
              std::to_string(line_of(xml.substr(second_story), "<Event name=\"Go\"") +
                             line_of(xml, "<Story name=\"S2\"") - 1) +
              ")); qualify it with '::'");
    text.stop = corsa::test::state_condition("event", "S2::A::G::M::Go");
    corsa::test::write_text(dir.path() / "s.xosc", text.str());
    corsa::Diagnostics diagnostics;
    const Scenario scenario = load_scenario(dir.path() / "s.xosc", {}, diagnostics);
    const auto& condition = std::get<StoryboardElementStateCondition>(
        std::get<ByValueCondition>(scenario.storyboard.stop_trigger->groups[0].conditions[0].kind));
    CHECK(condition.resolved_path == "S2::A::G::M::Go");
  }
}

TEST_CASE("names the standard requires to be unique are checked", "[xosc][errors]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  SECTION("entities") {
    const std::string twin = text.entities;
    text.entities += twin;
    const std::string xml = text.str();
    const auto error = load_error(dir, xml);
    CHECK(error.message == "entity name 'Ego' is used twice");
    const size_t second = xml.find("<ScenarioObject", xml.find("<ScenarioObject") + 1);
    CHECK(error.line == line_of(xml.substr(0, second) + "@", "@"));
  }
  // Repeated sibling storyboard names and repeated parameter declarations occur in published
  // files: they are read leniently (see the lenient-reading tests), and are errors under strict.
  LoadOptions strict;
  strict.strict = true;
  SECTION("sibling events") {
    text.stories =
        corsa::test::story_with(corsa::test::speed_event("Go") + corsa::test::speed_event("Go"));
    const auto error = load_error(dir, text.str(), strict);
    CHECK_THAT(error.message, Catch::StartsWith("event name 'Go' is used twice in <Maneuver>"));
  }
  SECTION("parameters") {
    text.parameters =
        "<ParameterDeclaration name=\"P\" parameterType=\"int\" value=\"1\"/>\n"
        "<ParameterDeclaration name=\"P\" parameterType=\"int\" value=\"2\"/>\n";
    const std::string xml = text.str();
    const auto error = load_error(dir, xml, strict);
    CHECK_THAT(error.message, Catch::StartsWith("parameter 'P' is declared twice (first at line " +
                                                std::to_string(line_of(xml, "name=\"P\"")) + ")"));
  }
}

TEST_CASE("required attributes and children are checked", "[xosc][errors]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  SECTION("attribute") {
    text.init =
        "<Private entityRef=\"Ego\"><PrivateAction><TeleportAction><Position>\n"
        "<WorldPosition y=\"0\"/>\n"
        "</Position></TeleportAction></PrivateAction></Private>\n";
    const std::string xml = text.str();
    const auto error = load_error(dir, xml);
    CHECK(error.message == "<WorldPosition> needs the attribute x");
    CHECK(error.line == line_of(xml, "<WorldPosition"));
  }
  SECTION("choice") {
    text.init =
        "<Private entityRef=\"Ego\"><PrivateAction><TeleportAction>\n<Position/>\n"
        "</TeleportAction></PrivateAction></Private>\n";
    const std::string xml = text.str();
    const auto error = load_error(dir, xml);
    CHECK_THAT(error.message, Catch::StartsWith("<Position> needs one of: WorldPosition, "));
    CHECK(error.line == line_of(xml, "<Position/>"));
  }
}

TEST_CASE("outside parameter values are type-checked and must be declared", "[xosc][errors]") {
  corsa::test::TempDir dir;
  ScenarioText text;
  text.parameters =
      "<ParameterDeclaration name=\"Speed\" parameterType=\"double\" value=\"3\">\n"
      "<ConstraintGroup><ValueConstraint rule=\"lessOrEqual\" value=\"50\"/>"
      "</ConstraintGroup>\n</ParameterDeclaration>\n";
  const std::string xml = text.str();
  LoadOptions options;
  SECTION("wrong type") {
    options.parameters = {{"Speed", "quick"}};
    const auto error = load_error(dir, xml, options);
    CHECK(error.format() == "--param: error: parameter 'Speed': 'quick' is not a valid double");
  }
  SECTION("not declared") {
    options.parameters = {{"Sped", "3"}};
    const auto error = load_error(dir, xml, options);
    CHECK(error.message == "the scenario declares no parameter 'Sped'");
  }
  SECTION("violating its constraints") {
    options.parameters = {{"Speed", "80"}};
    const auto error = load_error(dir, xml, options);
    CHECK(error.message == "parameter 'Speed' = '80' violates its value constraints");
  }
}

TEST_CASE("a catalog entry that references itself is an error, not a hang", "[xosc][errors]") {
  corsa::test::TempDir dir;
  corsa::test::write_text(dir.path() / "Catalogs/Routes/r.xosc", R"(<?xml version="1.0"?>
<OpenSCENARIO>
<FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" description="c" author="a"/>
<Catalog name="Routes">
<Route name="loop" closed="false">
<Waypoint routeStrategy="shortest"><Position><RoutePosition><RouteRef>
<CatalogReference catalogName="Routes" entryName="loop"/>
</RouteRef><InRoutePosition><FromRoadCoordinates pathS="0" t="0"/></InRoutePosition></RoutePosition></Position></Waypoint>
<Waypoint routeStrategy="shortest"><Position><WorldPosition x="0" y="0"/></Position></Waypoint>
</Route>
</Catalog>
</OpenSCENARIO>
)");
  ScenarioText text;
  text.catalogs = "<RouteCatalog><Directory path=\"Catalogs/Routes\"/></RouteCatalog>\n";
  text.init =
      "<Private entityRef=\"Ego\"><PrivateAction><RoutingAction><AssignRouteAction>\n"
      "<CatalogReference catalogName=\"Routes\" entryName=\"loop\"/>\n"
      "</AssignRouteAction></RoutingAction></PrivateAction></Private>\n";
  const auto error = load_error(dir, text.str());
  CHECK(error.message == "catalog entry 'loop' of catalog 'Routes' references itself");
  CHECK(error.file == (dir.path() / "Catalogs/Routes/r.xosc").lexically_normal().string());
  CHECK(error.line == 7);
}

TEST_CASE("catalog entries that fan out exponentially stop with an error, not a hang",
          "[xosc][errors]") {
  corsa::test::TempDir dir;
  // Route rK has two waypoints on route r(K+1): expanding r0 would need 2^24 expansions.
  std::string catalog =
      "<?xml version=\"1.0\"?>\n<OpenSCENARIO>\n<FileHeader revMajor=\"1\" "
      "revMinor=\"3\" date=\"2024-01-01T00:00:00\" description=\"c\" "
      "author=\"a\"/>\n<Catalog name=\"Routes\">\n";
  const std::string leaf = "<Position><WorldPosition x=\"0\" y=\"0\"/></Position>";
  for (int k = 0; k <= 24; ++k) {
    const std::string position =
        k == 24 ? leaf
                : "<Position><RoutePosition><RouteRef><CatalogReference catalogName=\"Routes\" "
                  "entryName=\"r" +
                      std::to_string(k + 1) +
                      "\"/></RouteRef><InRoutePosition><FromRoadCoordinates pathS=\"0\" "
                      "t=\"0\"/></InRoutePosition></RoutePosition></Position>";
    catalog += "<Route name=\"r" + std::to_string(k) + "\" closed=\"false\">";
    for (int w = 0; w < 2; ++w) {
      catalog += "<Waypoint routeStrategy=\"shortest\">" + position + "</Waypoint>";
    }
    catalog += "</Route>\n";
  }
  catalog += "</Catalog>\n</OpenSCENARIO>\n";
  corsa::test::write_text(dir.path() / "Catalogs/Routes/r.xosc", catalog);
  ScenarioText text;
  text.catalogs = "<RouteCatalog><Directory path=\"Catalogs/Routes\"/></RouteCatalog>\n";
  text.init =
      "<Private entityRef=\"Ego\"><PrivateAction><RoutingAction><AssignRouteAction>\n"
      "<CatalogReference catalogName=\"Routes\" entryName=\"r0\"/>\n"
      "</AssignRouteAction></RoutingAction></PrivateAction></Private>\n";
  const auto error = load_error(dir, text.str());
  CHECK_THAT(error.message, Catch::StartsWith("more than 10000 catalog references expanded"));
}
